// The differentiable least-squares solve (solve_least_squares) in double and through Eigen's AutoDiff.
#include "fit_test_support.hpp"

namespace {

using namespace ccal::fit_test;

// ---------------------------------------------------------------------------------------------------
// 7. Differentiable solve.

// A design with a parameter q in H and a parameter p in y:
//   H_i = [1, t_i, t_i^2 + q t_i^3],  y_i = sin(p t_i) + 0.3 t_i.
template <class Scalar>
void build(const Scalar& p, const Scalar& q, Eigen::Matrix<Scalar, -1, -1>& h,
           Eigen::Matrix<Scalar, -1, 1>& y) {
  const int n = 12;
  h.resize(n, 3);
  y.resize(n);
  for (int i = 0; i < n; ++i) {
    const double t = -1.0 + 2.0 * i / (n - 1);
    using std::sin;
    h(i, 0) = Scalar(1.0);
    h(i, 1) = Scalar(t);
    h(i, 2) = t * t + q * (t * t * t);
    y(i) = sin(p * t) + Scalar(0.3 * t);
  }
}

TEST(SolveLeastSquares, DoubleMatchesFit) {
  MatrixXd h;
  VectorXd y;
  build(0.8, 0.4, h, y);
  const VectorXd direct = ccal::solve_least_squares(h, y);
  const FitResult r = ccal::fit(FitProblem{names_of(3), h, y, {}, {}, {}});
  // Two backward-stable solvers on a condition ~10 problem: agreement to ~1e-15; 1e-12 relative.
  EXPECT_LT(relative_error(direct, r.value), 1e-12);
}

TEST(SolveLeastSquares, AutoDiffDerivativesMatchCentralDifferences) {
  using Derivatives = Eigen::Vector2d;  // d/dp, d/dq
  using AD = Eigen::AutoDiffScalar<Derivatives>;
  const double p0 = 0.8, q0 = 0.4;
  const AD p(p0, 2, 0), q(q0, 2, 1);
  Eigen::Matrix<AD, -1, -1> h;
  Eigen::Matrix<AD, -1, 1> y;
  build(p, q, h, y);
  const Eigen::Matrix<AD, -1, 1> b = ccal::solve_least_squares(h, y);

  const auto solve_at = [](double pp, double qq) {
    MatrixXd hd;
    VectorXd yd;
    build(pp, qq, hd, yd);
    return VectorXd(ccal::solve_least_squares(hd, yd));
  };
  // Central differences with step 1e-5: truncation error ~ h^2 |b'''| / 6 ~ 1e-11 and rounding error
  // ~ eps |b| / h ~ 1e-11, so the two derivatives should agree to ~1e-10; tolerance 1e-8 absolute
  // (coefficients and derivatives are of order 1).
  const double step = 1e-5;
  const VectorXd db_dp = (solve_at(p0 + step, q0) - solve_at(p0 - step, q0)) / (2 * step);
  const VectorXd db_dq = (solve_at(p0, q0 + step) - solve_at(p0, q0 - step)) / (2 * step);
  const VectorXd b0 = solve_at(p0, q0);
  for (Eigen::Index k = 0; k < 3; ++k) {
    EXPECT_NEAR(b(k).value(), b0(k), 1e-14 * std::max(1.0, std::abs(b0(k))));  // same arithmetic on values
    EXPECT_NEAR(b(k).derivatives()(0), db_dp(k), 1e-8) << "d b" << k << " / dp";
    EXPECT_NEAR(b(k).derivatives()(1), db_dq(k), 1e-8) << "d b" << k << " / dq";
  }
  // The parameter in y only enters linearly through y: d b / dp = H^+ dy/dp exactly; cross-check with
  // the double solver on dy/dp (same algorithm, so agreement to rounding, 1e-12).
  MatrixXd hd;
  VectorXd yd;
  build(p0, q0, hd, yd);
  VectorXd dy_dp(12);
  for (int i = 0; i < 12; ++i) {
    const double t = -1.0 + 2.0 * i / 11;
    dy_dp(i) = t * std::cos(p0 * t);
  }
  const VectorXd exact_db_dp = ccal::solve_least_squares(hd, dy_dp);
  for (Eigen::Index k = 0; k < 3; ++k) EXPECT_NEAR(b(k).derivatives()(0), exact_db_dp(k), 1e-12);
}

TEST(SolveLeastSquares, DynamicDerivativeVectorWorks) {
  using AD = Eigen::AutoDiffScalar<VectorXd>;
  const AD p(0.8, 2, 0), q(0.4, 2, 1);
  Eigen::Matrix<AD, -1, -1> h;
  Eigen::Matrix<AD, -1, 1> y;
  build(p, q, h, y);
  const Eigen::Matrix<AD, -1, 1> b = ccal::solve_least_squares(h, y);
  using Fixed = Eigen::AutoDiffScalar<Eigen::Vector2d>;
  Eigen::Matrix<Fixed, -1, -1> hf;
  Eigen::Matrix<Fixed, -1, 1> yf;
  build(Fixed(0.8, 2, 0), Fixed(0.4, 2, 1), hf, yf);
  const Eigen::Matrix<Fixed, -1, 1> bf = ccal::solve_least_squares(hf, yf);
  for (Eigen::Index k = 0; k < 3; ++k) {
    ASSERT_EQ(b(k).derivatives().size(), 2);
    // Same operations in the same order, only the derivative storage differs: agreement to rounding.
    EXPECT_NEAR(b(k).derivatives()(0), bf(k).derivatives()(0), 1e-12);
    EXPECT_NEAR(b(k).derivatives()(1), bf(k).derivatives()(1), 1e-12);
  }
}

TEST(SolveLeastSquares, RefusesUnderdeterminedAndDependent) {
  EXPECT_THROW(ccal::solve_least_squares(MatrixXd(MatrixXd::Ones(2, 3)), VectorXd(VectorXd::Ones(2))),
               IllPosedFit);
  MatrixXd h = random_design(6, 2, 3);
  h.col(1) = h.col(0);
  EXPECT_THROW(ccal::solve_least_squares(h, VectorXd(VectorXd::Ones(6))), IllPosedFit);
}

}  // namespace
