// Tolerance allocation with partly correlated sources (the barrier method in λ, uncertainty/allocate.hpp):
// the independent solver's answers when R only holds the groups, the closed form of two symmetric sources,
// the optimality (KKT) conditions on random correlated problems, and the floors.
//
// Tolerances: the barrier stops at a duality gap of 1e-11 of the objective and Newton's method on the KKT
// equations of its active set then puts the point on the optimum to round-off: the scales and prices agree with
// the independent solver's to 1e-9 (its own KKT residual is 1e-12), the objective to 1e-10.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ccal/uncertainty/allocate.hpp"

namespace ccal {
namespace {

// A random correlation matrix with positive and negative entries: D^(−1/2) A Aᵀ D^(−1/2), A of rank `rank`
// plus a little identity (so that R is definite).
Eigen::MatrixXd random_correlation(int n, int rank, std::mt19937& rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd A(n, rank);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < rank; ++j) A(i, j) = normal(rng);
  Eigen::MatrixXd S = A * A.transpose() + 0.05 * Eigen::MatrixXd::Identity(n, n);
  const Eigen::VectorXd d = S.diagonal().cwiseSqrt().cwiseInverse();
  return d.asDiagonal() * S * d.asDiagonal();
}

AllocationProblem random_problem(std::mt19937& rng, bool groups) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, unit(rng)); };
  const int nt = 1 + int(unit(rng) * 3), ns = 2 + int(unit(rng) * 20);
  AllocationProblem p;
  p.sensitivity.resize(nt, ns);
  for (int k = 0; k < nt; ++k)
    for (int s = 0; s < ns; ++s)
      p.sensitivity(k, s) = unit(rng) < 0.2 ? 0.0 : (unit(rng) < 0.5 ? -1 : 1) * log_uniform(1e-3, 1.0);
  p.standard_uncertainty.resize(ns);
  p.cost.resize(ns);
  for (int s = 0; s < ns; ++s) {
    p.standard_uncertainty[s] = log_uniform(1e-2, 1e2);
    p.cost[s] = log_uniform(0.1, 10.0);
    p.group.push_back(groups && unit(rng) < 0.3 ? std::string(1, char('a' + int(unit(rng) * 3))) : "");
  }
  p.max_scale = unit(rng) < 0.5 ? 10.0 : 2.0;
  p.target.resize(nt);
  for (int k = 0; k < nt; ++k) {
    const Eigen::RowVectorXd e = p.sensitivity.row(k).cwiseProduct(p.standard_uncertainty.transpose());
    p.target[k] = p.coverage_factor * e.norm() * log_uniform(1e-2, 2.0);
  }
  return p;
}

// R of the groups alone: 1 between the members of a group.
Eigen::MatrixXd group_correlation(const AllocationProblem& p) {
  const auto n = p.sensitivity.cols();
  Eigen::MatrixXd R = Eigen::MatrixXd::Identity(n, n);
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b)
      if (!p.group[std::size_t(a)].empty() && p.group[std::size_t(a)] == p.group[std::size_t(b)]) R(a, b) = 1;
  return R;
}

TEST(CorrelatedAllocation, GroupsAloneGiveTheIndependentSolversAnswer) {
  std::mt19937 rng(20261204);
  for (int problem = 0; problem < 40; ++problem) {
    SCOPED_TRACE(problem);
    AllocationProblem p = random_problem(rng, true);
    const AllocationSolution independent = solve_allocation(p);
    p.correlation = group_correlation(p);
    const AllocationSolution barrier = solve_allocation(p);
    EXPECT_EQ(barrier.method, "barrier (partly correlated sources)");
    EXPECT_TRUE(barrier.converged);
    EXPECT_NEAR(barrier.objective, independent.objective, 1e-10 * independent.objective);
    for (Eigen::Index s = 0; s < p.sensitivity.cols(); ++s)
      EXPECT_NEAR(barrier.scale[s], independent.scale[s], 1e-9 * independent.scale[s]) << s;
    for (Eigen::Index k = 0; k < p.target.size(); ++k) {
      EXPECT_NEAR(barrier.expanded[k], independent.expanded[k], 1e-6 * p.target[k]);
      EXPECT_NEAR(barrier.configured_expanded[k], independent.configured_expanded[k],
                  1e-13 * independent.configured_expanded[k]);
      // A row at its target with no price (μ = 0, a degenerate optimum) is active for one method and may be
      // left 1e-9 short by the other: only rows with a price must agree.
      if (independent.multiplier[k] > 1e-6 * independent.objective) {
        EXPECT_TRUE(barrier.active[std::size_t(k)]);
      }
      EXPECT_NEAR(barrier.multiplier[k], independent.multiplier[k], 1e-9 * independent.objective);
    }
  }
}

TEST(CorrelatedAllocation, TwoSymmetricSourcesHaveTheClosedForm) {
  // One target on y = x₁ + x₂ with u = 1 each, equal costs: by symmetry λ₁ = λ₂ = λ and the row is
  // (k_p/T)² 2λ²(1 + r) = 1, so λ = T/(k_p √(2(1 + r))). With T = 0.1 k_p: λ = 0.1/√(2(1 + r)).
  for (const double r : {-0.9, -0.5, 0.0, 0.5, 0.9}) {
    AllocationProblem p;
    p.sensitivity.resize(1, 2);
    p.sensitivity << 1.0, 1.0;
    p.standard_uncertainty = Eigen::Vector2d(1.0, 1.0);
    p.cost = Eigen::Vector2d(1.0, 1.0);
    p.target = Eigen::VectorXd::Constant(1, 0.1 * p.coverage_factor);
    p.correlation.resize(2, 2);
    p.correlation << 1.0, r, r, 1.0;
    const AllocationSolution s = solve_allocation(p);
    const double lambda = 0.1 / std::sqrt(2 * (1 + r));
    EXPECT_NEAR(s.scale[0], lambda, 1e-6 * lambda) << r;
    EXPECT_NEAR(s.scale[1], lambda, 1e-6 * lambda) << r;
    EXPECT_NEAR(s.objective, 2 / lambda, 1e-10 * 2 / lambda) << r;
    EXPECT_TRUE(s.active[0]);
    // The price: ∂(objective)/∂(ln T) = −2μ, and the objective is 2/λ ∝ 1/T: −2μ = −2/λ.
    EXPECT_NEAR(-2 * s.multiplier[0], -2 / lambda, 1e-6 * 2 / lambda) << r;
  }
}

TEST(CorrelatedAllocation, RandomCorrelatedProblemsAreOptimal) {
  std::mt19937 rng(7);
  std::normal_distribution<double> step(0.0, 0.2);
  for (int problem = 0; problem < 30; ++problem) {
    SCOPED_TRACE(problem);
    AllocationProblem p = random_problem(rng, false);
    const auto ns = p.sensitivity.cols(), nt = p.sensitivity.rows();
    p.correlation = random_correlation(int(ns), 1 + problem % 4, rng);
    const AllocationSolution s = solve_allocation(p);
    ASSERT_TRUE(s.converged) << s.method;
    // The rows, computed here: s_k = (k_p/T_k)² eᵀ R e with e = J_k (λ u).
    const auto row = [&](Eigen::Index k, const Eigen::VectorXd& lambda) {
      const Eigen::VectorXd e =
          p.sensitivity.row(k).transpose().cwiseProduct(p.standard_uncertainty).cwiseProduct(lambda);
      return std::pow(p.coverage_factor / p.target[k], 2) * e.dot(p.correlation * e);
    };
    for (Eigen::Index k = 0; k < nt; ++k) {
      EXPECT_LE(row(k, s.scale), 1 + 1e-12) << k;
      EXPECT_NEAR(s.expanded[k], p.target[k] * std::sqrt(row(k, s.scale)), 1e-12 * p.target[k]);
    }
    // Stationarity where no bound is active: C_s/λ_s² = Σ_k μ_k ∂s_k/∂λ_s, ∂s_k/∂λ = 2 (k_p/T_k)² diag(J_k u)
    // R e_k.
    for (Eigen::Index j = 0; j < ns; ++j) {
      if (s.scale[j] > p.max_scale * (1 - 1e-4)) continue;
      double push = 0;
      for (Eigen::Index k = 0; k < nt; ++k) {
        const Eigen::VectorXd ju = p.sensitivity.row(k).transpose().cwiseProduct(p.standard_uncertainty);
        const Eigen::VectorXd e = ju.cwiseProduct(s.scale);
        push += s.multiplier[k] * 2 * std::pow(p.coverage_factor / p.target[k], 2) * ju[j] *
                (p.correlation * e)[j];
      }
      const double pull = p.cost[j] / (s.scale[j] * s.scale[j]);
      EXPECT_NEAR(push, pull, 1e-5 * pull) << "source " << j;
    }
    // No random feasible point nearby is cheaper.
    for (int trial = 0; trial < 300; ++trial) {
      Eigen::VectorXd y(ns);
      for (Eigen::Index j = 0; j < ns; ++j) y[j] = std::min(p.max_scale, s.scale[j] * std::exp(step(rng)));
      double worst = 0;
      for (Eigen::Index k = 0; k < nt; ++k) worst = std::max(worst, row(k, y));
      if (worst > 1) y /= std::sqrt(worst);
      ASSERT_GE((p.cost.array() / y.array()).sum(), s.objective * (1 - 1e-10)) << "trial " << trial;
    }
  }
}

TEST(CorrelatedAllocation, FloorsHoldAndAnUnreachableTargetIsFound) {
  AllocationProblem p;
  p.sensitivity.resize(1, 3);
  p.sensitivity << 1.0, 2.0, 1.0;
  p.standard_uncertainty = Eigen::Vector3d(1.0, 1.0, 1.0);
  p.cost = Eigen::Vector3d(1.0, 1.0, 1.0);
  p.correlation = Eigen::Matrix3d{{1.0, 0.3, 0.0}, {0.3, 1.0, -0.2}, {0.0, -0.2, 1.0}};
  p.min_scale = Eigen::Vector3d(0.0, 0.5, 0.0);
  p.target = Eigen::VectorXd::Constant(1, 1.2 * p.coverage_factor);
  const AllocationSolution s = solve_allocation(p);
  ASSERT_TRUE(s.converged) << s.dual_gap << " " << s.objective << " " << s.iterations << " "
                           << s.scale.transpose();
  EXPECT_GE(s.scale[1], 0.5 * (1 - 1e-9));
  EXPECT_TRUE(s.active[0]);
  // At its floor source 2 alone gives U = k_p·2·0.5 = k_p: a target below that cannot be met.
  p.target[0] = 0.9 * p.coverage_factor;
  const AllocationSolution none = solve_allocation(p);
  EXPECT_TRUE(none.unreachable[0]);
  EXPECT_NEAR(none.least_expanded[0], p.coverage_factor, 1e-12);
}

}  // namespace
}  // namespace ccal
