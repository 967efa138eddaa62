// Reduction of recorded run logs: the mean output of pulse counts and of sampled outputs against closed
// forms, the encoder line fits through wrapped angles, the measured run, and the refusals of bad logs.
#include "ccal/intake/run_log.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "test_constants.hpp"

namespace ccal::test {
namespace {

using ccal::test::kPi;

// A log's CSV text from a header and a row generator over n samples.
template <class Row>
std::string log_text(const std::string& header, int n, Row row) {
  std::string text = "# a recorded run\n" + header + "\n";
  for (int k = 0; k < n; ++k) text += row(k) + "\n";
  return text;
}

TEST(RunLog, PulseCountGivesTheExactMeanAndEncodersTheMotion) {
  // Pulses counted from t = 2 s to 452 s at a mean rate that makes 123456.75 pulses of w = 2e-5 rad: the mean
  // output is ΔP·w/T whatever happens in between. Encoders: θ1 = 0.3 + 8.8 t and γ = 2 − 8.8001 t, written
  // wrapped to [0, 2π) as an encoder gives them, sampled every 0.1 s: the line fits recover rate and phases
  // to round-off of the angles (~1e-12 rad over 4000 rad of travel).
  const double w = 2e-5, t0 = 2.0, T = 450.0, n_pulses = 123456.75;
  const int n = 4501;
  auto wrap = [](double a) { return std::fmod(std::fmod(a, 2 * kPi) + 2 * kPi, 2 * kPi); };
  const std::string text = log_text("time,pulses,theta1,gamma", n, [&](int k) {
    const double t = t0 + 0.1 * k, s = t - t0;
    // pulses need not grow linearly: only the ends count
    const double p = 1000 + n_pulses * (s / T) + 5 * std::sin(s);
    return fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}", t, p, wrap(0.3 + 8.8 * s), wrap(2.0 - 8.8001 * s));
  });
  RunLogOptions o;
  o.pulse_weight = w;
  const ReducedLog r = reduce_run_log(parse_csv(text, "log.csv"), o, 8.8);
  EXPECT_EQ(r.samples, std::size_t(n));
  EXPECT_TRUE(r.pulses);
  EXPECT_NEAR(r.duration, T, 1e-12);
  EXPECT_NEAR(r.mean_output, (n_pulses + 5 * std::sin(T)) * w / T, 1e-15);
  ASSERT_TRUE(r.has_theta1 && r.has_gamma);
  EXPECT_NEAR(r.theta1_rate, 8.8, 1e-13);
  EXPECT_NEAR(r.theta1_start, 0.3, 1e-10);
  EXPECT_LT(r.theta1_rms, 1e-11);
  EXPECT_NEAR(r.gamma_rate, -8.8001, 1e-13);
  EXPECT_NEAR(r.gamma_start, 2.0, 1e-10);
  EXPECT_NEAR(r.gamma_end, std::fmod(std::fmod(2.0 - 8.8001 * T, 2 * kPi) + 2 * kPi, 2 * kPi), 1e-9);

  ccal::Run planned;
  planned.name = "20g";
  planned.g_level = 20;
  planned.duration = 500;
  planned.terminal_phase = kPi;
  const Geometry geometry{2.5, 0, 0, 0};
  Site site;
  site.g = 9.8;
  const ccal::Run measured = measured_run(planned, r, geometry, site);
  EXPECT_NEAR(measured.duration, T, 1e-12);
  EXPECT_NEAR(nominal_rate(measured, geometry, site), 8.8, 1e-13);  // the measured rate, through A
  EXPECT_NEAR(measured.arm_azimuth, 0.3, 1e-10);
  ASSERT_TRUE(measured.initial_phase.has_value());
  EXPECT_NEAR(*measured.initial_phase, 2.0, 1e-10);
  EXPECT_FALSE(measured.terminal_phase.has_value());
  EXPECT_NEAR(measured_platform_mismatch(planned, r), 8.8001 - 8.8, 1e-12);
}

TEST(RunLog, SampledOutputByTheTrapezoidRule) {
  // output = 3 + 2 cos(2π t / 1 s) + 0.5 sin(6π t) in deg/s, 16 samples per period over 100 whole periods:
  // the trapezoid rule integrates the harmonics exactly (below the Nyquist order 8), so the mean is 3 deg/s
  // to round-off.
  const int n = 1601;
  const std::string text = log_text("output,time", n, [&](int k) {
    const double t = k / 16.0;
    return fmt::format("{:.17g},{:.17g}", 3 + 2 * std::cos(2 * kPi * t) + 0.5 * std::sin(6 * kPi * t), t);
  });
  RunLogOptions o;
  o.output_scale = kPi / 180;
  const ReducedLog r = reduce_run_log(parse_csv(text, "log.csv"), o, 8.8);
  EXPECT_FALSE(r.pulses);
  EXPECT_FALSE(r.has_theta1 || r.has_gamma);
  EXPECT_NEAR(r.mean_output, 3 * kPi / 180, 1e-15);
  EXPECT_NEAR(r.duration, 100.0, 0);
}

// The CsvError of reducing `text`, with its line (0: the header's) and its message.
CsvError reduction_error(const std::string& text, RunLogOptions o = {}) {
  if (o.pulse_weight == 0) o.pulse_weight = 1e-5;
  try {
    reduce_run_log(parse_csv(text, "bad.csv"), o, 8.8);
  } catch (const CsvError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return CsvError("", 0, 0, "", "");
}

TEST(RunLog, RefusesBadLogsWithTheirPlace) {
  EXPECT_NE(std::string(reduction_error("time,pulses\n0,1\n").what()).find("at least two"),
            std::string::npos);
  {
    const CsvError e = reduction_error("time,pulses\n0,1\n1,2\n1,3\n");
    EXPECT_EQ(e.line(), 4);
    EXPECT_EQ(e.item(), "time");
    EXPECT_NE(e.problem().find("strictly increasing"), std::string::npos);
  }
  EXPECT_NE(std::string(reduction_error("time,pulses,output\n0,1,1\n1,2,1\n").what()).find("exactly one"),
            std::string::npos);
  EXPECT_NE(std::string(reduction_error("time,count\n0,1\n1,2\n").what()).find("no output column"),
            std::string::npos);
  {
    RunLogOptions no_weight;
    no_weight.pulse_weight = -1;
    EXPECT_NE(std::string(reduction_error("time,pulses\n0,1\n1,2\n", no_weight).what()).find("pulse weight"),
              std::string::npos);
  }
  {
    // 0.5 s between samples at 8.8 rad/s is 4.4 rad: the unwrapping would alias
    const CsvError e = reduction_error("time,pulses,theta1\n0,1,0\n0.1,2,0.88\n0.6,3,5.28\n");
    EXPECT_EQ(e.line(), 4);
    EXPECT_EQ(e.item(), "theta1");
  }
  {
    const CsvError e = reduction_error("time,pulses\n0,1\n1,x\n");
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.item(), "pulses");
  }
}

TEST(RunLog, AWildEncoderReadingIsRefusedWithItsLine) {
  // θ1 = 8.8 t + 1e-3 sin 3θ (a ripple a hundred times any machine's), every 0.1 s, wrapped to [0, 2π): a
  // reading departs from the line through the two before it by at most 4·1e-3 (the second difference of the
  // ripple), under the 0.01 rad limit, so the log is accepted. One reading moved by d (line 3 + k of the file:
  // after the comment and the header) departs by d plus that curvature: 0.02 rad is refused at its line, the
  // message giving the departure to 3 digits; 1e300 (a lost decimal point, the case) likewise.
  auto text = [](int moved, const std::string& cell) {
    return log_text("time,pulses,theta1", 2001, [&](int k) {
      const double t = 0.1 * k, nominal = 8.8 * t;
      const double angle = std::fmod(nominal + 1e-3 * std::sin(3 * nominal), 2 * kPi);
      return k == moved && !cell.empty() ? fmt::format("{:.17g},{},{}", t, k, cell)
                                         : fmt::format("{:.17g},{},{:.17g}", t, k, angle);
    });
  };
  RunLogOptions o;
  o.pulse_weight = 1e-5;
  EXPECT_NEAR(reduce_run_log(parse_csv(text(-1, ""), "log.csv"), o, 8.8).theta1_rate, 8.8, 1e-6);
  const double t = 0.1 * 700, nominal = 8.8 * t;
  const double moved = std::fmod(nominal + 1e-3 * std::sin(3 * nominal) + 0.02, 2 * kPi);
  for (const std::string& cell : {fmt::format("{:.17g}", moved), std::string("1e300")}) {
    const CsvError e = reduction_error(text(700, cell), o);
    EXPECT_EQ(e.line(), 703) << cell;
    EXPECT_EQ(e.item(), "theta1");
    EXPECT_NE(e.problem().find("from the line through the two readings before it; accepted: within 0.01 rad"),
              std::string::npos)
        << e.problem();
  }
  EXPECT_NE(reduction_error(text(700, fmt::format("{:.17g}", moved)), o).problem().find("departs by 0.02"),
            std::string::npos);
  // An encoder of 1000 counts per revolution: readings floored to counts depart from the line by up to two
  // counts (1.3e-2 rad), above 0.01 rad: the limit is then four counts, and the log is accepted.
  RunLogOptions counts = o;
  counts.angle_scale = counts.angle_quantum = 2 * kPi / 1000;
  const std::string coarse = log_text("time,pulses,theta1", 2001, [](int k) {
    const double t = 0.1 * k;
    return fmt::format("{:.17g},{},{}", t, k, std::floor(std::fmod(8.8 * t, 2 * kPi) / (2 * kPi / 1000)));
  });
  EXPECT_NEAR(reduce_run_log(parse_csv(coarse, "log.csv"), counts, 8.8).theta1_rate, 8.8, 1e-4);
}

TEST(RunLog, APulseCounterThatWrapsIsUnwrappedAtItsDeclaredWidth) {
  // 1461.5 pulses per 0.1 s sample over 450 s (6.6e6 pulses): a 16-bit counter wraps about a hundred times. With
  // counter_bits = 16 the steps are taken modulo 2^16 and the mean is that of the whole count, exactly (the
  // counts are integers: the sums are exact); without it the first wrap is refused at its line; a value beyond
  // 16 bits is no such count.
  const int n = 4501;
  auto count = [](int k) { return std::floor(1461.5 * k); };
  const std::string whole = log_text("time,pulses", n, [&](int k) { return fmt::format("{:.17g},{}", 0.1 * k, count(k)); });
  const std::string wrapped = log_text("time,pulses", n, [&](int k) {
    return fmt::format("{:.17g},{}", 0.1 * k, std::fmod(count(k), 65536.0));
  });
  RunLogOptions o;
  o.pulse_weight = 2e-5;
  const double mean = reduce_run_log(parse_csv(whole, "log.csv"), o, 8.8).mean_output;
  EXPECT_EQ(mean, count(n - 1) * 2e-5 / 450.0);
  RunLogOptions declared = o;
  declared.columns.counter_bits = 16;
  EXPECT_EQ(reduce_run_log(parse_csv(wrapped, "log.csv"), declared, 8.8).mean_output, mean);
  // The first wrap: the first k with count(k) ≥ 65536 (k = 45), on line 3 + k.
  int first = 0;
  while (count(first) < 65536) ++first;
  const CsvError e = reduction_error(wrapped, o);
  EXPECT_EQ(e.line(), 3 + first);
  EXPECT_EQ(e.item(), "pulses");
  EXPECT_NE(e.problem().find("a counter that wraps; accepted: its width declared"), std::string::npos)
      << e.problem();
  const CsvError beyond = reduction_error("time,pulses\n0,0\n1,65536\n", declared);
  EXPECT_EQ(beyond.line(), 3);
  EXPECT_NE(beyond.problem().find("65536 is not a count of a 16-bit counter"), std::string::npos)
      << beyond.problem();
}

}  // namespace
}  // namespace ccal::test
