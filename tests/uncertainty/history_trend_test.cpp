// Drift and agreement over an instrument's calibrations (uncertainty/history_trend.hpp) against hand
// computations: E_n of successive calibrations, the weighted straight line of a known drift, its prediction;
// with a covariance shared between calibrations, E_n with it taken out and the generalised least-squares line
// against the closed forms.
#include "ccal/uncertainty/history_trend.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <stdexcept>

namespace ccal {
namespace {

TEST(HistoryTrend, NormalisedErrorsOfSuccessiveCalibrations) {
  // E_n = (x₂ − x₁)/√(U₁² + U₂²): (10.3 − 10)/√(0.2² + 0.2²) = 1.0607 (disagree), (10.2 − 10.3)/√(0.2² +
  // 0.3²) = −0.2774; to round-off: x₂ − x₁ of two values near 10 carries ~10 ε, so 1e-14.
  const std::vector<HistoryPoint> p = {{0, 10.0, 0.2, 2}, {1, 10.3, 0.2, 2}, {2, 10.2, 0.3, 2}};
  const auto e = normalised_errors(p);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_NEAR(e[0].value, 0.3 / std::sqrt(0.08), 1e-14);
  EXPECT_TRUE(e[0].disagree);
  EXPECT_NEAR(e[1].value, -0.1 / std::sqrt(0.13), 1e-14);
  EXPECT_FALSE(e[1].disagree);
  EXPECT_EQ(e[1].from, 1u);
  EXPECT_EQ(e[1].to, 2u);
}

TEST(HistoryTrend, TheLineOfAnExactDriftAndItsUncertainty) {
  // x = 5 + 0.25 t exactly at t = 0, 1, 3 with u = 0.1, 0.1, 0.2 (U = 2u): the fit returns the line exactly,
  // χ² = 0. By hand: w = 100, 100, 25; Σw = 225, t̄ = (0 + 100 + 75)/225 = 7/9; S = Σ w (t − t̄)² = 100·(49/81)
  // + 100·(4/81) + 25·(400/81) = 15300/81 = 188.89; u(b) = 1/√S = 0.072761; u(a) = 1/15.
  const std::vector<HistoryPoint> p = {{0, 5.0, 0.2, 2}, {1, 5.25, 0.2, 2}, {3, 5.75, 0.4, 2}};
  const DriftLine line = drift_line(p);
  ASSERT_TRUE(line.available);
  EXPECT_NEAR(line.reference_years, 7.0 / 9.0, 1e-15);
  EXPECT_NEAR(line.slope, 0.25, 1e-14);
  EXPECT_NEAR(line.value, 5 + 0.25 * 7.0 / 9.0, 1e-14);
  EXPECT_NEAR(line.std_slope, 1 / std::sqrt(15300.0 / 81.0), 1e-15);
  EXPECT_NEAR(line.std_value, 1.0 / 15.0, 1e-15);
  EXPECT_NEAR(line.chi_squared, 0, 1e-20);
  EXPECT_EQ(line.dof, 1);
  const DriftPrediction at5 = predict(line, 5);
  EXPECT_NEAR(at5.value, 6.25, 1e-14);
  EXPECT_NEAR(at5.std_uncertainty, std::hypot(1.0 / 15.0, (5 - 7.0 / 9.0) / std::sqrt(15300.0 / 81.0)),
              1e-15);
}

TEST(HistoryTrend, ASimulatedDriftIsFoundWithinItsUncertainty) {
  // Ten sets of five yearly calibrations of a drift of 0.03 per year with u = 0.01: the slope's error over
  // its stated u(b) is standard normal; each within 4 (a 1-in-16 000 chance for any of the ten to fail by
  // chance).
  std::mt19937 rng(31);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int set = 0; set < 10; ++set) {
    std::vector<HistoryPoint> p;
    for (int year = 0; year < 5; ++year) p.push_back({double(year), 1.0 + 0.03 * year + noise(rng), 0.02, 2});
    const DriftLine line = drift_line(p);
    ASSERT_TRUE(line.available);
    EXPECT_LT(std::abs(line.slope - 0.03), 4 * line.std_slope) << set;
    EXPECT_NEAR(line.std_slope, 0.01 / std::sqrt(10.0), 1e-15);  // S = Σ (t − 2)²/u² = 10/u²
  }
}

TEST(HistoryTrend, TheBirgeRatioIsTheRootOfChiSquaredPerDegreeOfFreedom) {
  // x = 1.0, 1.3, 1.2 at t = 0, 1, 2 with u = 0.1: by hand t̄ = 1, b = (−1.0 + 1.2)/2 = 0.1, a = 3.5/3;
  // residuals −1/15, 2/15, −1/15, so χ² = (1 + 4 + 1)/225/0.01 = 8/3 with one degree of freedom and
  // R_B = √(8/3) = 1.633 (neither 0 nor 1, so χ²/dof in its place shows); to the round-off of sums near 1.
  const DriftLine line = drift_line({{0, 1.0, 0.2, 2}, {1, 1.3, 0.2, 2}, {2, 1.2, 0.2, 2}});
  ASSERT_TRUE(line.available);
  EXPECT_NEAR(line.slope, 0.1, 1e-14);
  EXPECT_NEAR(line.value, 3.5 / 3, 1e-14);
  EXPECT_NEAR(line.chi_squared, 8.0 / 3, 1e-12);
  EXPECT_EQ(line.dof, 1);
  EXPECT_NEAR(line.birge_ratio, std::sqrt(8.0 / 3), 1e-12);
}

TEST(HistoryTrend, NormalisedErrorAndLineNearTheLargestDouble) {
  // x = ±1e308 with U = 1e308 (k = 2): the difference and U² overflow a double, E_n = −2/√2 = −√2 does not.
  const auto e = normalised_errors({{0, 1e308, 1e308, 2}, {1, -1e308, 1e308, 2}});
  ASSERT_EQ(e.size(), 1u);
  EXPECT_TRUE(e[0].defined);
  EXPECT_NEAR(e[0].value, -std::sqrt(2.0), 1e-15);
  EXPECT_TRUE(e[0].disagree);
  // The line of 1e300 × the exact drift above: 1e300 × its slope and uncertainties (relative 1e-14).
  const DriftLine line = drift_line({{0, 5e300, 0.2e300, 2}, {1, 5.25e300, 0.2e300, 2}, {3, 5.75e300, 0.4e300, 2}});
  ASSERT_TRUE(line.available);
  EXPECT_NEAR(line.slope / 1e300, 0.25, 1e-14);
  EXPECT_NEAR(line.std_value / 1e300, 1.0 / 15.0, 1e-14);
}

TEST(HistoryTrend, NoLineWithoutThreeCalibrationsAtTwoTimes) {
  EXPECT_FALSE(drift_line({{0, 1, 0.1, 2}, {1, 1.1, 0.1, 2}}).available);
  EXPECT_FALSE(drift_line({{1, 1, 0.1, 2}, {1, 1.1, 0.1, 2}, {1, 1.2, 0.1, 2}}).available);
  EXPECT_FALSE(drift_line({{0, 1, 0.1, 2}, {1, 1.1, 0.0, 2}, {2, 1.2, 0.1, 2}}).available);
  EXPECT_THROW(predict(DriftLine{}, 1.0), std::invalid_argument);
  EXPECT_EQ(drift_line({{0, 1, 0.1, 2}, {1, 1.1, 0.1, 2}}).unavailable,
            "needs three calibrations at two dates at least");
}

TEST(HistoryTrend, NormalisedErrorWithASharedCovariance) {
  // x = 10, 10.3 with U = 0.2, 0.3 at k = 2, 2.5 and C = 0.004 shared: E_n = 0.3/√(0.04 + 0.09 −
  // 2·2·2.5·0.004) = 0.3/√0.09 = 1 + round-off (|E_n| > 1 is decided on the same number, so 1e-14 for the
  // value only).
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(2, 2);
  c(0, 1) = c(1, 0) = 0.004;
  c(0, 0) = c(1, 1) = 1e9;  // the diagonal is not read
  const auto e = normalised_errors({{0, 10.0, 0.2, 2}, {1, 10.3, 0.3, 2.5}}, c);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_TRUE(e[0].defined);
  EXPECT_NEAR(e[0].value, 0.3 / std::sqrt(0.04 + 0.09 - 0.04), 1e-14);
  EXPECT_DOUBLE_EQ(e[0].shared_covariance, 0.004);
  // Without it, ISO 13528's 0.3/√0.13.
  EXPECT_NEAR(normalised_errors({{0, 10.0, 0.2, 2}, {1, 10.3, 0.3, 2.5}})[0].value, 0.3 / std::sqrt(0.13),
              1e-14);
}

TEST(HistoryTrend, ADifferenceWithoutUncertaintyHasNoNormalisedError) {
  // U = 0 on both sides, or all of u shared at one k: no E_n (never ±∞ or NaN); the values decide.
  const auto zero = normalised_errors({{0, 1.0, 0, 2}, {1, 1.5, 0, 2}, {2, 1.5, 0, 2}});
  EXPECT_FALSE(zero[0].defined);
  EXPECT_TRUE(zero[0].disagree);
  EXPECT_EQ(zero[0].value, 0.0);
  EXPECT_FALSE(zero[1].defined);
  EXPECT_FALSE(zero[1].disagree);
  Eigen::MatrixXd all = Eigen::MatrixXd::Constant(2, 2, 0.01);  // u = 0.1 each, all of it shared
  const auto shared = normalised_errors({{0, 1.0, 0.2, 2}, {1, 1.0, 0.2, 2}}, all);
  EXPECT_FALSE(shared[0].defined);
  EXPECT_FALSE(shared[0].disagree);
}

TEST(HistoryTrend, ADiagonalCovarianceIsTheWeightedLine) {
  // An explicit zero covariance gives the weighted line's numbers of the test above (w_i = 1/u_i²) to a few
  // ulp: V⁻¹ by a Cholesky factor of a diagonal divides where the weights multiply.
  const std::vector<HistoryPoint> p = {{0, 5.0, 0.2, 2}, {1, 5.3, 0.2, 2}, {3, 5.7, 0.4, 2}};
  const DriftLine zero = drift_line(p, Eigen::MatrixXd::Zero(3, 3)), none = drift_line(p);
  ASSERT_TRUE(zero.available);
  EXPECT_FALSE(zero.correlated);
  // The weighted line by hand: w = 100, 100, 25, Σw = 225, t̄ = 7/9, S = 15300/81, b = Σ w (t − t̄) x / S.
  const double t_bar = 7.0 / 9.0, s = 15300.0 / 81.0;
  const double b = (100 * (0 - t_bar) * 5.0 + 100 * (1 - t_bar) * 5.3 + 25 * (3 - t_bar) * 5.7) / s;
  const double a = (100 * 5.0 + 100 * 5.3 + 25 * 5.7) / 225;
  for (const DriftLine& line : {zero, none}) {
    EXPECT_NEAR(line.slope, b, 1e-14);
    EXPECT_NEAR(line.value, a, 1e-14);
    EXPECT_NEAR(line.std_slope, 1 / std::sqrt(s), 1e-15);
    const double chi2 = std::pow((5.0 - a - b * (0 - t_bar)) / 0.1, 2) +
                        std::pow((5.3 - a - b * (1 - t_bar)) / 0.1, 2) +
                        std::pow((5.7 - a - b * (3 - t_bar)) / 0.2, 2);
    EXPECT_NEAR(line.chi_squared, chi2, 1e-12 * chi2);
  }
}

TEST(HistoryTrend, AFullySharedTypeBLeavesTheSlopeToTheTypeAPart) {
  // u_i² = u_A,i² + s² with all of s² shared (C_ij = s² for i ≠ j): V = D_A + s² 1 1ᵀ, and 1 is a column of
  // X, so the slope and u(b) are those of the Type A part alone, a absorbs the offset: u(a)² = u_A(a)² + s².
  // To round-off of the Cholesky solve of a matrix of condition ~ (s/u_A)² = 100: 1e-12 relative.
  const double s = 0.05;
  const std::vector<double> u_a = {0.005, 0.004, 0.006, 0.005}, t = {0, 1, 2, 3.5},
                            x = {1.0, 1.011, 1.019, 1.032};
  std::vector<HistoryPoint> with_b, only_a;
  for (std::size_t i = 0; i < t.size(); ++i) {
    with_b.push_back({t[i], x[i], 2 * std::hypot(u_a[i], s), 2});
    only_a.push_back({t[i], x[i], 2 * u_a[i], 2});
  }
  const DriftLine shared = drift_line(with_b, Eigen::MatrixXd::Constant(4, 4, s * s)), a = drift_line(only_a);
  const DriftLine independent = drift_line(with_b);
  ASSERT_TRUE(shared.available && a.available);
  EXPECT_TRUE(shared.correlated);
  EXPECT_NEAR(shared.slope, a.slope, 1e-12 * std::abs(a.slope));
  EXPECT_NEAR(shared.std_slope, a.std_slope, 1e-12 * a.std_slope);
  EXPECT_NEAR(shared.chi_squared, a.chi_squared, 1e-10 * a.chi_squared);
  EXPECT_NEAR(shared.std_value, std::hypot(a.std_value, s), 1e-12 * shared.std_value);
  // Charged in full as independent, the same Type B hides the drift: u(b) ten times larger here.
  EXPECT_GT(independent.std_slope, 8 * shared.std_slope);
}

TEST(HistoryTrend, TheGeneralisedLineIsTheTextbookOne) {
  // One pair correlated: b and its variance from (Xᵀ V⁻¹ X)⁻¹ Xᵀ V⁻¹ x with the uncentred X = [1, t], written
  // out with an explicit inverse; the centred fit must give the same slope and u(b) (1e-12 relative: two
  // routes through a well-conditioned 4 × 4).
  const std::vector<HistoryPoint> p = {
      {0, 2.0, 0.02, 2}, {1, 2.03, 0.03, 2}, {2, 2.05, 0.02, 2}, {4, 2.1, 0.04, 2}};
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(4, 4);
  c(1, 2) = c(2, 1) = 0.6 * 0.015 * 0.01;
  Eigen::Matrix4d v = c;  // fixed sizes: no heap temporaries in the textbook formula
  Eigen::Matrix<double, 4, 2> x;
  Eigen::Vector4d y;
  for (int i = 0; i < 4; ++i) {
    const double u = p[std::size_t(i)].expanded / 2;
    v(i, i) = u * u;
    x(i, 0) = 1;
    x(i, 1) = p[std::size_t(i)].years;
    y[i] = p[std::size_t(i)].value;
  }
  const Eigen::Matrix4d vi = v.inverse();
  const Eigen::Matrix2d cov = (x.transpose() * vi * x).inverse();
  const Eigen::Vector2d beta = cov * x.transpose() * vi * y;
  const Eigen::Vector4d r = y - x * beta;
  const double chi2 = r.dot(vi * r);
  const DriftLine line = drift_line(p, c);
  ASSERT_TRUE(line.available);
  EXPECT_NEAR(line.slope, beta[1], 1e-12 * std::abs(beta[1]));
  EXPECT_NEAR(line.std_slope, std::sqrt(cov(1, 1)), 1e-12 * std::sqrt(cov(1, 1)));
  EXPECT_NEAR(line.chi_squared, chi2, 1e-10);
  EXPECT_NEAR(line.birge_ratio, std::sqrt(chi2 / 2), 1e-10);
  // The line at t̄ is β₀ + β₁ t̄, with u(a)² = [1 t̄] cov [1 t̄]ᵀ.
  EXPECT_NEAR(line.value, beta[0] + beta[1] * line.reference_years, 1e-12);
  const Eigen::Vector2d at(1, line.reference_years);
  EXPECT_NEAR(line.std_value, std::sqrt(at.dot(cov * at)), 1e-12);
}

TEST(HistoryTrend, ACovarianceThatIsNotPositiveDefiniteIsSaid) {
  // u = 0.1 each but 0.02 shared: more than either holds; no line, and why.
  const DriftLine line =
      drift_line({{0, 1, 0.2, 2}, {1, 1.1, 0.2, 2}, {2, 1.2, 0.2, 2}}, Eigen::MatrixXd::Constant(3, 3, 0.02));
  EXPECT_FALSE(line.available);
  EXPECT_NE(line.unavailable.find("not positive definite"), std::string::npos) << line.unavailable;
}

}  // namespace
}  // namespace ccal
