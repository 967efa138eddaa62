// The drives' rate ripple measured by the encoders (docs/model.md §13.1) and the platform's control read from
// them (§13.2), on logs generated here from closed forms of the joint angles:
//   θ1 = θ1ⁿ + δ1(θ1ⁿ),  γ = γⁿ + δ3(γⁿ) [− δ1(θ1ⁿ) when phase-locked],  δ(q) = Σ (ck sin kq − sk cos kq)/k,
// with θ1ⁿ = θ1(0) + (Ω + Δω) t and γⁿ = φ0 − (Ω + Δω + ΔΩ) t (model.md §2.3, §3.1).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "ccal/io/config_file.hpp"
#include "ccal/intake/run_log.hpp"
#include "ccal/reduction/run_average.hpp"
#include "cli_support.hpp"
#include "test_constants.hpp"

namespace {

using namespace ccal::test;
using ccal::test::kPi;

// The angle error of a relative rate ripple c1, s1, …, cN, sN (model.md §3.1), written out here.
double angle_error(const std::vector<double>& ripple, double q) {
  double d = 0;
  for (std::size_t i = 0; i + 1 < ripple.size(); i += 2) {
    const double k = double(i / 2 + 1);
    d += (ripple[i] * std::sin(k * q) - ripple[i + 1] * std::cos(k * q)) / k;
  }
  return d;
}

double wrap(double a) { return std::fmod(std::fmod(a, 2 * kPi) + 2 * kPi, 2 * kPi); }

struct Drives {
  std::vector<double> main, platform;  // ripple of each drive (c1, s1, …)
  bool phase_locked = false;
};

// A log of `seconds` at `step` s: cumulative pulses of a constant output (mean × t / w) and both encoders.
std::string log_text(double rate, double gamma_rate, double theta0, double phi0, const Drives& d,
                     double seconds, double step, double mean, double w) {
  std::string text = "time,pulses,theta1,gamma\n";
  const int n = int(std::lround(seconds / step));
  for (int k = 0; k <= n; ++k) {
    const double t = seconds * k / n;
    const double theta_n = theta0 + rate * t, gamma_n = phi0 + gamma_rate * t;
    const double d1 = angle_error(d.main, theta_n);
    const double gamma = gamma_n + angle_error(d.platform, gamma_n) - (d.phase_locked ? d1 : 0.0);
    text +=
        fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}\n", t, mean * t / w, wrap(theta_n + d1), wrap(gamma));
  }
  return text;
}

TEST(RippleFromEncoders, KnownRippleComesBackAsItsHarmonics) {
  // 30 g (Ω = 10.84 rad/s) for 100 s sampled at 200 Hz; main ripple c1 = 10, s1 = −4, c2 = 3, s2 = 2 ppm,
  // platform c1 = −6, s1 = 5 ppm, speed control. The fit's argument is the measured angle, not the nominal
  // one: the regressors differ by O(δ) ~ 1e-5 rad, the coefficients by O(k δ · ripple) ~ 1e-10 (relative
  // rate): tolerance 1e-9, a thousandth of the smallest harmonic. The rate and phase come back to the same
  // order (1e-9 rad/s, 1e-8 rad).
  const double rate = std::sqrt(30 * 9.8 / 2.5), theta0 = 0.4, phi0 = 2.1;
  Drives d;
  d.main = {10e-6, -4e-6, 3e-6, 2e-6};
  d.platform = {-6e-6, 5e-6, 0, 0};
  ccal::RunLogOptions o;
  o.pulse_weight = 1e-5;
  o.harmonic_order = 2;
  const ccal::ReducedLog r = ccal::reduce_run_log(
      ccal::parse_csv(log_text(rate, -rate, theta0, phi0, d, 100, 0.005, 1.0, 1e-5), "ripple.csv"), o, rate);
  const std::vector<double> main = ccal::ripple_from_angle_harmonics(r.theta1_harmonics);
  const std::vector<double> platform = ccal::ripple_from_angle_harmonics(r.gamma_harmonics);
  ASSERT_EQ(main.size(), 4u);
  ASSERT_EQ(platform.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(main[i], d.main[i], 1e-9) << i;
    EXPECT_NEAR(platform[i], d.platform[i], 1e-9) << i;
  }
  EXPECT_NEAR(r.theta1_rate, rate, 1e-9);
  EXPECT_NEAR(r.gamma_rate, -rate, 1e-9);
  EXPECT_NEAR(r.theta1_start, theta0, 1e-8);
  EXPECT_NEAR(r.gamma_start, phi0, 1e-8);
  // The residual is the harmonics' second-order remainder, far below the 1e-5 rad ripple.
  EXPECT_LT(r.theta1_rms, 1e-9);
}

TEST(RippleFromEncoders, ConversionIsModelSection31) {
  // δ(q) = Ĉ cos q + Ŝ sin q with Ĉ = −s1, Ŝ = c1 (k = 1); k = 2: Ĉ = −s2/2, Ŝ = c2/2.
  const std::vector<double> ripple{1.0, 2.0, 3.0, 4.0};
  const std::vector<double> angle = ccal::angle_harmonics_from_ripple(ripple);
  EXPECT_EQ(angle, (std::vector<double>{-2.0, 1.0, -2.0, 1.5}));
  EXPECT_EQ(ccal::ripple_from_angle_harmonics(angle), ripple);
}

TEST(RippleFromEncoders, ControlModeFromBothEncoders) {
  // Main ripple 10 ppm at 20 g; the platform's own ripple 2 ppm. Phase-locked, γ carries −δ1: λ = 1 up to the
  // platform's own ripple projected on it (|δ3|/|δ1| = 0.2); speed: λ = 0 up to the same. No main ripple:
  // nothing to compare, undetermined.
  const double rate = std::sqrt(20 * 9.8 / 2.5);
  ccal::RunLogOptions o;
  o.pulse_weight = 1e-5;
  o.harmonic_order = 1;
  auto look = [&](const Drives& d) {
    const std::string text = log_text(rate, -rate, 0.3, 1.7, d, 60, 0.01, 1.0, 1e-5);
    return ccal::platform_control_evidence(ccal::reduce_run_log(ccal::parse_csv(text, "mode.csv"), o, rate));
  };
  Drives d;
  d.main = {10e-6, 3e-6};
  d.platform = {1e-6, -1.7e-6};
  d.phase_locked = true;
  const ccal::ControlEvidence locked = look(d);
  EXPECT_EQ(locked.look, ccal::ControlLook::phase_locked);
  EXPECT_NEAR(locked.following, 1, 0.25);
  EXPECT_GT(locked.main_in_gamma, locked.threshold);
  d.phase_locked = false;
  const ccal::ControlEvidence speed = look(d);
  EXPECT_EQ(speed.look, ccal::ControlLook::speed);
  EXPECT_NEAR(speed.following, 0, 0.25);
  d.main = {0, 0};
  const ccal::ControlEvidence none = look(d);
  EXPECT_EQ(none.look, ccal::ControlLook::undetermined);
  EXPECT_LT(none.main_in_gamma, none.threshold);
}

// The bundled example with the drives' ripple as known errors and compensated, its logs written from the
// closed forms above with the truth's run means as pulse counts (every 0.05 s).
class ReduceRipple : public Cli {
 protected:
  std::string config_text(bool ripple, bool phase_locked, bool compensate = true) const {
    std::string text = read(kExample);
    auto replace = [&](const std::string& from, const std::string& to) {
      const auto at = text.find(from);
      EXPECT_NE(at, std::string::npos) << from;
      text.replace(at, from.size(), to);
    };
    if (ripple)
      replace(
          "# dthz5 = \"2 arcsec\"       # instrument azimuth (IA) zero error",
          "ripple1_c1 = \"10 ppm\"\nripple1_s1 = \"-6 ppm\"\nripple3_c1 = \"4 ppm\"\nripple3_s1 = \"3 ppm\"");
    if (phase_locked) replace("platform_control = \"speed\"", "platform_control = \"phase_locked\"");
    if (compensate) replace("compensate = false", "compensate = true");
    return text;
  }

  std::string write_logs(const ccal::Config& cfg, bool phase_locked) const {
    const ccal::Experiment ex = cfg.experiment();
    const Eigen::VectorXd& e = cfg.centrifuge.errors;
    const ccal::ErrorLayout& layout = cfg.centrifuge.layout;
    Drives d;
    d.phase_locked = phase_locked;
    for (bool sine : {false, true}) {
      d.main.push_back(e[layout.harmonic_index(ccal::ch::ripple1, 1, sine)]);
      d.platform.push_back(e[layout.harmonic_index(ccal::ch::ripple3, 1, sine)]);
    }
    std::string args;
    for (std::size_t r = 0; r < cfg.plan.runs.size(); ++r) {
      const ccal::Run& run = cfg.plan.runs[r];
      const double mean =
          ccal::average_run<double>(ex.geometry, ex.layout, e, ex.site, run, &ex.instrument, {}).output;
      const double rate = ccal::nominal_rate(run, ex.geometry, ex.site);
      const double phi0 = ccal::initial_phase(run, ex.geometry, ex.site);
      const std::string name = fmt::format("run{}.csv", r + 1);
      std::ofstream(dir_ / name) << log_text(rate, -rate, run.arm_azimuth, phi0, d, run.duration, 0.05, mean,
                                             1e-3 * kPi / 180);
      args += fmt::format(" --log {}={}", run.name, name);
    }
    return args;
  }
};

TEST_F(ReduceRipple, MeasuredRippleGivesTheSimulatedIdentification) {
  // The logs of a rippled centrifuge reduced with a configuration that knows nothing of the ripple: the
  // encoders' ripple replaces the configured (zero) one, so the coefficients are those `simulate` identifies
  // for the rippled centrifuge. Left out of the model (`simulate` with compensate = false) the ripple moves
  // K0 by 25 % and K3 by 4 times its value (`effect`); the measured first harmonic is exact to third order
  // (the argument's error δ turns cos q into harmonics 0 and 2), and the coefficients agree to ~3e-9 of that
  // effect: tolerance 1e-6 of the effect, plus the line fits' 1e-9 of the value (cli/reduce_test.cpp).
  for (bool phase_locked : {false, true}) {
    SCOPED_TRACE(phase_locked ? "phase_locked" : "speed");
    write("rippled.toml", config_text(true, phase_locked));
    write("plain.toml", config_text(false, phase_locked));
    const ccal::Config cfg = ccal::load_config(dir_ / "rippled.toml");
    const std::string logs = write_logs(cfg, phase_locked);
    const Result sim = run("simulate rippled.toml --format json");
    ASSERT_EQ(sim.code, 0) << sim.err;
    const Result red = run("reduce plain.toml --format json --pulse-weight 1e-3" + logs);
    ASSERT_EQ(red.code, 0) << red.err;
    EXPECT_EQ(red.err.find("warning"), std::string::npos) << red.err;  // the control is the configured one
    write("blind.toml", config_text(true, phase_locked, false));
    const Result plain = run("simulate blind.toml --format json");  // the ripple not in the model
    ASSERT_EQ(plain.code, 0) << plain.err;
    const auto s = nlohmann::json::parse(sim.out), r = nlohmann::json::parse(red.out);
    const auto p = nlohmann::json::parse(plain.out);
    for (const char* k : {"K0", "K2", "K3"}) {
      const double a = s["identification"]["coefficients"][k]["value"];
      const double b = r["identification"]["coefficients"][k]["value"];
      const double effect = std::abs(a - double(p["identification"]["coefficients"][k]["value"]));
      const double tolerance = 1e-6 * effect + 1e-9 * std::abs(a);
      EXPECT_NEAR(b, a, tolerance) << k;
      EXPECT_GT(effect, 10 * tolerance) << k;  // the ripple matters: a model without it would fail
    }
    const auto& x = r["runs"][5];
    EXPECT_NEAR(double(x["main_encoder"]["ripple"]["ripple1_c1"]), 10e-6, 1e-9);
    EXPECT_NEAR(double(x["main_encoder"]["ripple"]["ripple1_s1"]), -6e-6, 1e-9);
    EXPECT_NEAR(double(x["platform_encoder"]["ripple"]["ripple3_c1"]), 4e-6, 1e-9);
    EXPECT_NEAR(double(x["platform_encoder"]["ripple"]["ripple3_s1"]), 3e-6, 1e-9);
    EXPECT_EQ(x["platform_control"]["looks_like"], phase_locked ? "phase_locked" : "speed");
  }
}

TEST_F(ReduceRipple, ContradictedControlIsWarnedAbout) {
  // Phase-locked logs reduced with a configuration that says speed: a warning on stderr, exit 0.
  write("locked.toml", config_text(true, true));
  write("speed.toml", config_text(true, false));
  const std::string logs = write_logs(ccal::load_config(dir_ / "locked.toml"), true);
  const Result red = run("reduce speed.toml --pulse-weight 1e-3" + logs);
  ASSERT_EQ(red.code, 0) << red.err;
  EXPECT_NE(red.err.find("warning"), std::string::npos) << red.err;
  EXPECT_NE(red.err.find("phase_locked"), std::string::npos) << red.err;
  EXPECT_NE(red.out.find("phase_locked"), std::string::npos) << red.out;
}

TEST_F(ReduceRipple, NoRippleInTheLogsLeavesTheModelAsBefore) {
  // Ripple-free logs: every measured harmonic is below the fits' resolution, so it is exactly zero in the
  // model and the run's model is the ripple-free one `simulate` uses: the same coefficients to 1e-9.
  write("plain.toml", config_text(false, false));
  const std::string logs = write_logs(ccal::load_config(dir_ / "plain.toml"), false);
  const Result sim = run("simulate plain.toml --format json");
  const Result red = run("reduce plain.toml --format json --pulse-weight 1e-3" + logs);
  ASSERT_EQ(red.code, 0) << red.err;
  const auto s = nlohmann::json::parse(sim.out), r = nlohmann::json::parse(red.out);
  for (const char* k : {"K0", "K2", "K3"}) {
    const double a = s["identification"]["coefficients"][k]["value"];
    const double b = r["identification"]["coefficients"][k]["value"];
    EXPECT_NEAR(b, a, 1e-9 * std::abs(a)) << k;
  }
  EXPECT_EQ(double(r["runs"][0]["main_encoder"]["ripple"]["ripple1_c1"]), 0.0);
  EXPECT_EQ(r["runs"][0]["platform_control"]["looks_like"], "undetermined");
}

}  // namespace
