// Reduction of recorded runs whose logs come from a closed-form motion written here, not from ccal's own
// reduction: an error-free centrifuge of radius R0 turning at Ω, its platform counter-rotating (γ = φ0 − Ωt,
// so the IA keeps its inertial azimuth ψ = θ1(0) + φ0), with the Earth rotating (model.md §1):
//   specific force on the IA:  a_i = −(A + C) cos γ,  A = Ω² R0 / g,  C = 2 ω_e R0 Ω sin φ / g
//     (the centripetal pull and the Coriolis force 2 ω_ie × v of the tangential velocity R0 Ω, both inward);
//   inertial rate about the IA: ω_IA = ω_e cos φ sin ψ   (the platform does not turn inertially);
//   output α = K0 + K1 a_i + K2 a_i² + K3 a_i³ + ω_IA, and the cumulative pulse count P(t) = (1/w)∫₀ᵗ α
//   from ∫cos γ = (sin φ0 − sin γ)/Ω, ∫cos² γ = t/2 + (sin 2φ0 − sin 2γ)/(4Ω),
//   ∫cos³ γ = 3(sin φ0 − sin γ)/(4Ω) + (sin 3φ0 − sin 3γ)/(12Ω).
// ccal reduces these logs with its own model of the runs (exact chain, Earth included) and identifies K0, K2
// and K3 with K1 held: they must come back as the instrument's. An error in the chain's physics (the Coriolis
// term, the Earth rate's latitude, the centripetal sign) no longer cancels between the logs and the model.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ccal/io/config_file.hpp"
#include "ccal/intake/run_log.hpp"
#include "ccal/reduction/observe.hpp"
#include "test_constants.hpp"

namespace ccal {
namespace {

using ccal::test::kDeg;
using ccal::test::kPi;

struct Motion {
  double rate, phi0, theta1_0;
};

// The log of one run: time, cumulative pulses of weight w, wrapped encoder angles, every 0.05 s.
std::string closed_form_log(const Motion& m, double T, double B, double K[4], double rate_ia, double w) {
  auto wrap = [](double a) { return std::fmod(std::fmod(a, 2 * kPi) + 2 * kPi, 2 * kPi); };
  const double W = m.rate, p0 = m.phi0;
  auto integral = [&](double t) {
    const double g = p0 - W * t;
    const double i1 = (std::sin(p0) - std::sin(g)) / W;
    const double i2 = t / 2 + (std::sin(2 * p0) - std::sin(2 * g)) / (4 * W);
    const double i3 =
        3 * (std::sin(p0) - std::sin(g)) / (4 * W) + (std::sin(3 * p0) - std::sin(3 * g)) / (12 * W);
    return K[0] * t - K[1] * B * i1 + K[2] * B * B * i2 - K[3] * B * B * B * i3 + rate_ia * t;
  };
  std::string text = "time,pulses,theta1,gamma\n";
  const int n = int(std::lround(T / 0.05));
  for (int k = 0; k <= n; ++k) {
    const double t = T * k / n;
    text += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g}\n", t, integral(t) / w, wrap(m.theta1_0 + W * t),
                        wrap(p0 - W * t));
  }
  return text;
}

TEST(ClosedFormLogs, ReduceToTheInstrumentsCoefficients) {
  // The bundled example's site and plan, written out: 45.75° N, g = 9.8 m/s², R0 = 2.5 m, six 450 s runs at
  // 5 … 30 g ending at ψ = π (φ0 = (π + ΩT) mod 2π), arm on East at t = 0; the paper's PIGA K0 = 0.061973
  // °/s, K1 = 505.2097 °/s/g, K2 = 0.02 °/s/g², K3 = 0.003 °/s/g³, s_ω = +1; pulses of 1e-4 rad (not rounded
  // to whole counts: the test is of the physics, not of quantisation). Tolerances: the logs' means are exact
  // to round-off (~1e-15 of the output swing of 0.3 rad/s); the encoder line fits give Ω and φ0 to ~1e-13
  // rad/s and 1e-10 rad, which moves the model's means by at most ~1e-10 of the swing; H⁺ of the six runs
  // amplifies that by up to ~1e3 on K3 (its column Z3 is small): tolerances 1e-9 relative on K0 and K2, 1e-8
  // on K3. Against them: leaving the Coriolis term out moves (K0, K2, K3) by (2.8e-5, 3.6e-7, 1.3e-5) in
  // °/s/gⁿ, i.e. 5e-4, 2e-5, 4e-3 relative; swapping sin φ and cos φ in the Earth rate moves K0 by 2e-3
  // relative.
  const Config cfg = bundled_example();
  const double g = 9.8, R0 = 2.5, lat = 45.75 * kDeg, we = 7.2921150e-5, T = 450.0, w = 1e-4;
  double K[4] = {0.061973 * kDeg, 505.2097 * kDeg, 0.02 * kDeg, 0.003 * kDeg};
  ASSERT_EQ(cfg.plan.runs.size(), 6u);
  std::vector<std::pair<std::size_t, CsvTable>> logs;
  for (std::size_t r = 0; r < 6; ++r) {
    const double A = 5.0 * double(r + 1);
    Motion m;
    m.rate = std::sqrt(A * g / R0);
    m.phi0 = std::fmod(kPi + m.rate * T, 2 * kPi);
    m.theta1_0 = 0.0;
    const double C = 2 * we * R0 * m.rate * std::sin(lat) / g;
    const double rate_ia = we * std::cos(lat) * std::sin(m.theta1_0 + m.phi0);
    const std::string text = closed_form_log(m, T, A + C, K, rate_ia, w);
    logs.emplace_back(r, parse_csv(text, fmt::format("run{}.csv", r + 1)));
  }
  RunLogOptions options;
  options.pulse_weight = w;
  const LogReduction red = reduce_logs(cfg, logs, options, ModelMode::exact);
  ASSERT_EQ(red.runs.size(), 6u);
  for (const LoggedRun& run : red.runs) {
    // The measured motion is the closed form's: no rate error, no mismatch (line fits: 1e-12).
    EXPECT_NEAR(run.rate, std::sqrt(5.0 * double(run.index + 1) * g / R0), 1e-12) << run.index;
    EXPECT_NEAR(run.mismatch, 0.0, 1e-12) << run.index;
  }
  const Eigen::VectorXd got = identify_coefficients<double>(red.observations, cfg.identification) / kDeg;
  ASSERT_EQ(got.size(), 3);
  EXPECT_NEAR(got[0], 0.061973, 1e-9 * 0.061973);
  EXPECT_NEAR(got[1], 0.02, 1e-9 * 0.02);
  EXPECT_NEAR(got[2], 0.003, 1e-8 * 0.003);
}

}  // namespace
}  // namespace ccal
