// The weighted least-squares path with terms held fixed, against closed forms written here: the fixed
// terms' contribution H_fixed·k is subtracted from y before the weighted solve,
//     x = (Hᵀ W H)⁻¹ Hᵀ W (y − H_fixed k),   Cov = (Hᵀ W H)⁻¹,
// which for a single free constant is the weighted mean of y − H_fixed k with variance 1/Σw.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "ccal/reduction/fit.hpp"

namespace {

using ccal::FitProblem;
using Eigen::MatrixXd;
using Eigen::VectorXd;

TEST(WeightedFit, FixedSlopeGivesTheWeightedMeanOfTheRest) {
  // y = a + b t with b held at 3: â = Σ w (y − 3 t) / Σ w, var(â) = 1/Σ w. Small integers and binary
  // fractions: exact up to a few ulps (tolerance 1e-13). Leaving the fixed term in y would give
  // Σ w y / Σ w, larger by 3 Σ w t / Σ w = 7.3.
  VectorXd t(5), y(5), w(5);
  t << 0, 1, 2, 3, 4;
  y << 2.5, 4.75, 8.25, 11.0, 13.5;
  w << 1.0, 4.0, 0.5, 2.0, 0.25;
  const MatrixXd h = ccal::polynomial_design(t, 1);
  FitProblem p{ccal::polynomial_term_names(1), h, y, w, {{"K1", 3.0}}, {}};
  const ccal::FitResult r = ccal::fit(p);
  ASSERT_EQ(r.value.size(), 1);
  const double sw = w.sum();
  double swr = 0;
  for (int i = 0; i < 5; ++i) swr += w(i) * (y(i) - 3.0 * t(i));
  EXPECT_NEAR(r.value(0), swr / sw, 1e-13);
  EXPECT_NEAR(r.covariance(0, 0), 1.0 / sw, 1e-15);
  // Residuals in the units of y, fixed term included: y − â − 3 t.
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(r.residuals(i), y(i) - swr / sw - 3.0 * t(i), 1e-13) << i;
  // χ² = Σ w r².
  double chi2 = 0;
  for (int i = 0; i < 5; ++i) chi2 += w(i) * std::pow(y(i) - swr / sw - 3.0 * t(i), 2);
  EXPECT_NEAR(r.chi2, chi2, 1e-12 * chi2);
}

TEST(WeightedFit, CalibrationShapedProblemWithK1HeldFixed) {
  // The ccal shape: columns 1, A, A², A³ at A = 5 … 30 g, K1 held fixed at a large value (≈ 8.8 output per g,
  // so the fixed term dominates y), unequal weights. Expected: the normal equations of the reduced problem
  // solved here by LDLᵀ. The scaled design is well conditioned (cond ≈ 1e3 after column scaling), so both
  // routes agree to ~cond·ε·|y|/|H_k|: tolerance 1e-9 relative per coefficient.
  VectorXd A(6);
  A << 5, 10, 15, 20, 25, 30;
  const MatrixXd h = ccal::polynomial_design(A, 3);
  VectorXd truth(4);
  truth << 1.1e-3, 8.8175, 3.5e-4, 5.2e-5;
  VectorXd w(6), bump(6);
  w << 1.0, 3.0, 0.7, 2.0, 5.0, 0.4;
  bump << 1e-4, -2e-4, 0.5e-4, 1.5e-4, -1e-4, 0.3e-4;  // not in the column space: weights matter
  const VectorXd y = h * truth + bump;
  FitProblem p{ccal::polynomial_term_names(3), h, y, w, {{"K1", truth(1)}}, {}};
  const ccal::FitResult r = ccal::fit(p);
  ASSERT_EQ(r.names, (std::vector<std::string>{"K0", "K2", "K3"}));
  MatrixXd hf(6, 3);
  hf << h.col(0), h.col(2), h.col(3);
  const VectorXd reduced = y - h.col(1) * truth(1);
  const MatrixXd normal = hf.transpose() * w.asDiagonal() * hf;
  const VectorXd want = normal.ldlt().solve(hf.transpose() * w.asDiagonal() * reduced);
  const MatrixXd cov = normal.inverse();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(r.value(k), want(k), 1e-9 * std::abs(want(k))) << r.names[std::size_t(k)];
    EXPECT_NEAR(r.covariance(k, k), cov(k, k), 1e-8 * cov(k, k)) << r.names[std::size_t(k)];
  }
}

}  // namespace
