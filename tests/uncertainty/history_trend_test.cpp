// Drift and agreement over an instrument's calibrations (uncertainty/history_trend.hpp) against hand
// computations: E_n of successive calibrations, the weighted straight line of a known drift, its prediction.
#include "ccal/uncertainty/history_trend.hpp"

#include <gtest/gtest.h>

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

TEST(HistoryTrend, NoLineWithoutThreeCalibrationsAtTwoTimes) {
  EXPECT_FALSE(drift_line({{0, 1, 0.1, 2}, {1, 1.1, 0.1, 2}}).available);
  EXPECT_FALSE(drift_line({{1, 1, 0.1, 2}, {1, 1.1, 0.1, 2}, {1, 1.2, 0.1, 2}}).available);
  EXPECT_FALSE(drift_line({{0, 1, 0.1, 2}, {1, 1.1, 0.0, 2}, {2, 1.2, 0.1, 2}}).available);
  EXPECT_THROW(predict(DriftLine{}, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace ccal
