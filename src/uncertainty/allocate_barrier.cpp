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

// The barrier's problem in y = ln x: the used rows' log-coefficients la(r, g) (−∞ where a is 0), the upper
// bounds Y = ln X and the lower ones ln L (−∞ where L_g = 0: no lower bound).
struct BarrierProblem {
  const Eigen::VectorXd &C, &L;
  std::vector<Eigen::Index> rows;
  Eigen::VectorXd Y, lowest;
  Eigen::MatrixXd la;

  BarrierProblem(const Eigen::MatrixXd& a, const Eigen::VectorXd& C_, const Eigen::VectorXd& L_,
                 const Eigen::VectorXd& X, const std::vector<bool>& use)
      : C(C_), L(L_), Y(X.array().log().matrix()), lowest(L_.array().log().matrix()) {
    const double inf = std::numeric_limits<double>::infinity();
    for (Eigen::Index k = 0; k < a.rows(); ++k)
      if (use[std::size_t(k)]) rows.push_back(k);
    la.resize(Eigen::Index(rows.size()), C.size());
    for (Eigen::Index r = 0; r < la.rows(); ++r)
      for (Eigen::Index g = 0; g < la.cols(); ++g) {
        const double v = a(rows[std::size_t(r)], g);
        la(r, g) = v > 0 ? std::log(v) : -inf;
      }
  }
  Eigen::Index groups() const { return C.size(); }
  Eigen::Index used_rows() const { return la.rows(); }
  // h_r(y) by log-sum-exp, and its gradient π (a probability vector).
  double constraint(const Eigen::VectorXd& y, Eigen::Index r, Eigen::VectorXd* pi) const {
    const Eigen::Index ng = groups();
    double top = -std::numeric_limits<double>::infinity();
    for (Eigen::Index g = 0; g < ng; ++g) top = std::max(top, la(r, g) + y[g]);
    double sum = 0;
    for (Eigen::Index g = 0; g < ng; ++g) sum += std::exp(la(r, g) + y[g] - top);
    const double h = top + std::log(sum);
    if (pi) {
      pi->resize(ng);
      for (Eigen::Index g = 0; g < ng; ++g) (*pi)[g] = std::exp(la(r, g) + y[g] - h);
    }
    return h;
  }
  double objective(const Eigen::VectorXd& y) const { return (C.array() * (-0.5 * y.array()).exp()).sum(); }
  // t F − Σ ln(−h_r) − Σ ln(Y_g − y_g) − Σ ln(y_g − ln L_g), +∞ outside the domain.
  double value(const Eigen::VectorXd& y, double t) const {
    const double inf = std::numeric_limits<double>::infinity();
    double v = t * objective(y);
    for (Eigen::Index g = 0; g < groups(); ++g) {
      if (!(y[g] < Y[g] && y[g] > lowest[g])) return inf;
      v -= std::log(Y[g] - y[g]);
      if (L[g] > 0) v -= std::log(y[g] - lowest[g]);
    }
    for (Eigen::Index r = 0; r < used_rows(); ++r) {
      const double h = constraint(y, r, nullptr);
      if (!(h < 0)) return inf;
      v -= std::log(-h);
    }
    return v;
  }
};

// The barrier function's gradient and Hessian at y for the weight t of the objective.
void newton_system(const BarrierProblem& b, const Eigen::VectorXd& y, double t, Eigen::VectorXd& grad,
                   Eigen::MatrixXd& H) {
  const Eigen::ArrayXd e = (-0.5 * y.array()).exp() * b.C.array();
  grad = -0.5 * t * e.matrix();
  H = (0.25 * t * e).matrix().asDiagonal();
  for (Eigen::Index g = 0; g < b.groups(); ++g) {
    const double d = b.Y[g] - y[g];
    grad[g] += 1 / d;
    H(g, g) += 1 / (d * d);
    if (b.L[g] > 0) {
      const double lower = y[g] - b.lowest[g];
      grad[g] -= 1 / lower;
      H(g, g) += 1 / (lower * lower);
    }
  }
  Eigen::VectorXd pi;
  for (Eigen::Index r = 0; r < b.used_rows(); ++r) {
    const double h = b.constraint(y, r, &pi);
    grad += pi / -h;
    H.diagonal() += pi / -h;
    H.noalias() += (1 / (h * h) - 1 / -h) * pi * pi.transpose();
  }
}

// Newton's method with a backtracking line search on the barrier function at weight t (at most 200 steps,
// until the Newton decrement falls to 2e-12 or no step lowers the function).
void newton_centre(const BarrierProblem& b, double t, Eigen::VectorXd& y) {
  Eigen::VectorXd grad(b.groups());
  Eigen::MatrixXd H(b.groups(), b.groups());
  for (int inner = 0; inner < 200; ++inner) {
    newton_system(b, y, t, grad, H);
    const Eigen::VectorXd dy = -Eigen::LDLT<Eigen::MatrixXd>(H).solve(grad);
    const double decrement = -grad.dot(dy);
    if (!dy.allFinite() || !(decrement > 2e-12)) return;
    const double v0 = b.value(y, t);
    double step = 1;
    while (step > 1e-14 && !(b.value(y + step * dy, t) <= v0 - 0.01 * step * decrement)) step *= 0.5;
    if (step <= 1e-14) return;
    y += step * dy;
  }
}

}  // namespace

BarrierResult solve_barrier(const Eigen::MatrixXd& a, const Eigen::VectorXd& C, const Eigen::VectorXd& L,
                            const Eigen::VectorXd& X, const std::vector<bool>& use) {
  const BarrierProblem b(a, C, L, X, use);
  BarrierResult res;
  Eigen::VectorXd y = barrier_start(a, L, X, b.rows);
  const double m = double(b.used_rows() + b.groups() + (L.array() > 0).count());
  double t = m / b.objective(y);
  for (int outer = 0; outer < 100; ++outer) {
    newton_centre(b, t, y);
    res.gap = m / t / b.objective(y);
    if (res.gap <= 1e-10) break;
    t *= 20;
  }
  res.y = y;
  res.mu = Eigen::VectorXd::Zero(a.rows());
  for (Eigen::Index r = 0; r < b.used_rows(); ++r)
    res.mu[b.rows[std::size_t(r)]] = 1 / (t * -b.constraint(y, r, nullptr));
  return res;
}

}  // namespace ccal
