// One coverage convention (docs/model.md §10.4): the same tolerances give the same U by the same method in
// every verb that states one. The bundled example, p = 95 %, the normal LPU total: budget, allocate's
// configured U, design's configured budget, the report's budget and a statement without Type A.
#include <gtest/gtest.h>

#include <cmath>

#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/statement.hpp"
#include "ccal/verbs/allocate.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/design.hpp"

namespace ccal {
namespace {

// The budget's U(K3) of the bundled example at p = 95 %, 4 significant digits as `ccal budget` prints it.
constexpr double kBundledUK3 = 0.04608;

TEST(OneCoverage, EveryVerbStatesTheSameUForTheSameMethod) {
  const Config config = bundled_example();
  const verbs::BudgetResult budget = verbs::budget(config);
  const auto k3 = Eigen::Index(2);
  const double U = budget.budget.expanded_uncertainty[k3] * budget.budget.display_scale[2];
  EXPECT_NEAR(U, kBundledUK3, 0.5e-5);  // half a unit of the printed digit
  EXPECT_EQ(budget.budget.coverage.method, CoverageMethod::normal);
  EXPECT_EQ(budget.budget.coverage.factor, normal_coverage_factor(0.95));

  // allocate: its "configured U" is the budget's U, the same sensitivities and the same k (relative 1e-12:
  // the two sum the same squares in different orders).
  AllocateOptions ao;
  ao.targets = {"K3=1e-3"};
  ao.verify_trials = 0;
  const verbs::AllocateResult allocation = verbs::allocate(config, ao);
  EXPECT_NEAR(allocation.allocation.coefficients[2].configured_expanded, budget.budget.expanded_uncertainty[k3],
              1e-12 * budget.budget.expanded_uncertainty[k3]);
  EXPECT_EQ(allocation.allocation.coverage_factor, budget.budget.coverage.factor);

  // design: the configured plan's full budget is `ccal budget`'s, bit for bit.
  verbs::DesignOptions d;
  d.starts = 1;
  const verbs::DesignResult design = verbs::design(config, d);
  EXPECT_EQ(design.before.budget.expanded_uncertainty[k3], budget.budget.expanded_uncertainty[k3]);

  // A statement of the Type B part alone: Student t at ν_eff = ∞ is the normal k, so U is the budget's.
  StatementInput in;
  in.type_b.u = budget.budget.standard_uncertainty[k3];
  EXPECT_EQ(state_coefficient(in, 0.95).expanded, budget.budget.expanded_uncertainty[k3]);

  // The same p elsewhere moves every U alike: at 99 % the budget's k is 2.5758 (the normal quantile).
  BudgetOptions p99;
  p99.coverage_probability = 0.99;
  EXPECT_NEAR(verbs::budget(config, p99).budget.expanded_uncertainty[k3] / budget.budget.standard_uncertainty[k3],
              2.5758293035489004, 1e-14);
}

}  // namespace
}  // namespace ccal
