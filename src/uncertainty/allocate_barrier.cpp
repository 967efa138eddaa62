// The barrier method on the allocation's primal (allocation_groups.hpp, docs/model.md §10.3).
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "allocation_groups.hpp"

namespace ccal {
namespace {

// A strictly feasible start of the barrier: every y one below its upper bound, then all lowered until every
// h_r ≤ −1 (a common shift of y shifts every h_r by the same amount); where that crosses a lower bound,
// x = L + θ (X − L) with θ half the largest value that keeps every used row below 1 (at most 1/2), which
// exists when every row holds strictly with every group at L.
Eigen::VectorXd barrier_start(const Eigen::MatrixXd& a, const Eigen::VectorXd& L, const Eigen::VectorXd& X,
                              const std::vector<Eigen::Index>& rows) {
  const Eigen::Index ng = L.size();
  Eigen::VectorXd y = X.array().log().matrix() - Eigen::VectorXd::Ones(ng);
  double worst = 0;
  for (const Eigen::Index k : rows) worst = std::max(worst, a.row(k).dot(y.array().exp().matrix()));
  if (worst > 0 && std::log(worst) > -1) y.array() -= std::log(worst) + 1;
  if ((y.array().exp() > L.array()).all()) return y;
  double theta = 0.5;
  for (const Eigen::Index k : rows) {
    const double at_floor = a.row(k).dot(L), span = a.row(k).dot(X - L);
    if (span > 0) theta = std::min(theta, 0.5 * (1 - at_floor) / span);
  }
  return (L + theta * (X - L)).array().log().matrix();
}

}  // namespace

BarrierResult solve_barrier(const Eigen::MatrixXd& a, const Eigen::VectorXd& C, const Eigen::VectorXd& L,
                            const Eigen::VectorXd& X, const std::vector<bool>& use) {
  const Eigen::Index ng = C.size();
  std::vector<Eigen::Index> rows;
  for (Eigen::Index k = 0; k < a.rows(); ++k)
    if (use[std::size_t(k)]) rows.push_back(k);
  const auto nr = Eigen::Index(rows.size());
  const double inf = std::numeric_limits<double>::infinity();
  const Eigen::VectorXd Y = X.array().log().matrix();
  const Eigen::VectorXd lowest = L.array().log().matrix();  // −∞ where L_g = 0: no lower bound
  Eigen::MatrixXd la(nr, ng);
  for (Eigen::Index r = 0; r < nr; ++r)
    for (Eigen::Index g = 0; g < ng; ++g) {
      const double v = a(rows[std::size_t(r)], g);
      la(r, g) = v > 0 ? std::log(v) : -inf;
    }
  // h_r(y) by log-sum-exp, and its gradient π (a probability vector).
  auto constraint = [&](const Eigen::VectorXd& y, Eigen::Index r, Eigen::VectorXd* pi) {
    double top = -inf;
    for (Eigen::Index g = 0; g < ng; ++g) top = std::max(top, la(r, g) + y[g]);
    double sum = 0;
    for (Eigen::Index g = 0; g < ng; ++g) sum += std::exp(la(r, g) + y[g] - top);
    const double h = top + std::log(sum);
    if (pi) {
      pi->resize(ng);
      for (Eigen::Index g = 0; g < ng; ++g) (*pi)[g] = std::exp(la(r, g) + y[g] - h);
    }
    return h;
  };
  auto objective = [&](const Eigen::VectorXd& y) { return (C.array() * (-0.5 * y.array()).exp()).sum(); };
  // t F − Σ ln(−h_r) − Σ ln(Y_g − y_g) − Σ ln(y_g − ln L_g), +∞ outside the domain.
  auto value = [&](const Eigen::VectorXd& y, double t) {
    double v = t * objective(y);
    for (Eigen::Index g = 0; g < ng; ++g) {
      if (!(y[g] < Y[g] && y[g] > lowest[g])) return inf;
      v -= std::log(Y[g] - y[g]);
      if (L[g] > 0) v -= std::log(y[g] - lowest[g]);
    }
    for (Eigen::Index r = 0; r < nr; ++r) {
      const double h = constraint(y, r, nullptr);
      if (!(h < 0)) return inf;
      v -= std::log(-h);
    }
    return v;
  };

  BarrierResult res;
  Eigen::VectorXd y = barrier_start(a, L, X, rows);
  const double m = double(nr + ng + (L.array() > 0).count());
  double t = m / objective(y);
  Eigen::VectorXd grad(ng), pi;
  Eigen::MatrixXd H(ng, ng);
  for (int outer = 0; outer < 100; ++outer) {
    for (int inner = 0; inner < 200; ++inner) {
      const Eigen::ArrayXd e = (-0.5 * y.array()).exp() * C.array();
      grad = -0.5 * t * e.matrix();
      H = (0.25 * t * e).matrix().asDiagonal();
      for (Eigen::Index g = 0; g < ng; ++g) {
        const double d = Y[g] - y[g];
        grad[g] += 1 / d;
        H(g, g) += 1 / (d * d);
        if (L[g] > 0) {
          const double e = y[g] - lowest[g];
          grad[g] -= 1 / e;
          H(g, g) += 1 / (e * e);
        }
      }
      for (Eigen::Index r = 0; r < nr; ++r) {
        const double h = constraint(y, r, &pi);
        grad += pi / -h;
        H.diagonal() += pi / -h;
        H.noalias() += (1 / (h * h) - 1 / -h) * pi * pi.transpose();
      }
      const Eigen::VectorXd dy = -Eigen::LDLT<Eigen::MatrixXd>(H).solve(grad);
      const double decrement = -grad.dot(dy);
      if (!dy.allFinite() || !(decrement > 2e-12)) break;
      const double v0 = value(y, t);
      double step = 1;
      while (step > 1e-14 && !(value(y + step * dy, t) <= v0 - 0.01 * step * decrement)) step *= 0.5;
      if (step <= 1e-14) break;
      y += step * dy;
    }
    res.gap = m / t / objective(y);
    if (res.gap <= 1e-10) break;
    t *= 20;
  }
  res.y = y;
  res.mu = Eigen::VectorXd::Zero(a.rows());
  for (Eigen::Index r = 0; r < nr; ++r) res.mu[rows[std::size_t(r)]] = 1 / (t * -constraint(y, r, nullptr));
  return res;
}

}  // namespace ccal
