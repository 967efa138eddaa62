// What the logs of a test measured (intake/measured_inputs.hpp): the line fit's rate standard error against its
// closed form, and which inputs a set of logged runs measured, with what uncertainty.
#include "ccal/intake/measured_inputs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ccal/io/config_file.hpp"

namespace ccal::test {
namespace {

TEST(MeasuredInputs, LineRateStandardErrorIsTheLeastSquaresSlopes) {
  // σ_b = s/√Σ(τ − τ̄)² for n samples equally spaced over T, the sum taken here directly (1e-12 relative).
  for (std::size_t n : {3u, 10u, 4501u}) {
    const double T = 450, dt = T / double(n - 1);
    double mean = 0, spread = 0;
    for (std::size_t i = 0; i < n; ++i) mean += double(i) * dt / double(n);
    for (std::size_t i = 0; i < n; ++i) spread += std::pow(double(i) * dt - mean, 2);
    const double s = 1e-7, expected = s / std::sqrt(spread);
    EXPECT_NEAR(line_rate_standard_error(s, n, T, 10.0), expected, 1e-12 * expected) << n;
  }
  // Residuals below the round-off of the rate: the round-off, 1e-16 of the rate.
  EXPECT_EQ(line_rate_standard_error(0.0, 4501, 450, 10.0), 1e-15);
  EXPECT_EQ(line_rate_standard_error(1e-7, 2, 450, 10.0), 1e-15);
}

// A logged run with both encoders and first harmonics, as the reduction would give it.
LoggedRun logged(double rms, double sigma, double c1, double s1) {
  LoggedRun lr;
  lr.measured.mode = PlatformMode::counter_rotating;
  lr.log.samples = 4501;
  lr.log.duration = 450;
  lr.log.has_theta1 = lr.log.has_gamma = true;
  lr.log.theta1_rate = 10;
  lr.log.gamma_rate = -10;
  lr.log.theta1_rms = lr.log.gamma_rms = rms;
  lr.log.theta1_harmonics = lr.log.gamma_harmonics = {c1, s1};
  lr.log.theta1_harmonic_sigma = lr.log.gamma_harmonic_sigma = sigma;
  return lr;
}

TEST(MeasuredInputs, EveryRunMeasuresTheRatesAndTheRippleAtTheWorstRunsUncertainty) {
  const Config config = bundled_example();  // harmonic order 1, speed control
  LogReduction logs;
  logs.runs = {logged(1e-7, 1e-9, 1e-6, 0), logged(2e-7, 2e-9, 0, 0)};
  const std::vector<MeasuredInput> m = measured_inputs(config, logs);
  ASSERT_EQ(m.size(), 6u);
  const double rate = line_rate_standard_error(2e-7, 4501, 450, 10);  // the worse run's
  EXPECT_EQ(m[0].id, "domega");
  EXPECT_EQ(m[0].standard_uncertainty, rate);
  EXPECT_EQ(m[1].id, "dOmega");
  EXPECT_NEAR(m[1].standard_uncertainty, std::sqrt(2.0) * rate, 1e-15 * rate);
  // ripple1: the first run resolved its harmonic (1e-6 rad ≫ 10σ), the second did not (0 ≤ max(10σ, 1e-10)):
  // the second's k r/√3 with r = 10σ = 2e-8 rad is the larger, and the harmonic counts as not resolved.
  EXPECT_EQ(m[2].id, "ripple1_c1");
  EXPECT_EQ(m[3].id, "ripple1_s1");
  EXPECT_NEAR(m[2].standard_uncertainty, 2e-8 / std::sqrt(3.0), 1e-22);
  EXPECT_FALSE(m[2].resolved);
  EXPECT_EQ(m[4].id, "ripple3_c1");
  EXPECT_EQ(m[5].id, "ripple3_s1");

  // Resolved in every run: k σ of the worse run.
  logs.runs = {logged(1e-7, 1e-9, 1e-6, 0), logged(1e-7, 2e-9, 0, 1e-6)};
  const std::vector<MeasuredInput> r = measured_inputs(config, logs);
  EXPECT_EQ(r[2].standard_uncertainty, 2e-9);
  EXPECT_TRUE(r[2].resolved);

  // A run without the platform encoder: dOmega and ripple3 keep their tolerances; without the main-axis
  // encoder nothing of the main axis is measured either.
  logs.runs[1].log.has_gamma = false;
  logs.runs[1].log.gamma_harmonics.clear();
  std::vector<std::string> ids;
  for (const MeasuredInput& x : measured_inputs(config, logs)) ids.push_back(x.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"domega", "ripple1_c1", "ripple1_s1"}));
  logs.runs[1].log.has_theta1 = false;
  logs.runs[1].log.theta1_harmonics.clear();
  EXPECT_TRUE(measured_inputs(config, logs).empty());
}

TEST(MeasuredInputs, DeclaredEncodersAreExpectedToMeasureAtTheirFitsResolution) {
  // [centrifuge] encoders: before a test, what its logs will measure, each at the resolution floor of its fit
  // (rates 1e-10 rad over the shortest run, 450 s; ripple k·1e-10/√3, not resolved).
  Config config = bundled_example();
  EXPECT_TRUE(expected_measured_inputs(config).empty());
  config.centrifuge.encoders.main = true;
  std::vector<std::string> ids;
  for (const MeasuredInput& m : expected_measured_inputs(config)) ids.push_back(m.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"domega", "ripple1_c1", "ripple1_s1"}));
  config.centrifuge.encoders.platform = true;
  const std::vector<MeasuredInput> both = expected_measured_inputs(config);
  ASSERT_EQ(both.size(), 6u);
  EXPECT_EQ(both[0].standard_uncertainty, kRippleResolutionFloor / 450);
  EXPECT_EQ(both[1].id, "dOmega");
  EXPECT_NEAR(both[1].standard_uncertainty, std::sqrt(2.0) * kRippleResolutionFloor / 450, 1e-27);
  EXPECT_EQ(both[5].id, "ripple3_s1");
  EXPECT_EQ(both[5].standard_uncertainty, kRippleResolutionFloor / std::sqrt(3.0));
  EXPECT_FALSE(both[5].resolved);
  // A fixed platform does not turn against the main axis: no mismatch, no platform ripple to measure.
  for (ccal::Run& run : config.plan.runs) run.mode = PlatformMode::fixed;
  ids.clear();
  for (const MeasuredInput& m : expected_measured_inputs(config)) ids.push_back(m.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"domega", "ripple1_c1", "ripple1_s1"}));
}

}  // namespace
}  // namespace ccal::test
