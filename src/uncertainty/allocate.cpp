#include "ccal/uncertainty/allocate.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <utility>

#include "allocation_groups.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"
#include "ccal/reduction/fit.hpp"

namespace ccal {

Groups merge_groups(const Eigen::MatrixXd& J, const Eigen::VectorXd& u0, const Eigen::VectorXd& cost,
                    const std::vector<std::string>& group) {
  Groups g;
  const CorrelationGroups index = correlation_groups(group, std::size_t(J.cols()));
  g.of = index.of;
  const int n = index.count;
  g.cost = Eigen::VectorXd::Zero(n);
  g.effect = Eigen::MatrixXd::Zero(J.rows(), n);
  for (Eigen::Index s = 0; s < J.cols(); ++s) {
    const int k = g.of[std::size_t(s)];
    g.cost[k] += cost[s];
    g.effect.col(k) += J.col(s) * u0[s];
  }
  return g;
}

namespace {

// The dual of  min Σ_g C_g x_g^(−1/2)  s.t.  a x ≤ 1,  L_g ≤ x_g ≤ X_g  (see allocate.hpp); L_g ≥ 0 (0:
// x_g > 0 only), L_g < X_g.
struct DualProblem {
  const Eigen::MatrixXd& a;  // n_rows × n_groups
  const Eigen::VectorXd& C;
  const Eigen::VectorXd& L;
  const Eigen::VectorXd& X;

  struct Point {
    Eigen::VectorXd mu, b, x;
    std::vector<bool> interior;  // L_g < x_g < X_g (no bound is active)
    Eigen::VectorXd slack;       // 1 − a x: the gradient of −D
    double minus_dual = 0;       // −D(μ)
  };

  Point at(const Eigen::VectorXd& mu) const {
    Point p;
    p.mu = mu;
    p.b = a.transpose() * mu;
    const auto n = C.size();
    p.x.resize(n);
    p.interior.assign(std::size_t(n), false);
    double d = 0;
    for (Eigen::Index g = 0; g < n; ++g) {
      // The minimiser of C x^(−1/2) + b x over [L, X]: the stationary point clamped to the interval.
      double x = X[g];
      if (p.b[g] > 0) {
        const double r = std::cbrt(C[g] / (2 * p.b[g]));
        if (r * r <= L[g]) {
          x = L[g];
        } else if (r * r < X[g]) {
          x = r * r;
          p.interior[std::size_t(g)] = true;
        }
      }
      p.x[g] = x;
      d += C[g] / std::sqrt(x) + p.b[g] * x;
    }
    p.slack = Eigen::VectorXd::Ones(a.rows()) - a * p.x;
    p.minus_dual = mu.sum() - d;
    return p;
  }
};

// Largest violation of the optimality conditions of the dual over μ ≥ 0 (in units of the normalised
// constraint): |slack| where μ_k > 0, the violated part of the constraint where μ_k = 0.
double kkt_residual(const DualProblem::Point& p, const std::vector<bool>& candidate) {
  double r = 0;
  for (Eigen::Index k = 0; k < p.slack.size(); ++k) {
    if (!candidate[std::size_t(k)]) continue;
    r = std::max(r, p.mu[k] > 0 ? std::abs(p.slack[k]) : std::max(0.0, -p.slack[k]));
  }
  return r;
}

constexpr double kTolerance = 1e-13;  // on the slack of a normalised constraint

struct DualRun {
  Eigen::VectorXd nu;
  DualProblem::Point point;
  double residual = 0;
  int iterations = 0;
};

// The Hessian of −D(m ν) in ν:  diag(m) H_μ diag(m),  H_μ,kl = ∂²(−D)/∂μ_k∂μ_l = (2/3) Σ_{g: x_g < X} a_kg
// a_lg x_g / b_g (a group at its bound X does not move with μ).
Eigen::MatrixXd dual_hessian(const DualProblem& dual, const DualProblem::Point& point,
                             const Eigen::VectorXd& m) {
  const Eigen::Index nt = m.size(), ng = dual.C.size();
  const Eigen::MatrixXd& a = dual.a;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(nt, nt);
  for (Eigen::Index g = 0; g < ng; ++g)
    if (point.interior[std::size_t(g)])
      H.noalias() += (2.0 / 3.0) * point.x[g] / point.b[g] * a.col(g) * a.col(g).transpose();
  H = m.asDiagonal() * H * m.asDiagonal();
  return H;
}

// The ε-active set of the projected Newton method: the multipliers at or near zero (ν_k ≤ ε with
// ε = min(1e-3, |ν − max(0, ν − ∇/m)|)) whose constraint is slack beyond round-off; these go to zero.
// Targets that are not candidates are held as well (they stay at zero).
std::vector<bool> held_multipliers(const Eigen::VectorXd& nu, const Eigen::VectorXd& grad,
                                   const Eigen::VectorXd& m, const Eigen::VectorXd& slack,
                                   const std::vector<bool>& candidate) {
  const Eigen::Index nt = m.size();
  double w = 0;
  for (Eigen::Index k = 0; k < nt; ++k)
    if (candidate[std::size_t(k)]) w += std::pow(nu[k] - std::max(0.0, nu[k] - grad[k] / m[k]), 2);
  const double eps = std::min(1e-3, std::sqrt(w));
  std::vector<bool> held(std::size_t(nt), true);
  for (Eigen::Index k = 0; k < nt; ++k)
    if (candidate[std::size_t(k)] && !(nu[k] <= eps && slack[k] > kTolerance)) held[std::size_t(k)] = false;
  return held;
}

// The Newton step −H_f⁻¹ g_f on the free multipliers `free`, and the floor curvature of each: that of the
// target alone at ν = 1 with no bound active, (2/3) m_k. Directions of no curvature (every source of the
// target at the largest scale, where −D is linear in μ_k) get the floor curvature, so that the search starts
// with a step of a sensible size; a small ridge guards against near-singularity. Where the factorisation
// gives no descent direction, the scaled gradient.
struct FreeStep {
  Eigen::VectorXd direction, floor;
};
FreeStep newton_step_on_free(const Eigen::MatrixXd& H, const Eigen::VectorXd& grad, const Eigen::VectorXd& m,
                             const std::vector<Eigen::Index>& free) {
  const auto nf = Eigen::Index(free.size());
  Eigen::MatrixXd Hf(nf, nf);
  Eigen::VectorXd gf(nf);
  FreeStep step;
  step.floor.resize(nf);
  for (Eigen::Index i = 0; i < nf; ++i) {
    gf[i] = grad[free[std::size_t(i)]];
    step.floor[i] = (2.0 / 3.0) * m[free[std::size_t(i)]];
    for (Eigen::Index j = 0; j < nf; ++j) Hf(i, j) = H(free[std::size_t(i)], free[std::size_t(j)]);
  }
  for (Eigen::Index i = 0; i < nf; ++i) {
    if (Hf(i, i) < 1e-8 * step.floor[i]) Hf(i, i) += step.floor[i];
    Hf(i, i) *= 1 + 1e-12;
  }
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(Hf);
  if (ldlt.info() == Eigen::Success && ldlt.isPositive()) step.direction = -ldlt.solve(gf);
  if (step.direction.size() != nf || !step.direction.allFinite() || !(gf.dot(step.direction) < 0))
    step.direction = -gf.cwiseQuotient(Hf.diagonal().cwiseMax(step.floor));  // scaled gradient
  return step;
}

// The search direction d: −ν_k for the held multipliers, the Newton step on the others. A multiplier at zero
// that the step would take below zero is held at zero as well, and the step recomputed without it. Where −D
// is linear in ν_k and falls towards zero, its minimum along ν_k is at zero.
Eigen::VectorXd search_direction(const Eigen::MatrixXd& H, const Eigen::VectorXd& grad,
                                 const Eigen::VectorXd& m, const Eigen::VectorXd& nu,
                                 const std::vector<bool>& candidate, std::vector<bool>& held) {
  const Eigen::Index nt = m.size();
  Eigen::VectorXd d = Eigen::VectorXd::Zero(nt);
  for (Eigen::Index k = 0; k < nt; ++k)
    if (candidate[std::size_t(k)] && held[std::size_t(k)]) d[k] = -nu[k];
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<Eigen::Index> free;
    for (Eigen::Index k = 0; k < nt; ++k)
      if (!held[std::size_t(k)]) free.push_back(k);
    if (free.empty()) break;
    const FreeStep step = newton_step_on_free(H, grad, m, free);
    for (Eigen::Index i = 0; i < Eigen::Index(free.size()); ++i) {
      const Eigen::Index k = free[std::size_t(i)];
      d[k] = step.direction[i];
      if (H(k, k) < 1e-8 * step.floor[i] && grad[k] > 0) d[k] = std::min(d[k], -nu[k]);
      if (nu[k] == 0 && d[k] < 0) {
        held[std::size_t(k)] = true;
        d[k] = 0;
        changed = true;
      }
    }
  }
  return d;
}

// Exact line search along ν + t d, t in (0, t_max]: t_max = 1, or less where a component would become
// negative (it is then set to zero). −D is convex along the segment, so its slope
//     ψ'(t) = (m ⊙ s(ν + t d)) · d
// is non-decreasing in t: the full step if ψ'(t_max) ≤ 0, else bisection for ψ' = 0. (A backtracking
// search is not enough: −D grows like b^(1/3) from b = 0, far from its quadratic model.)
struct LineSearch {
  Eigen::VectorXd nu;
  DualProblem::Point point;
  double t = 0, t_max = 0;
};
LineSearch exact_line_search(const DualProblem& dual, const Eigen::VectorXd& m,
                             const std::vector<bool>& candidate, const Eigen::VectorXd& nu,
                             const Eigen::VectorXd& d) {
  const Eigen::Index nt = m.size();
  LineSearch s;
  s.t_max = 1;
  Eigen::Index stop = -1;
  for (Eigen::Index k = 0; k < nt; ++k)
    if (candidate[std::size_t(k)] && d[k] < 0 && nu[k] + d[k] <= 0 && nu[k] / -d[k] <= s.t_max) {
      s.t_max = nu[k] / -d[k];
      stop = k;
    }
  const double t_max = s.t_max;
  auto along = [&](double t) {
    Eigen::VectorXd v = (nu + t * d).cwiseMax(0.0);
    for (Eigen::Index k = 0; k < nt; ++k)
      if (!candidate[std::size_t(k)] || (k == stop && t == t_max)) v[k] = 0;
    return v;
  };
  auto slope = [&](const DualProblem::Point& p) { return m.cwiseProduct(p.slack).dot(d); };
  s.t = t_max;
  s.point = dual.at(m.cwiseProduct(along(s.t)));
  if (slope(s.point) > 0) {
    double lo = 0, hi = t_max;
    for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      s.point = dual.at(m.cwiseProduct(along(mid)));
      (slope(s.point) > 0 ? hi : lo) = mid;
    }
    s.t = 0.5 * (lo + hi);
    s.point = dual.at(m.cwiseProduct(along(s.t)));
  }
  s.nu = along(s.t);
  return s;
}

// The multipliers sent to zero reach it only with the full step; where the search stopped short, zero them
// anyway if that neither raises −D nor breaks their constraints (else they would only shrink geometrically).
void zero_held_if_harmless(const DualProblem& dual, const Eigen::VectorXd& m, const std::vector<bool>& held,
                           Eigen::VectorXd& nu, DualProblem::Point& point) {
  const Eigen::Index nt = m.size();
  Eigen::VectorXd zeroed = nu;
  for (Eigen::Index k = 0; k < nt; ++k)
    if (held[std::size_t(k)]) zeroed[k] = 0;
  if (zeroed == nu) return;
  const DualProblem::Point z = dual.at(m.cwiseProduct(zeroed));
  bool holds = z.minus_dual <= point.minus_dual;
  for (Eigen::Index k = 0; k < nt; ++k)
    if (held[std::size_t(k)] && z.slack[k] < -kTolerance) holds = false;
  if (holds) {
    nu = zeroed;
    point = z;
  }
}

// Projected Newton on −D(m ν) over ν ≥ 0 (Bertsekas, "Projected Newton methods for optimization problems
// with simple constraints", SIAM J. Control Optim. 20, 1982): multipliers at or near zero whose constraint is
// slack are sent to zero, the others take a Newton step on the Hessian of −D (dual_hessian), with an exact
// line search. Until the residual is below kTolerance or no progress is possible.
DualRun run_dual(const DualProblem& dual, const Eigen::VectorXd& m, const std::vector<bool>& candidate,
                 Eigen::VectorXd nu, int max_iterations) {
  DualRun run;
  run.point = dual.at(m.cwiseProduct(nu));
  run.residual = kkt_residual(run.point, candidate);
  for (int iteration = 0; iteration < max_iterations && run.residual > kTolerance; ++iteration) {
    run.iterations = iteration + 1;
    const Eigen::VectorXd grad = m.cwiseProduct(run.point.slack);
    const Eigen::MatrixXd H = dual_hessian(dual, run.point, m);
    std::vector<bool> held = held_multipliers(nu, grad, m, run.point.slack, candidate);
    const Eigen::VectorXd d = search_direction(H, grad, m, nu, candidate, held);
    if (!(grad.dot(d) < 0)) break;  // no descent direction left at this precision
    LineSearch s = exact_line_search(dual, m, candidate, nu, d);
    nu = std::move(s.nu);
    run.point = std::move(s.point);
    if (s.t < s.t_max) zero_held_if_harmless(dual, m, held, nu, run.point);
    run.residual = kkt_residual(run.point, candidate);
  }
  run.nu = nu;
  return run;
}

}  // namespace

namespace {

// Refuses a problem of inconsistent sizes or with a value no allocation can use.
void check_problem(const AllocationProblem& P) {
  const Eigen::Index nt = P.sensitivity.rows(), ns = P.sensitivity.cols();
  if (P.target.size() != nt || P.standard_uncertainty.size() != ns || P.cost.size() != ns ||
      (!P.group.empty() && Eigen::Index(P.group.size()) != ns))
    throw InputError(fmt::format(
        "allocation: inconsistent sizes ({} × {} sensitivities, {} targets, {} uncertainties, {} costs, {} "
        "groups)",
        nt, ns, P.target.size(), P.standard_uncertainty.size(), P.cost.size(), P.group.size()));
  for (Eigen::Index k = 0; k < nt; ++k)
    if (!(std::isfinite(P.target[k]) && P.target[k] > 0))
      throw InputError(
          fmt::format("allocation: target {} is {}; every target must be a number > 0", k + 1, P.target[k]));
  for (Eigen::Index s = 0; s < ns; ++s) {
    if (!(std::isfinite(P.cost[s]) && P.cost[s] > 0))
      throw InputError(
          fmt::format("allocation: the cost of source {} is {}; it must be > 0", s + 1, P.cost[s]));
    if (!(std::isfinite(P.standard_uncertainty[s]) && P.standard_uncertainty[s] >= 0))
      throw InputError(fmt::format("allocation: the standard uncertainty of source {} is {}; it must be ≥ 0",
                                   s + 1, P.standard_uncertainty[s]));
  }
  if (!P.sensitivity.allFinite()) throw InputError("allocation: the sensitivities are not all finite");
  if (!(std::isfinite(P.max_scale) && P.max_scale > 0))
    throw InputError(fmt::format("allocation: the largest scale is {}; it must be > 0", P.max_scale));
  if (P.min_scale.size() != 0 && P.min_scale.size() != ns)
    throw InputError(fmt::format("allocation: {} least scales for {} sources", P.min_scale.size(), ns));
  for (Eigen::Index s = 0; s < P.min_scale.size(); ++s)
    if (!(P.min_scale[s] >= 0 && P.min_scale[s] <= P.max_scale))
      throw InputError(
          fmt::format("allocation: the least scale of source {} is {}; accepted: 0 to the largest "
                      "scale {}",
                      s + 1, P.min_scale[s], P.max_scale));
  if (!(std::isfinite(P.coverage_factor) && P.coverage_factor > 0))
    throw InputError(fmt::format("allocation: the coverage factor is {}; it must be > 0", P.coverage_factor));
}

// The scale m_k of each target's multiplier, and whether the target can be active at all. A target met with
// every tolerance at the largest scale can never be active (x ≤ X), μ_k = 0. Each other target gets the
// scale of its multiplier when alone and no bound is active:
//     x_g = (C_g / (2 μ a_g))^(2/3),  Σ_g a_g x_g = 1  ⇒  μ = (Σ_g a_g^(1/3) (C_g/2)^(2/3))^(3/2).
void multiplier_scales(const Eigen::MatrixXd& a, const Eigen::VectorXd& cost, const Eigen::VectorXd& X,
                       Eigen::VectorXd& m, std::vector<bool>& candidate) {
  const Eigen::Index nt = a.rows(), ng = a.cols();
  candidate.assign(std::size_t(nt), false);
  m = Eigen::VectorXd::Zero(nt);
  for (Eigen::Index k = 0; k < nt; ++k) {
    if (a.row(k).dot(X) <= 1) continue;
    double sum = 0;
    for (Eigen::Index g = 0; g < ng; ++g)
      if (a(k, g) > 0) sum += std::cbrt(a(k, g)) * std::pow(cost[g] / 2, 2.0 / 3.0);
    m[k] = std::pow(sum, 1.5);
    candidate[std::size_t(k)] = m[k] > 0;
  }
}

// The optimum of the normalised problem: x per group, μ per target.
struct GroupOptimum {
  Eigen::VectorXd x, mu;
  double residual = 0, minus_dual = 0;
  int iterations = 0;
  std::string method;
};

// The dual iteration from ν = μ/m = 1 (where every multiplier is of order one); should it fail (it can on
// badly scaled problems), the barrier method on the primal, then the dual iteration from the barrier's
// multipliers; should that fail too, the barrier's own (feasible, near-optimal) point.
GroupOptimum optimise_groups(const Eigen::MatrixXd& a, const Eigen::VectorXd& cost, const Eigen::VectorXd& L,
                             const Eigen::VectorXd& X) {
  const Eigen::Index nt = a.rows();
  const DualProblem dual{a, cost, L, X};
  Eigen::VectorXd m;
  std::vector<bool> candidate;
  multiplier_scales(a, cost, X, m, candidate);
  Eigen::VectorXd start = Eigen::VectorXd::Zero(nt);
  for (Eigen::Index k = 0; k < nt; ++k)
    if (candidate[std::size_t(k)]) start[k] = 1.0;
  DualRun run = run_dual(dual, m, candidate, start, 500);
  GroupOptimum o{run.point.x,          m.cwiseProduct(run.nu), run.residual,
                 run.point.minus_dual, run.iterations,         "dual Newton"};
  if (o.residual <= 1e-12) return o;
  const BarrierResult barrier = solve_barrier(a, cost, L, X, candidate);
  for (Eigen::Index k = 0; k < nt; ++k) start[k] = candidate[std::size_t(k)] ? barrier.mu[k] / m[k] : 0.0;
  run = run_dual(dual, m, candidate, start, 500);
  o.iterations += run.iterations;
  if (run.residual <= 1e-12) {
    o.method = "barrier, then dual Newton";
    o.x = run.point.x;
    o.mu = m.cwiseProduct(run.nu);
    o.residual = run.residual;
    o.minus_dual = run.point.minus_dual;
  } else {
    o.method = "barrier";
    o.x = barrier.y.array().exp().matrix().cwiseMin(X).cwiseMax(L);
    o.mu = barrier.mu;
    o.minus_dual = dual.at(o.mu).minus_dual;
    o.residual = barrier.gap;
  }
  return o;
}

}  // namespace

namespace {

// The optimum over the free groups of `bounds` (the pinned ones at L), rows normalised by their capacity:
// x per group, μ per row of a (of the constraint Σ_g a_kg x_g ≤ 1: μ'_k / capacity_k for the multiplier
// μ'_k of the renormalised row; 0 for a dropped one).
GroupOptimum optimise_bounded(const Eigen::MatrixXd& a, const Eigen::VectorXd& cost,
                              const BoundedRows& bounds) {
  std::vector<Eigen::Index> rows, cols;
  for (Eigen::Index k = 0; k < a.rows(); ++k)
    if (!bounds.dropped[std::size_t(k)]) rows.push_back(k);
  for (Eigen::Index g = 0; g < a.cols(); ++g)
    if (!bounds.pinned[std::size_t(g)]) cols.push_back(g);
  const auto nr = Eigen::Index(rows.size()), nc = Eigen::Index(cols.size());
  Eigen::MatrixXd af(nr, nc);
  Eigen::VectorXd Cf(nc), Lf(nc), Xf(nc);
  for (Eigen::Index j = 0; j < nc; ++j) {
    const Eigen::Index g = cols[std::size_t(j)];
    Cf[j] = cost[g];
    Lf[j] = bounds.L[g];
    Xf[j] = bounds.X[g];
    for (Eigen::Index i = 0; i < nr; ++i)
      af(i, j) = a(rows[std::size_t(i)], g) / bounds.capacity[rows[std::size_t(i)]];
  }
  GroupOptimum f;
  if (nc > 0)
    f = optimise_groups(af, Cf, Lf, Xf);
  else
    f.method = "none (every source at its floor)";
  GroupOptimum o = f;
  o.x = bounds.L;
  for (Eigen::Index j = 0; j < nc; ++j) o.x[cols[std::size_t(j)]] = f.x[j];
  o.mu = Eigen::VectorXd::Zero(a.rows());
  for (Eigen::Index i = 0; i < nr && nc > 0; ++i)
    o.mu[rows[std::size_t(i)]] = f.mu[i] / bounds.capacity[rows[std::size_t(i)]];
  // The pinned groups' cost is a constant of the primal; the dual of the free groups does not have it.
  for (Eigen::Index g = 0; g < a.cols(); ++g)
    if (bounds.pinned[std::size_t(g)]) o.minus_dual -= cost[g] / std::sqrt(bounds.L[g]);
  return o;
}

}  // namespace

AllocationSolution solve_allocation(const AllocationProblem& P) {
  check_problem(P);
  if (P.correlation.size() > 0) return solve_correlated_allocation(P);
  const Eigen::Index nt = P.sensitivity.rows(), ns = P.sensitivity.cols();
  const Groups groups = merge_groups(P.sensitivity, P.standard_uncertainty, P.cost, P.group);
  const Eigen::Index ng = groups.cost.size();
  // a_kg = (k_p c_kg / T_k)²: the normalised constraints Σ_g a_kg x_g ≤ 1.
  Eigen::MatrixXd a(nt, ng);
  for (Eigen::Index k = 0; k < nt; ++k)
    for (Eigen::Index g = 0; g < ng; ++g) {
      const double v = P.coverage_factor * groups.effect(k, g) / P.target[k];
      a(k, g) = v * v;
    }
  const Eigen::VectorXd least =
      P.min_scale.size() ? Eigen::VectorXd(P.min_scale) : Eigen::VectorXd(Eigen::VectorXd::Zero(ns));
  const BoundedRows bounds = bound_rows(a, groups, least, P.max_scale);
  AllocationSolution sol;
  sol.unreachable = bounds.unreachable;
  sol.least_expanded = P.target.cwiseProduct(bounds.at_floor.cwiseSqrt());
  if (std::find(sol.unreachable.begin(), sol.unreachable.end(), true) != sol.unreachable.end()) {
    sol.method = "none (a target cannot be met with every source at its floor)";
    return sol;
  }
  const GroupOptimum o = optimise_bounded(a, groups.cost, bounds);
  sol.iterations = o.iterations;
  sol.method = o.method;
  sol.converged = o.residual <= 1e-12 || (sol.method == "barrier" && o.residual <= 1e-9);
  Eigen::VectorXd x = o.x;

  // The primal solution; scaled onto the feasible set should round-off leave a constraint above 1 (not
  // below the floors: a scaled x stays within 1e-12 of them).
  const double primal_before = (groups.cost.array() / x.array().sqrt()).sum();
  sol.dual_gap = primal_before + o.minus_dual;
  double worst = 0;
  for (Eigen::Index k = 0; k < nt; ++k) worst = std::max(worst, a.row(k).dot(x));
  if (worst > 1 + 1e-12) x = (x / worst).cwiseMax(bounds.L);

  sol.multiplier = o.mu;
  sol.scale.resize(ns);
  for (Eigen::Index s = 0; s < ns; ++s) sol.scale[s] = std::sqrt(x[groups.of[std::size_t(s)]]);
  sol.objective = (P.cost.array() / sol.scale.array()).sum();
  Eigen::VectorXd allocated(nt), configured(nt);
  for (Eigen::Index k = 0; k < nt; ++k) {  // each row as before (a dot product, a row sum): the same bits
    allocated[k] = a.row(k).dot(x);
    configured[k] = a.row(k).sum();
  }
  state_rows(P, allocated, configured, sol);
  return sol;
}

void state_rows(const AllocationProblem& P, const Eigen::VectorXd& allocated,
                const Eigen::VectorXd& configured, AllocationSolution& sol) {
  const Eigen::Index nt = P.target.size();
  sol.expanded.resize(nt);
  sol.configured_expanded.resize(nt);
  sol.active.assign(std::size_t(nt), false);
  double common = P.max_scale;
  for (Eigen::Index k = 0; k < nt; ++k) {
    sol.expanded[k] = P.target[k] * std::sqrt(std::max(allocated[k], 0.0));
    sol.configured_expanded[k] = P.target[k] * std::sqrt(std::max(configured[k], 0.0));
    sol.active[std::size_t(k)] = 1 - allocated[k] <= 1e-9;
    if (sol.configured_expanded[k] > 0) common = std::min(common, P.target[k] / sol.configured_expanded[k]);
  }
  sol.common_scale = common;
  sol.common_objective = P.cost.sum() / common;
  sol.common_expanded = common * sol.configured_expanded;
}

}  // namespace ccal
