// verbs::allocate in-process (docs/model.md §10.3): the targets read in the coefficients' display units, the
// allocation equal to that of the same targets given in SI units, the allocated tolerances'
// expanded uncertainties equal to verbs::budget of a configuration carrying them, the mode taken from the
// configuration, and the options' errors naming the option.
#include "ccal/uncertainty/allocate.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/verbs/allocate.hpp"
#include "ccal/verbs/budget.hpp"
#include "test_constants.hpp"
#include "verbs_support.hpp"

namespace ccal::test {
namespace {

using ccal::test::kDeg;

AllocateOptions k2_k3_targets() {
  AllocateOptions o;
  o.targets = {"K2=1e-7", "K3=1e-6 deg/s/g^3"};  // deg/s/g² is K2's display unit
  o.verify_trials = 0;
  return o;
}

TEST(AllocateVerb, TargetsInDisplayUnitsGiveTheLibrarysAllocation) {
  const Config config = load_config(kPaperConfigPath);
  const verbs::AllocateResult r = verbs::allocate(config, k2_k3_targets());
  // The same targets in SI, with their units: the same allocation (to 1e-9 of each scale: the targets agree
  // to a few ulp after the unit conversions, and the solver's scales follow them to its 1e-12 tolerance).
  AllocateOptions si;
  si.verify_trials = 0;
  si.targets = {fmt::format("K2={:.17g} rad/s/g^2", 1e-7 * kDeg), fmt::format("K3={:.17g} rad/s/g^3", 1e-6 * kDeg)};
  const AllocationDetail direct = allocate_tolerances(config, si);
  ASSERT_EQ(r.allocation.sources.size(), direct.sources.size());
  for (std::size_t s = 0; s < direct.sources.size(); ++s) {
    EXPECT_EQ(r.allocation.sources[s].id, direct.sources[s].id);
    EXPECT_NEAR(r.allocation.sources[s].scale, direct.sources[s].scale, 1e-9 * direct.sources[s].scale)
        << direct.sources[s].id;
  }
  ASSERT_EQ(r.allocation.targets.size(), 2u);
  const AllocatedCoefficient& k2 = r.allocation.coefficients[r.allocation.targets[0]];
  EXPECT_EQ(k2.id, "K2");
  EXPECT_NEAR(k2.target, 1e-7 * kDeg, 1e-15 * 1e-7 * kDeg);
  EXPECT_EQ(r.allocation.mode, config.mode);
}

TEST(AllocateVerb, AllocatedTolerancesBudgetToTheReportedUncertainties) {
  // The configuration with every bound scaled by its λ, budgeted by verbs::budget with the allocation's
  // coverage factor: its U per coefficient is the allocation's allocated U (the same LPU: sensitivities at
  // the configured errors times the scaled σ), to 1e-9 relative (sums of 52 squares in another order);
  // every target holds and an active one with equality (1e-6: the solver's tolerance on the constraint).
  const Config config = load_config(kPaperConfigPath);
  const verbs::AllocateResult r = verbs::allocate(config, k2_k3_targets());
  Config allocated = config;
  for (Tolerance& t : allocated.tolerances) {
    const auto s = std::find_if(r.allocation.sources.begin(), r.allocation.sources.end(),
                                [&](const AllocatedSource& a) { return a.id == t.id; });
    ASSERT_NE(s, r.allocation.sources.end()) << t.id;
    t.bound = s->allocated_bound;
  }
  BudgetOptions bo;
  bo.coverage_factor = r.allocation.coverage_factor;
  const verbs::BudgetResult b = verbs::budget(allocated, bo);
  int active = 0;
  for (std::size_t k = 0; k < r.allocation.coefficients.size(); ++k) {
    const AllocatedCoefficient& c = r.allocation.coefficients[k];
    SCOPED_TRACE(c.id);
    ASSERT_EQ(b.budget.coefficients[k], c.id);
    const double U = b.budget.expanded_uncertainty[Eigen::Index(k)];
    EXPECT_NEAR(c.allocated_expanded, U, 1e-9 * U);
    if (c.has_target) {
      EXPECT_LE(U, c.target * (1 + 1e-9));
      if (c.active) {
        ++active;
        EXPECT_NEAR(U, c.target, 1e-6 * c.target);
      }
    }
  }
  EXPECT_GE(active, 1);
}

TEST(AllocateVerb, TheModeIsTheConfigurationsUnlessGiven) {
  Config config = load_config(kPaperConfigPath);
  config.mode = ModelMode::paper;
  EXPECT_EQ(verbs::allocate(config, k2_k3_targets()).allocation.mode, ModelMode::paper);
  AllocateOptions exact = k2_k3_targets();
  exact.mode = ModelMode::exact;
  EXPECT_EQ(verbs::allocate(config, exact).allocation.mode, ModelMode::exact);
}

TEST(AllocateVerb, BadOptionsNameTheOption) {
  const Config config = load_config(kPaperConfigPath);
  auto message = [&](const AllocateOptions& o) -> std::string {
    try {
      verbs::allocate(config, o);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  AllocateOptions p = k2_k3_targets(), scale = k2_k3_targets(), trials = k2_k3_targets(),
                         target = k2_k3_targets(), unit = k2_k3_targets();
  p.coverage_probability = 0;
  scale.max_scale = -1;
  trials.verify_trials = 1;
  target.targets = {"K1=1e-7"};  // K1 is held, not free
  unit.targets = {"K2=1e-7 m"};  // not the dimension of K2
  // The library names the field (an OptionError); each front end words it with its own name of the option.
  EXPECT_EQ(message(p).rfind("coverage_probability: ", 0), 0u) << message(p);
  EXPECT_EQ(message(scale).rfind("max_scale: ", 0), 0u) << message(scale);
  EXPECT_EQ(message(trials).rfind("verify_trials: ", 0), 0u) << message(trials);
  EXPECT_NE(message(target).find("targets: "), std::string::npos) << message(target);
  EXPECT_NE(message(unit).find("targets: "), std::string::npos) << message(unit);
  Config empty = config;
  empty.tolerances.clear();
  EXPECT_THROW(verbs::allocate(empty, k2_k3_targets()), InputError);
}

}  // namespace
}  // namespace ccal::test
