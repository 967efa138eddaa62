// The design's mechanism (src/verbs/design_mechanism.hpp): the U from the tolerances alone against its closed
// form, the heading imbalance against closed forms of a few plans, and the words against plans whose answer
// is known (a plan against itself changes nothing; opposite headings in pairs are named).
#include "../src/verbs/design_mechanism.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/verbs/budget.hpp"
#include "test_constants.hpp"

namespace ccal::verbs {
namespace {

using ccal::test::kPi;

Config bundled() { return parse_config(bundled_example_text(), "mechanism_test.toml"); }

// Six runs: two at each of 5, 15 and 30 g, each run's heading ψ_IA = θ1(0) + φ0 given.
Config with_headings(const double (&headings)[6]) {
  Config c = bundled();
  const double levels[] = {5, 5, 15, 15, 30, 30};
  for (std::size_t j = 0; j < 6; ++j) {
    ccal::Run& run = c.plan.runs[j];
    run.g_level = levels[j];
    run.terminal_phase.reset();
    run.initial_phase = 0.5;
    run.arm_azimuth = headings[j] - 0.5;
  }
  return c;
}

TEST(DesignMechanism, ToleranceUIsTheQuadratureSumOfTheSourcesWhenNoneIsGrouped) {
  // The bundled example groups no source: U_k = k √Σ_s (J_ks u_s)². 1e-12 relative: two summation orders.
  const Config c = bundled();
  for (const Tolerance& t : c.tolerances) ASSERT_TRUE(t.group.empty()) << t.id;
  const BudgetResult b = budget(c);
  const Eigen::VectorXd u = tolerance_expanded(b.budget);
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    double sum = 0;
    for (const SourceBudget& s : b.budget.sources) sum += s.effect[k] * s.effect[k];
    const double want = b.budget.coverage.factor * std::sqrt(sum);
    EXPECT_NEAR(u[k], want, 1e-12 * want) << b.budget.coefficients[k];
  }
}

TEST(DesignMechanism, ToleranceUAddsAGroupsSourcesWithTheirSigns) {
  // Two sources in one group add as signed effects before the quadrature sum: U² changes by 2 k² e_a e_b.
  Config c = bundled();
  c.tolerances[0].group = "pair";
  c.tolerances[1].group = "pair";
  const BudgetResult b = budget(c);
  const Eigen::VectorXd u = tolerance_expanded(b.budget);
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    double sum = 0;
    for (const SourceBudget& s : b.budget.sources) sum += s.effect[k] * s.effect[k];
    sum += 2 * b.budget.sources[0].effect[k] * b.budget.sources[1].effect[k];
    const double want = b.budget.coverage.factor * std::sqrt(sum);
    EXPECT_NEAR(u[k], want, 1e-12 * want) << b.budget.coefficients[k];
  }
}

TEST(DesignMechanism, HeadingImbalanceIsTheWorstLevelsMeanResultant) {
  // |Σ e^{iψ}|/n per g-level, the largest over the levels. 1e-12: sums of a few sines and cosines.
  EXPECT_NEAR(heading_imbalance(with_headings({0, kPi, 1, 1 + kPi, 2, 2 + kPi})), 0, 1e-12);
  EXPECT_NEAR(heading_imbalance(with_headings({0, kPi, 1, 1, 2, 2 + kPi})), 1, 1e-12);
  EXPECT_NEAR(heading_imbalance(with_headings({0, kPi / 2, 1, 1 + kPi, 2, 2 + kPi})), std::sqrt(0.5), 1e-12);
  // The paper plan: one run per g-level, each level's resultant is 1.
  EXPECT_NEAR(heading_imbalance(bundled()), 1, 1e-12);
}

DesignResult result_of(const Config& configured, const Config& designed) {
  DesignResult r;
  r.config = configured;
  r.designed = designed;
  r.before = budget(configured);
  r.after = budget(designed);
  for (const std::string& id : r.before.budget.coefficients) r.targets.push_back({id, 1.0, 1.0, false});
  r.tolerance_before = tolerance_expanded(r.before.budget);
  r.tolerance_after = tolerance_expanded(r.after.budget);
  return r;
}

TEST(DesignMechanism, APlanAgainstItselfChangesNothingInWords) {
  const std::string text = mechanism_text(result_of(bundled(), bundled()));
  for (const char* id : {"K0", "K2", "K3"}) {
    EXPECT_NE(text.find(std::string(id) + ": the inputs' tolerances cost U = "), std::string::npos)
        << text;
    EXPECT_NE(text.find("(x1)."), std::string::npos) << text;
    EXPECT_NE(
        text.find(std::string("The designed runs show the part of ") + id +
                  "'s signal that no other coefficient can imitate about as strongly as the configured ones "
                  "(x1); the change is the errors' effects on " +
                  id + " cancelling between the runs about as before (x1)."),
        std::string::npos)
        << text;
  }
  // Every source is named in words beside its id.
  EXPECT_NE(text.find("main-axis rate ripple (relative to the rate), cos theta1 (ripple1_c1)"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("opposite directions"), std::string::npos) << text;
}

TEST(DesignMechanism, OppositeHeadingsInPairsAreNamed) {
  const std::string text =
      mechanism_text(result_of(bundled(), with_headings({0, kPi, 1, 1 + kPi, 2, 2 + kPi})));
  EXPECT_NE(
      text.find("At each g-level the designed runs point the input axis in opposite directions in pairs "
                "(its heading at the start, arm azimuth + platform phase, is balanced to 0.00; configured "
                "plan 1.00, 1 "
                "when all runs of a level point alike)"),
      std::string::npos)
      << text;
}

}  // namespace
}  // namespace ccal::verbs
