// The search of `ccal design` (uncertainty/design_search.hpp) on problems with known optima: the D-optimal
// designs of polynomial regression on an interval (Kiefer & Wolfowitz; e.g. Atkinson, Donev & Tobias,
// "Optimum Experimental Designs", §11.4) reproduced through the same exchange search and local refinement
// that design centrifuge plans, and the refusals of a space that cannot fit or cannot identify.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "../src/uncertainty/design_exchange.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/design_search.hpp"

namespace ccal {
namespace {

// Rows of the polynomial model y = Σ_{k≤d} K_k x^k with equal, unit noise; x is carried in
// DesignRun::g_level.
CandidateRows polynomial_rows(const std::vector<DesignRun>& runs, int degree) {
  const auto n = Eigen::Index(runs.size());
  CandidateRows r;
  r.regressors.resize(n, degree + 1);
  r.natural = Eigen::MatrixXd::Ones(n, degree + 1);
  r.leaks = Eigen::MatrixXd::Zero(n, 1);
  r.scatter = Eigen::VectorXd::Zero(n);
  r.noise = Eigen::VectorXd::Zero(n);  // no noise given: the criterion takes equal variances
  r.duration = Eigen::VectorXd::Ones(n);
  for (Eigen::Index j = 0; j < n; ++j)
    for (int k = 0; k <= degree; ++k) r.regressors(j, k) = std::pow(runs[std::size_t(j)].g_level, k);
  return r;
}

DesignProblem polynomial_problem(int degree, int runs, double grid_step, bool refine) {
  DesignProblem p;
  p.runs = runs;
  for (double x = -1; x <= 1 + 1e-12; x += grid_step) {
    DesignRun r;
    r.g_level = std::clamp(std::round(x / grid_step) * grid_step, -1.0, 1.0);
    p.candidates.push_back(r);
  }
  p.rows = polynomial_rows(p.candidates, degree);
  p.criterion.objective = DesignObjective::d_optimal;
  p.criterion.weight = Eigen::VectorXd::Ones(degree + 1);
  p.criterion.reference = Eigen::VectorXd::Ones(degree + 1);
  if (refine) {
    p.evaluate = [degree](const std::vector<DesignRun>& r) { return polynomial_rows(r, degree); };
    p.refinement.g_step = grid_step / 2;
    p.refinement.g_low = -1;
    p.refinement.g_high = 1;
  }
  return p;
}

std::vector<double> support(const DesignSearchResult& r) {
  std::vector<double> x;
  for (const DesignRun& run : r.runs) x.push_back(run.g_level);
  std::sort(x.begin(), x.end());
  return x;
}

// det(HᵀH) of a design with m runs at each of the d + 1 points x_i: H = V repeated m times, so
// det(HᵀH) = m^(d+1) det(V)², det V = Π_{i<j} (x_j − x_i) (Vandermonde).
double repeated_vandermonde_det(const std::vector<double>& x, int m) {
  double v = 1;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = i + 1; j < x.size(); ++j) v *= x[j] - x[i];
  return std::pow(double(m), double(x.size())) * v * v;
}

// Quadratic on [−1, 1]: the D-optimal design puts equal weight 1/3 on {−1, 0, 1}; det M = 4/27 for the
// normalised information M = HᵀH/n. All three points are on the grid, so the exchange alone must reach it
// exactly (tolerance: round-off of a 3×3 determinant).
TEST(DesignSearch, QuadraticDOptimalOnTheGrid) {
  const DesignProblem p = polynomial_problem(2, 6, 0.05, false);
  const DesignSearchResult r = search_design(p, {});
  const std::vector<double> x = support(r);
  const std::vector<double> expected{-1, -1, 0, 0, 1, 1};
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(x[i], expected[i], 1e-12) << i;
  const double det = std::exp(-r.score.objective);
  EXPECT_NEAR(det, repeated_vandermonde_det({-1, 0, 1}, 2), 1e-10 * det);
  EXPECT_NEAR(det / std::pow(6.0, 3), 4.0 / 27.0, 1e-12);  // det(HᵀH/n)
}

// Cubic on [−1, 1]: support {−1, −1/√5, 1/√5, 1} (the roots of (1 − x²) P₃′(x)), equal weights 1/4, and
// det M = (1/4)⁴ det(V)² = (1/256)·4096/3125 = 16/3125. ±1/√5 = ±0.44721… is not on the grid: the local
// refinement must find it. Tolerances: the refinement's last step is 0.025/2¹² = 6e-6 and det is stationary
// at the optimum, so the determinant is exact to ~1e-9 relative and the points to ~1e-5.
TEST(DesignSearch, CubicDOptimalNeedsTheRefinement) {
  const double a = 1 / std::sqrt(5.0);
  const DesignProblem p = polynomial_problem(3, 8, 0.05, true);
  const DesignSearchResult r = search_design(p, {});
  const std::vector<double> x = support(r);
  const std::vector<double> expected{-1, -1, -a, -a, a, a, 1, 1};
  for (std::size_t i = 0; i < x.size(); ++i) EXPECT_NEAR(x[i], expected[i], 1e-4) << i;
  const double det = std::exp(-r.score.objective);
  EXPECT_NEAR(det / std::pow(8.0, 4), 16.0 / 3125.0, 1e-8 * 16.0 / 3125.0);
  EXPECT_NEAR(det, repeated_vandermonde_det({-1, -a, a, 1}, 2), 1e-8 * det);
  // The grid alone cannot: its best support is ±0.45, a determinant below the optimum.
  EXPECT_GT(r.grid_objective, r.score.objective);
}

// The same seed gives the same plan; the result does not depend on the start order of equal candidates.
TEST(DesignSearch, DeterministicForASeed) {
  const DesignProblem p = polynomial_problem(3, 8, 0.05, true);
  DesignSearchOptions o;
  o.seed = 42;
  const DesignSearchResult a = search_design(p, o), b = search_design(p, o);
  ASSERT_EQ(a.runs.size(), b.runs.size());
  for (std::size_t i = 0; i < a.runs.size(); ++i) EXPECT_EQ(a.runs[i].g_level, b.runs[i].g_level);
  EXPECT_EQ(a.score.objective, b.score.objective);
  EXPECT_EQ(a.start_objectives, b.start_objectives);
}

// The time budget holds: the D-optimal points x = −1, 0, 1 cost 5 s each and every other point 1 s, with at
// most 7 s for three runs, so the unconstrained optimum (15 s) is out of reach and at most one of them can be
// used; and the objective never rises above that of an initial plan that is a start.
TEST(DesignSearch, TimeBudgetAndNeverWorseThanTheStart) {
  DesignProblem p = polynomial_problem(2, 3, 0.25, false);
  for (Eigen::Index j = 0; j < p.rows.size(); ++j) p.rows.duration[j] = (j == 0 || j == 4 || j == 8) ? 5 : 1;
  p.total_time = 7;
  p.initial_plans = {{1, 3, 6}};  // x = −0.75, −0.25, 0.5: 3 s
  const PlanScore start = score_plan(p.rows.select(p.initial_plans.front()), p.criterion);
  const DesignSearchResult r = search_design(p, {});
  EXPECT_LE(r.rows.duration.sum(), 7 * (1 + 1e-12));
  EXPECT_LE(r.score.objective, start.objective);
}

// A space that cannot identify the terms (two distinct x for a quadratic) or cannot fit the time is refused.
TEST(DesignSearch, RefusesSpacesWithoutAWellPosedPlan) {
  DesignProblem p = polynomial_problem(2, 4, 0.05, false);
  std::vector<DesignRun> two(2);
  two[0].g_level = 0;
  two[1].g_level = 1;
  p.candidates = two;
  p.rows = polynomial_rows(two, 2);
  EXPECT_THROW(search_design(p, {}), InputError);
  DesignProblem q = polynomial_problem(2, 3, 0.05, false);
  q.total_time = 2.5;  // three runs of 1 s each cannot fit
  try {
    search_design(q, {});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("total time"), std::string::npos) << e.what();
  }
}

// The uncertainty objective is the budget's law of propagation on the plan's rows: with H = I (three runs,
// one per coefficient) H⁺ = I, so Cov = L Lᵀ + diag(v) exactly.
TEST(DesignSearch, UncertaintyScoreIsTheLawOfPropagation) {
  CandidateRows r;
  r.regressors = Eigen::MatrixXd::Identity(3, 3);
  r.natural = Eigen::MatrixXd::Ones(3, 3);
  r.leaks.resize(3, 2);
  r.leaks << 1, 2, 3, 4, 5, 6;
  r.scatter = Eigen::VectorXd::Constant(3, 0.5);
  r.noise = Eigen::VectorXd::Constant(3, 0.25);
  r.duration = Eigen::VectorXd::Ones(3);
  DesignCriterion c;
  c.weight = Eigen::Vector3d(1, 0, 2);
  c.reference = Eigen::Vector3d(1, 1, 4);
  c.coverage_factor = 2;
  const PlanScore s = score_plan(r, c);
  ASSERT_TRUE(s.well_posed);
  const Eigen::Matrix3d expected = r.leaks * r.leaks.transpose() + 0.75 * Eigen::Matrix3d::Identity();
  EXPECT_LT((s.covariance - expected).norm(), 1e-13 * expected.norm());
  // F = Σ w (k u / R)²: 1·4·(5 + 0.75)/1 + 2·4·(61 + 0.75)/16
  EXPECT_NEAR(s.objective, 4 * 5.75 + 8 * 61.75 / 16, 1e-12);
}

// The exchange step's rank-one updates (design_exchange.hpp) give the objective of the full fit on the trial
// plan: random rows (4 terms, 7 tolerance groups, scales from 1 to 1e4 like gⁿ), a 6-run plan, every position
// and 200 candidates. Both compute the same algebra on well-conditioned 4×4 systems in a different order:
// 1e-10 relative. A candidate that duplicates a run of a 4-run plan leaves it ill-posed in both (infinity).
TEST(DesignSearch, ExchangeUpdatesScoreAsTheFullFit) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal;
  const Eigen::Index candidates = 200, p = 4, groups = 7;
  CandidateRows r;
  r.regressors.resize(candidates, p);
  r.natural.resize(candidates, p);
  r.leaks.resize(candidates, groups);
  r.scatter.resize(candidates);
  r.noise.resize(candidates);
  r.duration = Eigen::VectorXd::Ones(candidates);
  for (Eigen::Index j = 0; j < candidates; ++j) {
    const double x = 1 + 29 * std::abs(normal(rng)) / 3;  // a g-level
    for (Eigen::Index k = 0; k < p; ++k) {
      r.natural(j, k) = std::pow(x, double(k));
      r.regressors(j, k) = r.natural(j, k) * (1 + 0.1 * normal(rng));
    }
    for (Eigen::Index g = 0; g < groups; ++g) r.leaks(j, g) = normal(rng);
    r.scatter[j] = 0.1 * std::abs(normal(rng));
    r.noise[j] = 0.05 * std::abs(normal(rng));
  }
  DesignCriterion c;
  c.weight = Eigen::Vector4d(1, 0, 2, 0.5);
  c.reference = Eigen::Vector4d(1, 3, 0.1, 1e-3);
  const Eigen::VectorXd norms = design_detail::leak_norms(r);
  const std::vector<int> plan{3, 17, 42, 99, 150, 181};
  design_detail::ExchangeScorer update(r, norms, c);
  for (std::size_t i = 0; i < plan.size(); ++i) {
    update.set_others(plan, i);
    for (int cand = 0; cand < int(candidates); ++cand) {
      std::vector<int> trial = plan;
      trial[i] = cand;
      const double full = score_plan(r.select(trial), c).objective;
      ASSERT_TRUE(std::isfinite(full));
      EXPECT_LT(std::abs(update.objective(cand) - full), 1e-10 * full)
          << "position " << i << ", candidate " << cand;
    }
  }
  const std::vector<int> four{3, 17, 42, 99};
  update.set_others(four, 0);
  EXPECT_TRUE(std::isinf(update.objective(17)));
  EXPECT_TRUE(std::isinf(score_plan(r.select({17, 17, 42, 99}), c).objective));
}

}  // namespace
}  // namespace ccal
