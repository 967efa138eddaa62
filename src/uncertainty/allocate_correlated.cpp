// The allocation with partly correlated sources (AllocationProblem::correlation; docs/model.md §10.3). With R
// the sources' correlation matrix and E_k = (J_ks u_s0) the effects on row k, the expanded uncertainty at
// the scales λ (one per group) is k_p √(λᵀ Q_k λ) with Q_k = Gᵀ diag(E_k) R diag(E_k) G (G the group
// indicator), and the rows read s_k(λ) = λᵀ Q̂_k λ ≤ 1 with Q̂_k = (k_p/T_k)² Q_k. The cross terms make s_k
// no longer linear in x = λ², where the independent case is solved; but Q̂_k is positive semi-definite, so
// each row is a convex quadratic in λ, the objective Σ_g C_g/λ_g is convex for λ > 0, and the problem is
// convex in λ: solved by the barrier method (Boyd & Vandenberghe, "Convex Optimization", 2004, §11.3),
//     minimise  t Σ_g C_g/λ_g − Σ_k ln(1 − s_k(λ)) − Σ_g [ln(λ_g − ℓ_g) + ln(Λ − λ_g)],
// Newton's method with backtracking from a strictly feasible start, t × 20 until the duality gap m/t is below
// 1e-11 of the objective; the rows' multipliers then from the stationarity of the Lagrangian.
#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

#include "allocation_groups.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/allocate.hpp"

namespace ccal {

namespace {

struct CorrelatedRows {
  std::vector<Eigen::MatrixXd> Q;  // Q̂_k, groups × groups
  Eigen::VectorXd cost, least;     // C_g; ℓ_g, the largest least scale of the group's sources
  double most = 10;                // Λ
  std::vector<bool> used;          // row k takes part (not met at the floors with its groups pinned)
  std::vector<bool> pinned;        // group g held at ℓ_g
};

double row_value(const Eigen::MatrixXd& Q, const Eigen::VectorXd& lambda) { return lambda.dot(Q * lambda); }

// The barrier function's value (∞ outside its domain), over the free groups of `lambda`.
double barrier_value(const CorrelatedRows& P, const Eigen::VectorXd& lambda, double t) {
  double f = 0;
  for (Eigen::Index g = 0; g < lambda.size(); ++g) {
    if (P.pinned[std::size_t(g)]) continue;
    const double low = lambda[g] - P.least[g], high = P.most - lambda[g];
    if (!(low > 0 && high > 0)) return std::numeric_limits<double>::infinity();
    f += t * P.cost[g] / lambda[g] - std::log(low) - std::log(high);
  }
  for (std::size_t k = 0; k < P.Q.size(); ++k) {
    if (!P.used[k]) continue;
    const double slack = 1 - row_value(P.Q[k], lambda);
    if (!(slack > 0)) return std::numeric_limits<double>::infinity();
    f -= std::log(slack);
  }
  return f;
}

// One centring: Newton's method on the barrier function at t over the free groups. Returns the steps taken.
int centre(const CorrelatedRows& P, double t, Eigen::VectorXd& lambda) {
  const Eigen::Index n = lambda.size();
  int steps = 0;
  for (; steps < 200; ++steps) {
    Eigen::VectorXd grad = Eigen::VectorXd::Zero(n);
    Eigen::MatrixXd hess = Eigen::MatrixXd::Zero(n, n);
    for (Eigen::Index g = 0; g < n; ++g) {
      if (P.pinned[std::size_t(g)]) continue;
      const double low = lambda[g] - P.least[g], high = P.most - lambda[g], l = lambda[g];
      grad[g] = -t * P.cost[g] / (l * l) - 1 / low + 1 / high;
      hess(g, g) = 2 * t * P.cost[g] / (l * l * l) + 1 / (low * low) + 1 / (high * high);
    }
    for (std::size_t k = 0; k < P.Q.size(); ++k) {
      if (!P.used[k]) continue;
      const Eigen::VectorXd q = P.Q[k] * lambda;
      const double slack = 1 - lambda.dot(q);
      grad += 2 * q / slack;
      hess += 2 * P.Q[k] / slack + 4 * q * q.transpose() / (slack * slack);
    }
    for (Eigen::Index g = 0; g < n;
         ++g)  // a pinned group is no variable: its row and column are the identity
      if (P.pinned[std::size_t(g)]) {
        grad[g] = 0;
        hess.row(g).setZero();
        hess.col(g).setZero();
        hess(g, g) = 1;
      }
    const Eigen::VectorXd step = -hess.ldlt().solve(grad);
    const double decrement = -grad.dot(step);  // the Newton decrement squared
    if (!(decrement > 1e-16)) break;
    // Into the domain first; then, far from the centre, backtracking on the barrier function (Armijo); near
    // it (decrement < ½) the full step, whose decrease is below the round-off of φ ~ t·objective at large t.
    double s = 1;
    while (s > 1e-30 && !std::isfinite(barrier_value(P, lambda + s * step, t))) s *= 0.5;
    if (decrement >= 0.5) {
      const double f0 = barrier_value(P, lambda, t);
      while (s > 1e-30 && barrier_value(P, lambda + s * step, t) > f0 - 0.25 * s * decrement) s *= 0.5;
    }
    if (s <= 1e-30) break;
    lambda += s * step;
  }
  return steps;
}

// The rows' multipliers from the stationarity of the Lagrangian at the optimum, C_g/λ_g² = Σ_k μ_k ∂s_k/∂λ_g
// over the groups that no bound holds (beyond 1e-7 of ℓ_g and Λ), for the rows within 1e-7 of 1 (the others
// have μ_k = 0): least squares, negative values set to 0. The barrier's own estimate 1/(t (1 − s_k)) divides
// by a slack of ~1e-12, which carries only ~4 digits.
Eigen::VectorXd row_multipliers(const CorrelatedRows& P, const Eigen::VectorXd& lambda) {
  const Eigen::Index ng = lambda.size(), nt = Eigen::Index(P.Q.size());
  std::vector<Eigen::Index> rows, groups;
  for (Eigen::Index k = 0; k < nt; ++k)
    if (P.used[std::size_t(k)] && 1 - row_value(P.Q[std::size_t(k)], lambda) <= 1e-7) rows.push_back(k);
  for (Eigen::Index g = 0; g < ng; ++g)
    if (!P.pinned[std::size_t(g)] && lambda[g] > P.least[g] + 1e-7 * lambda[g] &&
        lambda[g] < P.most * (1 - 1e-7))
      groups.push_back(g);
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(nt);
  if (rows.empty() || groups.empty()) return mu;
  Eigen::MatrixXd A(Eigen::Index(groups.size()), Eigen::Index(rows.size()));
  Eigen::VectorXd b(Eigen::Index(groups.size()));
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const Eigen::Index g = groups[i];
    b[Eigen::Index(i)] = P.cost[g] / (lambda[g] * lambda[g]);
    for (std::size_t j = 0; j < rows.size(); ++j)
      A(Eigen::Index(i), Eigen::Index(j)) = 2 * (P.Q[std::size_t(rows[j])] * lambda)[g];
  }
  const Eigen::VectorXd solved = A.colPivHouseholderQr().solve(b);
  for (std::size_t j = 0; j < rows.size(); ++j) mu[rows[j]] = std::max(solved[Eigen::Index(j)], 0.0);
  return mu;
}

// The barrier leaves a row with a small price 1/(t μ_k) short of its target. With the active set it found
// (the rows with μ_k > 0, the groups no bound holds), Newton's method on the KKT equations
//     C_g/λ_g² − Σ_k μ_k ∂s_k/∂λ_g = 0,   s_k(λ) = 1,
// puts the point and the multipliers on the optimum to round-off (the groups a bound holds exactly on it);
// kept only if every row still holds, every free λ stays within its bounds and every μ_k ≥ 0 (else the
// barrier's point stands).
void polish(const CorrelatedRows& P, Eigen::VectorXd& lambda, Eigen::VectorXd& mu) {
  const Eigen::Index ng = lambda.size(), nt = Eigen::Index(P.Q.size());
  std::vector<Eigen::Index> rows, groups;
  for (Eigen::Index k = 0; k < nt; ++k)
    if (mu[k] > 0) rows.push_back(k);
  for (Eigen::Index g = 0; g < ng; ++g)
    if (!P.pinned[std::size_t(g)] && lambda[g] > P.least[g] + 1e-7 * lambda[g] &&
        lambda[g] < P.most * (1 - 1e-7))
      groups.push_back(g);
  const auto nf = Eigen::Index(groups.size()), na = Eigen::Index(rows.size());
  if (na == 0 || nf == 0) return;
  Eigen::VectorXd l = lambda, m = mu;
  for (Eigen::Index g = 0; g < ng; ++g)  // a group a bound holds: exactly on it
    if (!P.pinned[std::size_t(g)] && std::find(groups.begin(), groups.end(), g) == groups.end())
      l[g] = l[g] >= P.most * (1 - 1e-7) ? P.most : P.least[g];
  for (int iteration = 0; iteration < 8; ++iteration) {
    Eigen::VectorXd r(nf + na);
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(nf + na, nf + na);
    std::vector<Eigen::VectorXd> q;
    for (const Eigen::Index k : rows) q.push_back(P.Q[std::size_t(k)] * l);
    for (Eigen::Index i = 0; i < nf; ++i) {
      const Eigen::Index g = groups[std::size_t(i)];
      r[i] = P.cost[g] / (l[g] * l[g]);
      J(i, i) = -2 * P.cost[g] / (l[g] * l[g] * l[g]);
      for (Eigen::Index a = 0; a < na; ++a) {
        const Eigen::Index k = rows[std::size_t(a)];
        r[i] -= m[k] * 2 * q[std::size_t(a)][g];
        for (Eigen::Index j = 0; j < nf; ++j)
          J(i, j) -= m[k] * 2 * P.Q[std::size_t(k)](g, groups[std::size_t(j)]);
        J(i, nf + a) = -2 * q[std::size_t(a)][g];
        J(nf + a, i) = -2 * q[std::size_t(a)][g];
      }
    }
    for (Eigen::Index a = 0; a < na; ++a) r[nf + a] = 1 - l.dot(q[std::size_t(a)]);
    const Eigen::VectorXd step = J.fullPivLu().solve(-r);
    if (!step.allFinite()) return;
    for (Eigen::Index i = 0; i < nf; ++i) l[groups[std::size_t(i)]] += step[i];
    for (Eigen::Index a = 0; a < na; ++a) m[rows[std::size_t(a)]] += step[nf + a];
  }
  for (Eigen::Index k = 0; k < nt; ++k)
    if (row_value(P.Q[std::size_t(k)], l) > 1 + 1e-12 || m[k] < 0) return;
  for (const Eigen::Index g : groups)
    if (!(l[g] >= P.least[g] && l[g] <= P.most)) return;
  lambda = l;
  mu = m;
}

}  // namespace

namespace {

// The rows Q_k = (k_p/T_k)² Gᵀ (E_k C E_k) G of the groups (E_k = diag of row k's sensitivities times the
// sources' u, G the sources' groups), symmetrised, with each group's cost and scale bounds.
CorrelatedRows correlated_rows(const AllocationProblem& P, const Groups& groups) {
  const Eigen::Index nt = P.sensitivity.rows(), ns = P.sensitivity.cols(), ng = groups.cost.size();
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(ns, ng);
  for (Eigen::Index s = 0; s < ns; ++s) G(s, groups.of[std::size_t(s)]) = 1;
  CorrelatedRows R;
  R.cost = groups.cost;
  R.most = P.max_scale;
  R.least = Eigen::VectorXd::Zero(ng);
  for (Eigen::Index s = 0; s < ns && P.min_scale.size() > 0; ++s)
    R.least[groups.of[std::size_t(s)]] = std::max(R.least[groups.of[std::size_t(s)]], P.min_scale[s]);
  for (Eigen::Index k = 0; k < nt; ++k) {
    const Eigen::VectorXd e = P.sensitivity.row(k).transpose().cwiseProduct(P.standard_uncertainty);
    const double w = P.coverage_factor / P.target[k];
    R.Q.push_back(w * w * (G.transpose() * (e.asDiagonal() * P.correlation * e.asDiagonal()) * G));
    R.Q.back() = 0.5 * (R.Q.back() + R.Q.back().transpose()).eval();
  }
  return R;
}

// The rows at the least scales: above 1, unreachable (loosening a source whose error cancels another's is
// not sought); at 1 with every group that acts on the row floored, met only there: pinned, the row dropped.
// Fills sol.unreachable and sol.least_expanded, R.used and R.pinned.
void rows_at_least_scales(const AllocationProblem& P, CorrelatedRows& R, AllocationSolution& sol) {
  const auto nt = Eigen::Index(R.Q.size());
  const Eigen::Index ng = R.least.size();
  sol.unreachable.assign(std::size_t(nt), false);
  sol.least_expanded.resize(nt);
  R.used.assign(std::size_t(nt), true);
  R.pinned.assign(std::size_t(ng), false);
  for (Eigen::Index k = 0; k < nt; ++k) {
    const double at_least = row_value(R.Q[std::size_t(k)], R.least);
    sol.least_expanded[k] = P.target[k] * std::sqrt(std::max(at_least, 0.0));
    if (at_least < 1 - 1e-12) continue;
    bool floored = at_least <= 1 + 1e-12;
    for (Eigen::Index g = 0; g < ng; ++g)
      if (R.Q[std::size_t(k)](g, g) > 0 && !(R.least[g] > 0)) floored = false;
    if (!floored) {
      sol.unreachable[std::size_t(k)] = true;
      continue;
    }
    R.used[std::size_t(k)] = false;
    for (Eigen::Index g = 0; g < ng; ++g)
      if (R.Q[std::size_t(k)](g, g) > 0) R.pinned[std::size_t(g)] = true;
  }
}

// A strictly feasible start: λ = ℓ + α (Λ − ℓ), α halved until every row has slack (it has at α → 0).
Eigen::VectorXd strictly_feasible_start(const CorrelatedRows& R) {
  Eigen::VectorXd lambda = R.least;
  for (double alpha = 0.5; alpha > 1e-300; alpha *= 0.5) {
    for (Eigen::Index g = 0; g < lambda.size(); ++g)
      lambda[g] = R.pinned[std::size_t(g)] ? R.least[g] : R.least[g] + alpha * (R.most - R.least[g]);
    if (std::isfinite(barrier_value(R, lambda, 1.0))) break;
  }
  return lambda;
}

// Σ_g c_g / λ_g, the cost of the scales.
double cost_of(const CorrelatedRows& R, const Eigen::VectorXd& lambda) {
  double f = 0;
  for (Eigen::Index g = 0; g < lambda.size(); ++g) f += R.cost[g] / lambda[g];
  return f;
}

// The barrier's outer loop from the start: t × 20 until the duality gap m/t is 1e-11 of the cost (or 5000
// Newton steps). Fills the iterations, the gap and whether it converged.
void barrier_iterations(const CorrelatedRows& R, Eigen::VectorXd& lambda, AllocationSolution& sol) {
  Eigen::Index m = 0;
  for (std::size_t k = 0; k < R.used.size(); ++k) m += R.used[k] ? 1 : 0;
  for (Eigen::Index g = 0; g < lambda.size(); ++g) m += R.pinned[std::size_t(g)] ? 0 : 2;
  double t = double(std::max<Eigen::Index>(m, 1)) / cost_of(R, lambda);
  int iterations = 0;
  while (true) {
    iterations += centre(R, t, lambda);
    if (double(m) / t <= 1e-11 * cost_of(R, lambda) || iterations > 5000) break;
    t *= 20;
  }
  sol.iterations = iterations;
  sol.dual_gap = double(m) / t;
  sol.converged = sol.dual_gap <= 1e-9 * cost_of(R, lambda);
}

}  // namespace

AllocationSolution solve_correlated_allocation(const AllocationProblem& P) {
  const Eigen::Index nt = P.sensitivity.rows(), ns = P.sensitivity.cols();
  if (P.correlation.rows() != ns || P.correlation.cols() != ns)
    throw InputError("allocation: the correlation matrix must be sources × sources");
  const Groups groups = merge_groups(P.sensitivity, P.standard_uncertainty, P.cost, P.group);
  const Eigen::Index ng = groups.cost.size();
  CorrelatedRows R = correlated_rows(P, groups);
  AllocationSolution sol;
  rows_at_least_scales(P, R, sol);
  if (std::find(sol.unreachable.begin(), sol.unreachable.end(), true) != sol.unreachable.end()) {
    sol.method = "none (a target cannot be met with every source at its floor)";
    return sol;
  }

  Eigen::VectorXd lambda = strictly_feasible_start(R);
  barrier_iterations(R, lambda, sol);
  sol.method = "barrier (partly correlated sources)";
  sol.multiplier = row_multipliers(R, lambda);
  polish(R, lambda, sol.multiplier);
  sol.scale.resize(ns);
  for (Eigen::Index s = 0; s < ns; ++s) sol.scale[s] = lambda[groups.of[std::size_t(s)]];
  sol.objective = (P.cost.array() / sol.scale.array()).sum();
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(ng);
  Eigen::VectorXd allocated(nt), configured(nt);
  for (Eigen::Index k = 0; k < nt; ++k) {
    allocated[k] = row_value(R.Q[std::size_t(k)], lambda);
    configured[k] = row_value(R.Q[std::size_t(k)], ones);
  }
  state_rows(P, allocated, configured, sol);
  return sol;
}

}  // namespace ccal
