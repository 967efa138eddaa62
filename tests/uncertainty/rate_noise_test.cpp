// The drives' random rate noise (docs/model.md §3.2): the closed forms of a run mean's scatter, a time-domain
// simulation of the noise through the exact chain, and the budget's and the Monte Carlo's Type A component.
#include "ccal/uncertainty/rate_noise.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "experiment_support.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

using ccal::test::kPi;

// One run on the platform axis (L = l = 0), Earth rotation off, an instrument with K1 = 1 per g only: its
// output is a_i, so the closed forms below are those of the IA input.
Experiment one_run(PlatformMode mode, PlatformControl control, double A, double duration, double phi0) {
  Experiment ex;
  ex.geometry = Geometry{2.5, 0.0, 0.0, 0.0};
  ex.geometry.platform_control = control;
  ex.layout = ErrorLayout(1);
  ex.site = paper_site(false);
  ccal::Run r;
  r.name = "run";
  r.g_level = A;
  r.duration = duration;
  r.initial_phase = phi0;
  r.arm_azimuth = 0.3;
  r.mode = mode;
  ex.plan.runs.push_back(r);
  ex.instrument.term_ids = {"K1"};
  ex.instrument.coefficients = Eigen::VectorXd::Constant(1, 1.0);
  ex.instrument.rate_gain = 0.0;
  return ex;
}

TEST(RateNoise, RunMeanScatterClosedForms) {
  // With a relative rate noise n of density N (two-sided PSD N²) the IA input moves by
  //   −2A n cos γ (centripetal) + (A/Ω) ṅ sin γ (tangential) [− A Φ sin γ ... when γ follows θ1],
  // whose run mean has, written out by integrating ṅ by parts over whole revolutions (γ = ψ0 − Ωt):
  //   fixed platform (γ = φ0):         σ/N = 2A |cos φ0| / √T
  //   counter-rotating, speed:          σ/N = A / √(2T)          (h = −A cos γ)
  //   counter-rotating, phase-locked:   σ/N = A |cos γ(T)| / √T  (h = −A cos γ(T): only the end heading)
  //   platform noise (either control):  σ/N = A √(½ + cos²γ(T)) / √T
  //                                     (γ moves by −Ω∫n: h = A cos γ − A cos γ(T))
  // Tolerance 1e-9 relative: the gain's spectral derivatives and primitives are exact for these band-limited
  // integrands over whole revolutions.
  const double A = 12.0, w = rate_for(A, 2.5, 9.8), T = 200 * 2 * kPi / w, phi0 = 0.7;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ErrorLayout(1).size());
  auto gain = [&](PlatformMode mode, PlatformControl control, int drive) {
    return rate_noise_gain(one_run(mode, control, A, T, phi0), zero, drive)[0];
  };
  EXPECT_NEAR(gain(PlatformMode::fixed, PlatformControl::speed, ch::ripple1),
              2 * A * std::abs(std::cos(phi0)) / std::sqrt(T), 1e-9 * A);
  EXPECT_EQ(gain(PlatformMode::fixed, PlatformControl::speed, ch::ripple3), 0.0);
  EXPECT_NEAR(gain(PlatformMode::counter_rotating, PlatformControl::speed, ch::ripple1), A / std::sqrt(2 * T),
              1e-9 * A);
  const double gamma_T = phi0 - w * T;
  EXPECT_NEAR(gain(PlatformMode::counter_rotating, PlatformControl::phase_locked, ch::ripple1),
              A * std::abs(std::cos(gamma_T)) / std::sqrt(T), 1e-9 * A);
  for (PlatformControl control : {PlatformControl::speed, PlatformControl::phase_locked})
    EXPECT_NEAR(gain(PlatformMode::counter_rotating, control, ch::ripple3),
                A * std::sqrt(0.5 + std::pow(std::cos(gamma_T), 2)) / std::sqrt(T), 1e-9 * A);
}

TEST(RateNoise, SimulatedRunMeansScatterAsTheClosedForm) {
  // The noise drawn in time and pushed through the exact chain: n(t) piecewise linear between knots every
  // Δ = 0.02 s with independent N(0, N²/Δ) values (a PSD within 1 % of N² below 2 Hz, where a run mean reads
  // it), tapered by linear ramps of L = 1 s at both ends so that no end value enters; θ1 = θⁿ + Ω∫n,
  // θ̇1 = Ω(1 + n), θ̈1 = Ω ṅ; the run mean by the trapezoid rule every 2 ms. Counter-rotating, speed control:
  // Var = N² ⟨h²⟩ ∫w² / T² = N² (A²/2)(T − 4L/3)/T². With 400 runs the sample variance has a relative
  // standard error √(2/400) = 7 %: tolerance 25 % (3.5 standard errors).
  const double A = 10.0, N = 1e-5, T = 20.0, L = 1.0, knot = 0.02, dt = 0.002;
  const Experiment ex = one_run(PlatformMode::counter_rotating, PlatformControl::speed, A, T, 0.7);
  const double w = rate_for(A, 2.5, 9.8);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const int steps = int(std::lround(T / dt)), per_knot = int(std::lround(knot / dt));
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> normal(0.0, N / std::sqrt(knot));
  auto window = [&](double t) { return std::min({1.0, t / L, (T - t) / L}); };
  auto window_slope = [&](double t) { return t < L ? 1.0 / L : (t > T - L ? -1.0 / L : 0.0); };
  auto run_mean = [&](const std::vector<double>& knots) {
    double sum = 0, phi = 0, previous = 0;
    for (int i = 0; i <= steps; ++i) {
      const double t = i * dt;
      const int k = std::min(i / per_knot, int(knots.size()) - 2);
      const double x = (t - k * knot) / knot;
      const double n = knots[std::size_t(k)] * (1 - x) + knots[std::size_t(k) + 1] * x;
      const double n_rate = (knots[std::size_t(k) + 1] - knots[std::size_t(k)]) / knot;
      const double tapered = window(t) * n;
      if (i > 0) phi += 0.5 * (previous + tapered) * dt;
      previous = tapered;
      JointState<double> j{0.3 + w * t + w * phi, w * (1 + tapered), 0.0, 0.0, 0.7 - w * t, -w};
      j.theta1_acc = w * (window(t) * n_rate + window_slope(t) * n);
      const double a_i = exact_state<double>(ex.geometry, ex.layout, zero, ex.site, j).specific_force[0];
      sum += (i == 0 || i == steps ? 0.5 : 1.0) * a_i;
    }
    return sum * dt / T;
  };
  const double quiet = run_mean(std::vector<double>(std::size_t(T / knot) + 2, 0.0));
  const int realisations = 400;
  double sum = 0, square = 0;
  for (int r = 0; r < realisations; ++r) {
    std::vector<double> knots(std::size_t(T / knot) + 2);
    for (double& v : knots) v = normal(rng);
    const double d = run_mean(knots) - quiet;
    sum += d;
    square += d * d;
  }
  const double variance = (square - sum * sum / realisations) / (realisations - 1);
  const double expected = N * N * (A * A / 2) * (T - 4 * L / 3) / (T * T);
  EXPECT_NEAR(variance / expected, 1.0, 0.25) << "sample sd " << std::sqrt(variance);
}

TEST(RateNoise, BudgetAddsTheTypeAComponentAndMonteCarloAgrees) {
  // The bundled example with only the drives' rate noise: the budget's noise covariance is H⁺ diag(σ²) H⁺ᵀ
  // (the u of each coefficient from the per-run σ written out here), and a Monte Carlo of the per-run draws
  // gives the same u within sampling error (M = 2·10⁴: relative standard error 1/√(2M) = 0.5 %, tolerance
  // 2.5 %).
  Config cfg = bundled_example();
  cfg.tolerances.clear();
  cfg.centrifuge.rate_noise = {2e-6, 3e-6};
  BudgetOptions bo;
  bo.compare_with_paper = false;
  const BudgetDetail b = compute_budget(cfg, bo);
  ASSERT_EQ(b.rate_noise.size(), 2u);
  const Experiment ex = cfg.experiment();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const auto obs = observe<double>(ex, zero, zero, cfg.identification, ModelMode::exact);
  const Eigen::MatrixXd H = obs.regressors.leftCols(3);
  const Eigen::MatrixXd pinv = (H.transpose() * H).inverse() * H.transpose();
  for (const RateNoiseBudget& n : b.rate_noise) {
    for (int k = 0; k < 3; ++k) {
      double var = 0;
      for (Eigen::Index j = 0; j < H.rows(); ++j) var += std::pow(pinv(k, j) * n.run_sd[j], 2);
      EXPECT_NEAR(n.effect[k], std::sqrt(var), 1e-9 * std::sqrt(var)) << n.id;
    }
  }
  const Eigen::VectorXd u = b.standard_uncertainty;
  EXPECT_NEAR(u[0], std::hypot(b.rate_noise[0].effect[0], b.rate_noise[1].effect[0]), 1e-12 * u[0]);

  PropagationOptions mo;
  mo.trials = 20000;
  mo.seed = 3;
  const CalibrationModel model = calibration_model(cfg);
  const MonteCarloDetail mc = run_monte_carlo(monte_carlo_sources(cfg), model.n_outputs(),
                                              model.output_names(), calibration_trial(model), mo);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(mc.outputs[std::size_t(k)].std_dev / u[k], 1.0, 0.025) << b.coefficients[std::size_t(k)];
}

}  // namespace
}  // namespace ccal::test
