// The budget's parts (src/render/budget_parts.hpp) on budgets of verbs::budget: the shares of a coefficient's
// u² add to 1, partly correlated sources ([[correlations]]) give one more line, their cross terms (negative
// where they cancel), which is absent without them, a fully correlated group is one line named
// "group (members)", the divisor as the tables print it, and CSV column names without spaces or brackets.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>

#include "../src/render/budget_parts.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/verbs/budget.hpp"
#include "verbs_support.hpp"

namespace ccal {
namespace budget_parts_render_test {

using render::budget_parts::Contribution;
using render::budget_parts::contributions;
using render::budget_parts::kCrossTermsLabel;

// The two ripples of K2 at r = -0.5 (their effects nearly cancel) and two azimuth errors at r = 0.6.
const std::string kCorrelatedPairs =
    "\n[[correlations]]\nbetween = [\"ripple1_c1\", \"ripple3_c1\"]\nr = -0.5\n\n[[correlations]]\n"
    "between = [\"dthy4\", \"dthy5\"]\nr = 0.6\n";

double share_sum(const std::vector<Contribution>& all) {
  return std::accumulate(all.begin(), all.end(), 0.0, [](double s, const Contribution& c) { return s + c.share; });
}

const Contribution* labelled(const std::vector<Contribution>& all, std::string_view label) {
  for (const Contribution& c : all)
    if (c.label == label) return &c;
  return nullptr;
}

TEST(BudgetParts, CorrelatedSourcesAddTheirCrossTermsAndTheSharesSumToOne) {
  const verbs::BudgetResult plain = verbs::budget(bundled_example());
  const verbs::BudgetResult correlated =
      verbs::budget(parse_config(std::string(bundled_example_text()) + kCorrelatedPairs, "c.toml"));
  for (std::size_t k = 0; k < plain.budget.coefficients.size(); ++k) {
    const auto none = contributions(plain.budget, k);
    EXPECT_EQ(labelled(none, kCrossTermsLabel), nullptr) << k;
    // Tolerance 1e-12: a sum of about 50 shares of order 1e-2 or less, each rounded once.
    EXPECT_NEAR(share_sum(none), 1.0, 1e-12) << k;
    const auto with = contributions(correlated.budget, k);
    ASSERT_NE(labelled(with, kCrossTermsLabel), nullptr) << k;
    EXPECT_NEAR(share_sum(with), 1.0, 1e-12) << k;
  }
  // K2 (the second coefficient): the ripples' cross term takes back nearly all of what each adds.
  EXPECT_LT(labelled(contributions(correlated.budget, 1), kCrossTermsLabel)->share, -0.9);
  // Sorted largest first: the negative cross term last.
  const auto k2 = contributions(correlated.budget, 1);
  for (std::size_t i = 1; i < k2.size(); ++i) EXPECT_GE(k2[i - 1].share, k2[i].share) << i;
}

TEST(BudgetParts, AFullyCorrelatedGroupIsOneLineNamedByItsMembers) {
  // A group draws its members once with the same sign: their effects add before squaring (docs/model.md §10.1).
  std::string text = test::edited(std::string(bundled_example_text()), "dR_s = \"25 um\"",
                                  "dR_s = { bound = \"25 um\", group = \"radius\" }");
  text = test::edited(text, "dy2t = \"25 um\"", "dy2t = { bound = \"25 um\", group = \"radius\" }");
  const verbs::BudgetResult r = verbs::budget(parse_config(text, "grouped.toml"));
  const BudgetDetail& b = r.budget;
  double effect = 0;
  for (const SourceBudget& s : b.sources)
    if (s.id == "dR_s" || s.id == "dy2t") effect += s.effect[1];
  const auto k2 = contributions(b, 1);
  const Contribution* group = labelled(k2, "radius (dR_s, dy2t)");
  ASSERT_NE(group, nullptr);
  EXPECT_EQ(labelled(k2, "dR_s"), nullptr);
  EXPECT_EQ(labelled(k2, "dy2t"), nullptr);
  // (e1 + e2)² / u²; 1e-12 relative: the same sums in another order.
  const double u = b.standard_uncertainty[1];
  EXPECT_NEAR(group->share, effect * effect / (u * u), 1e-12 * group->share);
  EXPECT_NEAR(share_sum(k2), 1.0, 1e-12);
}

TEST(BudgetParts, TheDivisorAndTheCsvColumnsAsPrinted) {
  EXPECT_EQ(render::budget_parts::divisor_text(1.0), "1");
  EXPECT_EQ(render::budget_parts::divisor_text(std::sqrt(2.0)), "√2");
  EXPECT_EQ(render::budget_parts::divisor_text(std::sqrt(3.0)), "√3");
  EXPECT_EQ(render::budget_parts::divisor_text(std::sqrt(6.0)), "√6");
  EXPECT_EQ(render::budget_parts::csv_column("dK0", "deg/s"), "dK0_deg_s");
  EXPECT_EQ(render::budget_parts::csv_column("dK2", "deg/s/g^2"), "dK2_deg_s_g2");
  EXPECT_EQ(render::budget_parts::csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(render::budget_parts::csv_field("say \"x\""), "\"say \"\"x\"\"\"");
  EXPECT_EQ(render::budget_parts::csv_field("plain"), "plain");
}

}  // namespace budget_parts_render_test
}  // namespace ccal
