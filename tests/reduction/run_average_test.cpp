// Run reduction: closed forms of model.md §4.1/§4.4, the spectral rule against two independent quadratures,
// and its derivatives.
#include "ccal/reduction/run_average.hpp"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss.hpp>
#include <random>

#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "experiment_support.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

using ccal::test::kPi;

ccal::Run paper_run(double A) {
  ccal::Run r;
  r.name = std::to_string(int(A)) + "g";
  r.g_level = A;
  r.duration = 450.0;
  r.mode = PlatformMode::counter_rotating;
  r.terminal_phase = kPi;
  return r;
}

TEST(ClosedForms, InitialPhasesOfTable3) {
  // model.md §6.1, φ0 = (π + ΩT) mod 2π, quoted to 4 decimals: tolerance 6e-5 rad (half a unit in the last
  // quoted digit plus margin).
  const Geometry geo{2.5, 0, 0, 0};
  Site site = paper_site();
  const double want_98[] = {3.6068, 5.7202, 4.3250, 4.0720, 3.1359, 1.0656};
  const double want_980665[] = {4.2826, 0.3928, 5.4955, 5.4236, 4.6471, 2.7210};
  for (int k = 0; k < 6; ++k) {
    site.g = 9.8;
    EXPECT_NEAR(initial_phase(paper_run(5.0 * (k + 1)), geo, site), want_98[k], 6e-5) << k;
    site.g = 9.80665;
    EXPECT_NEAR(initial_phase(paper_run(5.0 * (k + 1)), geo, site), want_980665[k], 6e-5) << k;
  }
}

TEST(ClosedForms, RegressorsOfThePaperRunsToSevenDigits) {
  // Reference values (g = 9.8): Z1 = ⟨a_i⟩, Z2 = ⟨a_i²⟩, Z3 = ⟨a_i³⟩ of a_i = −A cos γ, quoted to 7
  // significant digits: relative tolerance 5e-7 (half a unit in the 7th digit).
  const Geometry geo{2.5, 0, 0, 0};
  const Site site = paper_site();
  const double Z[6][3] = {{+1.125838e-3, 12.50252, +2.625802e-2}, {+1.894236e-3, 49.99199, +1.714393e-1},
                          {+4.024838e-3, 112.5114, +6.468112e-1}, {+4.024823e-3, 200.0240, +1.264897e+0},
                          {-3.177090e-5, 312.4996, -1.985660e-2}, {-5.379707e-3, 450.0391, -3.605826e+0}};
  for (int r = 0; r < 6; ++r) {
    const ccal::Run run = paper_run(5.0 * (r + 1));
    const double phi0 = initial_phase(run, geo, site);
    const double wT = nominal_rate(run, geo, site) * run.duration;
    for (int k = 1; k <= 3; ++k) {
      const double got = nominal_power_mean(k, run.g_level, phi0, wT);
      // Z2 is quoted to 7 significant digits too; its last digit is 1e-4 absolute at 450 g².
      EXPECT_NEAR(got, Z[r][k - 1], 5e-7 * std::abs(Z[r][k - 1])) << "A=" << run.g_level << " k=" << k;
    }
  }
}

TEST(ClosedForms, ErrorFreeExactReductionMatches) {
  // The spectral rule over the exact chain with no errors and no Earth rotation reproduces the closed forms
  // to 1e-12·A^k for ⟨a_iᵏ⟩ (a mean of O(A^k) values: a few roundings of A^k; Z1 is a small difference of
  // large numbers, hence relative to A, not to Z1), for k up to 5, on the six paper runs.
  const Geometry geo{2.5, 0.2, 0.05, 0};
  const ErrorLayout layout(1);
  const Site site = paper_site();
  const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
  const std::vector<TermSpec> terms = {{TermKind::power, 1},
                                       {TermKind::power, 2},
                                       {TermKind::power, 3},
                                       {TermKind::power, 4},
                                       {TermKind::power, 5}};
  for (int r = 0; r < 6; ++r) {
    const ccal::Run run = paper_run(5.0 * (r + 1));
    const auto avg = average_run<double>(geo, layout, e, site, run, nullptr, terms);
    const double phi0 = initial_phase(run, geo, site), wT = nominal_rate(run, geo, site) * run.duration;
    for (int k = 1; k <= 5; ++k)
      EXPECT_NEAR(avg.regressors[k - 1], nominal_power_mean(k, run.g_level, phi0, wT),
                  1e-12 * std::pow(run.g_level, k))
          << "A=" << run.g_level << " k=" << k;
  }
}

// Mean of the PIGA output and of a_i³ by a given rule over the exact chain.
std::pair<double, double> mean_by(const RunQuadrature<double>& quad, const Geometry& geo,
                                  const ErrorLayout& layout, const Eigen::VectorXd& e, const Site& site) {
  const InstrumentModel piga = paper_piga();
  const auto terms = piga.terms();
  long double out = 0, cube = 0;  // extended accumulation: the brute-force rule sums ~1e4 terms
  for (std::size_t n = 0; n < quad.nodes.size(); ++n) {
    const auto s = exact_state<double>(geo, layout, e, site, quad.nodes[n]);
    out += quad.weights[n] * instrument_output(piga, terms, s.specific_force, s.angular_rate[0]);
    cube += quad.weights[n] * std::pow(s.specific_force[0], 3);
  }
  return {double(out), double(cube)};
}

TEST(SpectralRule, AgreesWithTrapezoidPlusGaussLegendreWhenLocked) {
  // Counter-rotating with ΔΩ = 0 and a fixed platform, with static errors and first and second harmonics of
  // every dynamic error at 1e-4 (10× the paper's tolerances), Earth on. Two independent rules, each exact to
  // round-off for these band-limited integrands. The integrand swings by K1·A ≈ 176 rad/s around a mean of
  // O(0.1) rad/s, so round-off is relative to K1·A: tolerance 1e-15·K1·A on the output, 1e-15·A³ on ⟨a_i³⟩.
  const Geometry geo{2.5, 0.2, 0.05, 0};
  const ErrorLayout layout(2);
  const Site site = paper_site(true);
  const Eigen::VectorXd e = random_errors(layout, 1e-4, 3);
  for (PlatformMode mode : {PlatformMode::counter_rotating, PlatformMode::fixed}) {
    ccal::Run run = paper_run(20.0);
    run.mode = mode;
    run.duration = 73.3;
    const double rate = nominal_rate(run, geo, site), phi0 = initial_phase(run, geo, site);
    const auto motion = run_motion<double>(rate, 0.3, phi0, mode, 0.0, e);
    const auto spectral = run_quadrature<double>(motion, run.duration, mode, 0.0, {fast_nodes_for(3, 3), 0});
    const auto reference = trapezoid_gauss_quadrature(motion, run.duration, 32, 40);
    const auto [out_s, cube_s] = mean_by(spectral, geo, layout, e, site);
    const auto [out_r, cube_r] = mean_by(reference, geo, layout, e, site);
    const double swing = paper_piga().coefficients[1] * 20.0;
    EXPECT_NEAR(out_s, out_r, 1e-15 * swing) << int(mode);
    EXPECT_NEAR(cube_s, cube_r, 1e-15 * 8000.0) << int(mode);
  }
}

TEST(SpectralRule, HandlesPlatformMismatchLikeABruteForceIntegral) {
  // ΔΩ = 2e-4 rad/s (0.09 rad of heading drift over 450 s: 400× the paper's tolerance) against composite
  // 20-point Gauss–Legendre on every revolution (≈ 634 × 20 evaluations, exact to round-off per revolution,
  // summed in extended precision). Tolerance 1e-15 of the integrand's swing (K1·A on the output, A³ on
  // ⟨a_i³⟩): the spectral rule's interpolation error in time, (ΔΩT)^7/7! ≈ 1e-11 of the drift-dependent part,
  // is far below that.
  const Geometry geo{2.5, 0.2, 0.05, 0};
  const ErrorLayout layout(1);
  const Site site = paper_site(true);
  Eigen::VectorXd e = random_errors(layout, 1e-5, 5);
  e[ch::dOmega] = 2e-4;
  const ccal::Run run = paper_run(20.0);
  const double rate = nominal_rate(run, geo, site), phi0 = initial_phase(run, geo, site);
  const auto motion = run_motion<double>(rate, 0.0, phi0, run.mode, 0.0, e);
  const auto spectral =
      run_quadrature<double>(motion, run.duration, run.mode, e[ch::dOmega], {fast_nodes_for(3, 2), 0});
  RunQuadrature<double> brute;
  const double period = 2 * kPi / motion.theta1_rate;
  using GL = boost::math::quadrature::gauss<double, 20>;
  for (double a = 0; a < run.duration; a += period / 4) {  // quarter revolutions: GL-20 exact to round-off
    const double b = std::min(a + period / 4, run.duration), mid = (a + b) / 2, half = (b - a) / 2;
    for (std::size_t k = 0; k < GL::abscissa().size(); ++k) {
      for (double sign : {1.0, -1.0}) {
        if (GL::abscissa()[k] == 0 && sign < 0) continue;
        brute.nodes.push_back(motion.at(mid + sign * half * GL::abscissa()[k]));
        brute.weights.push_back(half * GL::weights()[k] / run.duration);
      }
    }
  }
  const auto [out_s, cube_s] = mean_by(spectral, geo, layout, e, site);
  const auto [out_b, cube_b] = mean_by(brute, geo, layout, e, site);
  EXPECT_NEAR(out_s, out_b, 1e-15 * paper_piga().coefficients[1] * 20.0);
  EXPECT_NEAR(cube_s, cube_b, 1e-15 * 8000.0);
  EXPECT_LT(spectral.nodes.size(), 300u);  // the point of the rule: 240 evaluations instead of ~50 000
}

TEST(SpectralRule, DerivativesWithRespectToDriveErrorsMatchFiniteDifferences) {
  // d⟨output⟩/dΔω and d⟨output⟩/dΔΩ through the weights (which depend on Ω and ΔΩ) and the nodes, at ΔΩ = 0
  // where the rule keeps two slow nodes so that the first derivative is exact. Central differences with
  // h = 1e-9 rad/s: truncation O(h²) negligible, round-off ≈ 1e-16·6/1e-9 ≈ 1e-6 relative to a derivative of
  // O(1e2…1e3): tolerance 1e-5 relative.
  const Geometry geo{2.5, 0.2, 0.05, 0};
  const ErrorLayout layout(1);
  const Site site = paper_site(true);
  const Eigen::VectorXd e0 = random_errors(layout, 1e-5, 9);
  const ccal::Run run = paper_run(25.0);
  const InstrumentModel piga = paper_piga();
  VecX<AD> e(layout.size());
  for (int i = 0; i < layout.size(); ++i) e[i] = make_dual(e0[i], i == ch::domega ? 0 : i == ch::dOmega ? 1 : -1);
  const auto avg = average_run<AD>(geo, layout, e, site, run, &piga, {});
  for (int which : {int(ch::domega), int(ch::dOmega)}) {
    const double h = 1e-9;
    Eigen::VectorXd ep = e0, em = e0;
    ep[which] += h;
    em[which] -= h;
    const double fp = average_run<double>(geo, layout, ep, site, run, &piga, {}).output;
    const double fm = average_run<double>(geo, layout, em, site, run, &piga, {}).output;
    const double fd = (fp - fm) / (2 * h);
    const double ad = avg.output.derivatives()[which == ch::domega ? 0 : 1];
    EXPECT_NEAR(ad, fd, 1e-5 * std::abs(fd)) << channels()[which].id;
    EXPECT_GT(std::abs(ad), 1.0);  // a real sensitivity, not a vacuous zero
  }
}

TEST(SpectralRule, StaticFastPathEqualsGeneralChain) {
  // Same run, static errors only: the factored chain and the general recursion give the same means to
  // round-off of the integrand's swing K1·A.
  const Geometry geo{2.5, 0.2, 0.05, 0};
  const ErrorLayout layout(1);
  const Site site = paper_site(true);
  Eigen::VectorXd e = random_errors(layout, 1e-5, 21);
  e.tail(e.size() - kStaticChannelCount).setZero();
  const InstrumentModel piga = paper_piga();
  ReductionOptions general;
  general.allow_static_chain = false;
  const double fast = average_run<double>(geo, layout, e, site, paper_run(30.0), &piga, {}).output;
  const double slow = average_run<double>(geo, layout, e, site, paper_run(30.0), &piga, {}, general).output;
  EXPECT_NEAR(fast, slow, 1e-15 * paper_piga().coefficients[1] * 30.0);  // round-off of the K1·A swing
}

}  // namespace
}  // namespace ccal::test

namespace ccal::test {
namespace {

TEST(SpectralRule, TrialQuadratureOfTheMonteCarloIsConverged) {
  // The Monte Carlo trials reduce the runs with the rule sized for them (M = 2(degree + N) + 2 = 10 fast, 2
  // slow nodes for |ΔΩ|T ≤ 1e-3). For draws of every bundled tolerance at 3σ (ΔΩ = 1.5e-6 rad/s), its run
  // means must agree with a converged rule (M = 48, Q = 8) to 1e-12 of the output's swing K1·A: far below the
  // coefficient spread (~1e-6 of the swing) that a Monte Carlo estimates.
  const Config cfg = bundled_example();
  const Experiment ex = cfg.experiment();
  const CalibrationModel model = calibration_model(cfg);
  std::mt19937 rng(11);
  ReductionOptions converged;
  converged.quadrature.fast_nodes = 48;
  converged.quadrature.slow_nodes = 8;
  for (int draw = 0; draw < 3; ++draw) {
    const Eigen::VectorXd e = corner_draw(cfg, 3.0, rng);
    for (const ccal::Run& run : ex.plan.runs) {
      const double trial =
          average_run<double>(ex.geometry, ex.layout, e, ex.site, run, &ex.instrument, {}, model.reduction())
              .output;
      const double reference =
          average_run<double>(ex.geometry, ex.layout, e, ex.site, run, &ex.instrument, {}, converged).output;
      const double swing = ex.instrument.coefficient("K1").value() * run.g_level;
      EXPECT_NEAR(trial, reference, 1e-12 * swing) << run.name << " draw " << draw;
    }
  }
}

}  // namespace
}  // namespace ccal::test
