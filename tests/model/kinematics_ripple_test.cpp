// The drives' rate ripple (docs/model.md §3.1, §2.3): closed forms of a single harmonic at the instrument and
// of the DC it leaves in a run mean, for both platform controls; the exact chain with ripple against central
// differences of the motion; the kernel of the Monte Carlo against the general reduction; the budget against
// the nonlinear re-identification.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "ccal/io/config_file.hpp"
#include "ccal/model/first_order.hpp"
#include "ccal/reduction/run_average.hpp"
#include "ccal/reduction/run_means.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "experiment_support.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

using ccal::test::kPi;

// The paper's geometry with the instrument on the platform axis (L = l = 0, β = 0), Earth rotation off, so
// that the instrument's specific force is the arm tip's acceleration plus gravity.
Geometry axis_geometry(PlatformControl control) {
  Geometry g{2.5, 0.0, 0.0, 0.0};
  g.platform_control = control;
  return g;
}

// Sets the ripple of harmonic k of a drive (relative rate r = c cos kq + s sin kq).
void set_ripple(const ErrorLayout& layout, Eigen::VectorXd& e, int channel, int k, double c, double s) {
  e[layout.harmonic_index(channel, k, false)] = c;
  e[layout.harmonic_index(channel, k, true)] = s;
}

TEST(RateRipple, SingleMainHarmonicAtTheInstrumentIsTangentialPlusCentripetal) {
  // Written out here, independent of the chain: with the main rate θ̇1 = Ω(1 + c cos θⁿ + s sin θⁿ), the arm
  // angle θ1 = θⁿ + c sin θⁿ − s cos θⁿ and θ̈1 = Ω²(s cos θⁿ − c sin θⁿ); with the IA at γ from the outward
  // radial (IA = cos γ e_r + sin γ e_t, PA = −sin γ e_r + cos γ e_t) the tip acceleration −R θ̇1² e_r + R θ̈1
  // e_t gives a_i = (−R θ̇1² cos γ + R θ̈1 sin γ)/g, a_p = (R θ̇1² sin γ + R θ̈1 cos γ)/g, a_o = 1, and ω_OA = θ̇1
  // + γ̇. Speed control: γ = γⁿ; phase-locked: γ = γⁿ − (θ1 − θⁿ). Tolerance 1e-13 g: the chain and the closed
  // form differ only in round-off of O(A) = 30 g terms.
  const ErrorLayout layout(2);
  const Site site = paper_site(false);
  const double A = 30.0, R = 2.5, w = rate_for(A, R, 9.8);
  const double c = 2e-4, s = -1.3e-4;  // large enough to be far above round-off
  for (PlatformControl control : {PlatformControl::speed, PlatformControl::phase_locked}) {
    const Geometry geo = axis_geometry(control);
    Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
    set_ripple(layout, e, ch::ripple1, 1, c, s);
    const RunMotion<double> motion =
        run_motion<double>(w, 0.4, 2.1, PlatformMode::counter_rotating, geo, layout, e);
    for (double t : {0.0, 0.37, 1.9, 123.4}) {
      const double qn = 0.4 + w * t, gn = 2.1 - w * t;
      const double delta = c * std::sin(qn) - s * std::cos(qn);
      const double rate = w * (1 + c * std::cos(qn) + s * std::sin(qn));
      const double acc = w * w * (s * std::cos(qn) - c * std::sin(qn));
      const bool locked = control == PlatformControl::phase_locked;
      const double gamma = locked ? gn - delta : gn;
      const double gamma_rate = locked ? -rate : -w;
      const auto state = exact_state<double>(geo, layout, e, site, motion.at(t));
      const double a_i = (-R * rate * rate * std::cos(gamma) + R * acc * std::sin(gamma)) / 9.8;
      const double a_p = (R * rate * rate * std::sin(gamma) + R * acc * std::cos(gamma)) / 9.8;
      EXPECT_NEAR(state.specific_force[0], a_i, 1e-13) << "t = " << t;
      EXPECT_NEAR(state.specific_force[1], a_p, 1e-13) << "t = " << t;
      EXPECT_NEAR(state.specific_force[2], 1.0, 1e-13);
      EXPECT_NEAR(state.angular_rate[2], rate + gamma_rate, 1e-13);
      EXPECT_NEAR(state.angular_rate[0], 0.0, 1e-15);
    }
  }
}

// Central differences of the instrument's position: five-point stencils, step h = 1e-3 s. Truncation
// h⁴/90·|p⁽⁶⁾| ≈ 1e-12·RΩ⁶/90 ≈ 3e-8 m/s² at 25 g; round-off of the positions (the joint angle's ulp at
// θ1 ≈ 500 rad, 6e-14 rad, times R) amplified by 64/(12 h²): ≈ 1e-7 m/s² late in a run.
Eigen::Vector3d central_acceleration(const std::function<Eigen::Vector3d(double)>& p, double t, double h) {
  return (-p(t + 2 * h) + 16 * p(t + h) - 30 * p(t) + 16 * p(t - h) - p(t - 2 * h)) / (12 * h * h);
}
Eigen::Vector3d central_velocity(const std::function<Eigen::Vector3d(double)>& p, double t, double h) {
  return (-p(t + 2 * h) + 8 * p(t + h) - 8 * p(t - h) + p(t - 2 * h)) / (12 * h);
}

TEST(RateRipple, ExactChainEqualsDifferentiatedMotion) {
  // Both drives ripple (harmonics 1 and 2, 1e-3 relative, so that the ripple's accelerations, ~0.3 m/s², are
  // far above the stencil's error), with lever arms and every other dynamic error: the chain's velocity and
  // acceleration must be the time derivatives of its own positions. Tolerances from the stencil errors
  // above: 1e-7 m/s (velocity), 5e-7 m/s² (acceleration), against ripple accelerations of ~0.3 m/s².
  const ErrorLayout layout(2);
  Eigen::VectorXd e = random_errors(layout, 1e-5, 11);
  for (int ch : {int(ch::ripple1), int(ch::ripple3)}) {
    e[layout.harmonic_index(ch, 0, false)] = 0.0;
    set_ripple(layout, e, ch, 1, 1e-3, -6e-4);
    set_ripple(layout, e, ch, 2, 4e-4, 7e-4);
  }
  const Site site = paper_site(false);
  for (PlatformControl control : {PlatformControl::speed, PlatformControl::phase_locked}) {
    Geometry geo{2.5, 0.2, 0.05, 0.0};
    geo.platform_control = control;
    const RunMotion<double> motion = run_motion<double>(rate_for(25.0, 2.5, 9.8), 0.2, 1.1,
                                                        PlatformMode::counter_rotating, geo, layout, e);
    auto position = [&](double t) {
      return Eigen::Vector3d(exact_state<double>(geo, layout, e, site, motion.at(t)).position);
    };
    for (double t : {3.0, 47.3}) {
      const auto state = exact_state<double>(geo, layout, e, site, motion.at(t));
      EXPECT_LT((central_velocity(position, t, 1e-3) - state.velocity).norm(), 1e-7) << t;
      EXPECT_LT((central_acceleration(position, t, 1e-3) - state.acceleration).norm(), 5e-7) << t;
    }
  }
}

// ⟨a_i⟩ of one counter-rotating run on the instrument axis (K1 = 1 g⁻¹ instrument: the regressor of K1),
// with the ripple `e`, over a whole number of revolutions.
double mean_input(const Geometry& geo, const ErrorLayout& layout, const Eigen::VectorXd& e, double A,
                  double phi0, double theta1_0, int revolutions) {
  ccal::Run run;
  run.g_level = A;
  run.duration = revolutions * 2 * kPi / rate_for(A, geo.R0, 9.8);
  run.initial_phase = phi0;
  run.arm_azimuth = theta1_0;
  const std::vector<TermSpec> k1{*parse_term("K1")};
  return average_run<double>(geo, layout, e, paper_site(false), run, nullptr, k1).regressors[0];
}

// The odd part in the ripple: (f(ε) − f(−ε))/2 leaves the first-order DC with an O(ε³) error.
double odd_part(const std::function<double(double)>& f, double eps) { return (f(eps) - f(-eps)) / 2; }

TEST(RateRipple, FirstHarmonicDcOfTheMainAxisClosedForm) {
  // model.md §3.1: a first-harmonic main-axis ripple r = c cos θⁿ + s sin θⁿ (angle δ = c sin θⁿ − s cos θⁿ)
  // under speed control leaves over whole revolutions the DC −(A/2)(c cos ψ0 + s sin ψ0) on a_i
  // (ψ0 = θ1(0) + φ0): centripetal +A(…), tangential −A/2(…), i.e. (A/2)(ĉ sin ψ0 − ŝ cos ψ0) in the angle
  // coefficients ĉ = −s, ŝ = c. Phase-locked, the heading term −A/2(…) cancels it: no DC. Harmonics k ≥ 2
  // leave none in either mode. Tolerance: O(A ε³) ≈ 1e-13 g after the odd part, plus the rule's round-off.
  const ErrorLayout layout(2);
  const double A = 20.0, phi0 = 1.2, theta1_0 = 0.5, psi0 = theta1_0 + phi0, eps = 1e-5;
  for (PlatformControl control : {PlatformControl::speed, PlatformControl::phase_locked}) {
    const Geometry geo = axis_geometry(control);
    for (auto [c, s] : {std::pair{1.0, 0.0}, std::pair{0.0, 1.0}, std::pair{0.6, -0.8}}) {
      auto dc = [&](int k) {
        return odd_part(
            [&](double x) {
              Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
              set_ripple(layout, e, ch::ripple1, k, c * x, s * x);
              return mean_input(geo, layout, e, A, phi0, theta1_0, 7);
            },
            eps);
      };
      const double expected = control == PlatformControl::speed
                                  ? -(A / 2) * eps * (c * std::cos(psi0) + s * std::sin(psi0))
                                  : 0.0;
      EXPECT_NEAR(dc(1), expected, 1e-12) << "c = " << c << ", s = " << s;
      EXPECT_NEAR(dc(2), 0.0, 1e-12) << "second harmonic, c = " << c << ", s = " << s;
    }
  }
}

TEST(RateRipple, FirstHarmonicDcOfThePlatformClosedForm) {
  // A platform ripple r3 = c cos γⁿ + s sin γⁿ turns the IA from the radial by δ3 = c sin γⁿ − s cos γⁿ:
  // a_i = −A cos(γⁿ + δ3) ≈ −A cos γⁿ + A δ3 sin γⁿ, whose DC over whole revolutions is (A/2) c, in both
  // controls (a phase-locked platform tracks the main axis with this ripple as its error). A fixed platform
  // does not turn and has none.
  const ErrorLayout layout(1);
  const double A = 15.0, eps = 1e-5;
  for (PlatformControl control : {PlatformControl::speed, PlatformControl::phase_locked}) {
    const Geometry geo = axis_geometry(control);
    for (auto [c, s] : {std::pair{1.0, 0.0}, std::pair{0.0, 1.0}}) {
      const double dc = odd_part(
          [&](double x) {
            Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
            set_ripple(layout, e, ch::ripple3, 1, c * x, s * x);
            return mean_input(geo, layout, e, A, 0.9, 0.3, 5);
          },
          eps);
      EXPECT_NEAR(dc, (A / 2) * c * eps, 1e-12) << "c = " << c << ", s = " << s;
    }
  }
}

TEST(RateRipple, ZeroRippleLeavesTheMotionUntouched) {
  // Exactly zero ripple coefficients build no ripple at all (the same joint states bit for bit).
  const ErrorLayout layout(2);
  Eigen::VectorXd e = random_errors(layout, 1e-5, 3);
  for (int ch : {int(ch::ripple1), int(ch::ripple3)})
    for (int i = 0; i < 5; ++i) e[layout.harmonic_index(ch, 0, false) + i] = 0.0;
  for (PlatformControl control : {PlatformControl::speed, PlatformControl::phase_locked}) {
    Geometry geo{2.5, 0.0, 0.0, 0.0};
    geo.platform_control = control;
    const auto with = run_motion<double>(8.0, 0.1, 0.2, PlatformMode::counter_rotating, geo, layout, e);
    const auto without = run_motion<double>(8.0, 0.1, 0.2, PlatformMode::counter_rotating, 0.0, e);
    EXPECT_FALSE(with.has_ripple());
    const auto a = with.at(12.3), b = without.at(12.3);
    EXPECT_EQ(a.theta1, b.theta1);
    EXPECT_EQ(a.gamma, b.gamma);
    EXPECT_EQ(a.theta1_rate, b.theta1_rate);
    EXPECT_EQ(a.gamma_rate, b.gamma_rate);
    EXPECT_EQ(a.theta1_acc, 0.0);
    EXPECT_EQ(a.gamma_acc, 0.0);
  }
}

TEST(RateRipple, FirstOrderColumnsEqualTheChainsDerivatives) {
  // exact_first_order's ripple columns (closed form for β = 0) against forward-mode derivatives of the exact
  // chain, for both controls and a fixed platform, at several instants. Tolerance 1e-11 per unit: both are
  // exact derivatives; they differ in round-off of O(A) terms.
  const ErrorLayout layout(2);
  const Site site = paper_site(true);
  const double w = rate_for(20.0, 2.5, 9.8);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(layout.size());
  for (PlatformControl control : {PlatformControl::speed, PlatformControl::phase_locked})
    for (PlatformMode mode : {PlatformMode::counter_rotating, PlatformMode::fixed}) {
      Geometry geo{2.5, 0.2, 0.05, 0.0};
      geo.platform_control = control;
      const RunMotion<double> nominal = run_motion<double>(w, 0.4, 1.3, mode, geo, layout, zero);
      for (double t : {0.0, 0.77, 31.0}) {
        const auto fo = exact_first_order(geo, layout, site, nominal, mode, t);
        const auto J = ad_jacobian(geo, layout, zero, site, w, 0.4, 1.3, mode, t);
        for (int ch : {int(ch::ripple1), int(ch::ripple3)})
          for (int k = 1; k <= 2; ++k)
            for (bool sine : {false, true}) {
              const int i = layout.harmonic_index(ch, k, sine);
              EXPECT_LT((fo.sensitivity.col(i) - J.col(i)).lpNorm<Eigen::Infinity>(), 1e-11)
                  << layout.parameter_id(i) << " t = " << t;
            }
      }
    }
}

TEST(RateRipple, KernelEqualsTheGeneralReduction) {
  // The Monte Carlo's kernel with both ripples (and every bundled tolerance at ±3σ) against average_run, in
  // both controls and with ripples above the small-angle threshold (the one-node loops). Same 1e-14-of-swing
  // tolerance as tests/reduction/run_means_test.cpp: same chain and rule, another order of operations.
  for (PlatformControl control : {PlatformControl::speed, PlatformControl::phase_locked})
    for (double size : {1e-5, 3e-3}) {
      Config cfg = bundled_example();
      cfg.centrifuge.geometry.platform_control = control;
      Experiment ex = cfg.experiment();
      ex.plan.runs.back().mode = PlatformMode::fixed;
      ex.plan.runs.back().terminal_phase.reset();
      ex.plan.runs.back().initial_phase = 0.4;
      const CalibrationModel model = calibration_model(cfg);
      std::mt19937 rng(17);
      Eigen::VectorXd e = corner_draw(cfg, 3.0, rng);
      set_ripple(ex.layout, e, ch::ripple1, 1, size, -0.7 * size);
      set_ripple(ex.layout, e, ch::ripple3, 1, -0.4 * size, 0.9 * size);
      const RunMeanKernel kernel(ex.geometry, ex.layout, ex.site, ex.plan.runs, ex.instrument,
                                 model.reduction());
      std::vector<double> means(ex.plan.runs.size());
      kernel.means(std::span<const double>(e.data(), std::size_t(e.size())), means);
      for (std::size_t r = 0; r < ex.plan.runs.size(); ++r) {
        const double general = average_run<double>(ex.geometry, ex.layout, e, ex.site, ex.plan.runs[r],
                                                   &ex.instrument, {}, model.reduction())
                                   .output;
        const double swing = std::abs(ex.instrument.coefficient("K1").value()) * ex.plan.runs[r].g_level;
        EXPECT_NEAR(means[r], general, 1e-14 * swing) << "run " << r << ", ripple " << size;
      }
    }
}

TEST(RateRipple, BudgetRowsEqualTheNonlinearReidentification) {
  // Each ripple source's budget effect J·u against the coefficients identified from the exact nonlinear
  // pipeline with the ripple applied at ±u (odd part): equal to O(ε²) relative, with ε ~ 1e-5: 1e-4 relative
  // of the largest effect of the coefficient, in both controls.
  for (PlatformControl control : {PlatformControl::speed, PlatformControl::phase_locked}) {
    Config cfg = bundled_example();
    cfg.centrifuge.geometry.platform_control = control;
    cfg.tolerances.clear();
    for (int ch : {int(ch::ripple1), int(ch::ripple3)})
      for (bool sine : {false, true}) {
        Tolerance t;
        t.parameter = cfg.centrifuge.layout.harmonic_index(ch, 1, sine);
        t.id = cfg.centrifuge.layout.parameter_id(t.parameter);
        t.bound = 1e-5;
        cfg.tolerances.push_back(t);
      }
    const BudgetDetail b = compute_budget(cfg);
    const Experiment ex = cfg.experiment();
    for (const SourceBudget& s : b.sources) {
      auto identified = [&](double x) {
        Eigen::VectorXd e = Eigen::VectorXd::Zero(ex.layout.size());
        e[s.parameter] = x;
        return Eigen::Vector3d(identified_deg(ex, e, cfg.identification, ModelMode::exact) * kDeg);
      };
      const Eigen::Vector3d reidentified =
          (identified(s.standard_uncertainty) - identified(-s.standard_uncertainty)) / 2;
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(s.effect[k], reidentified[k], 1e-4 * std::abs(reidentified[k]) + 1e-18)
            << s.id << " " << b.coefficients[std::size_t(k)];
      EXPECT_GT(s.effect.cwiseAbs().maxCoeff(), 0.0) << s.id;
    }
  }
}

}  // namespace
}  // namespace ccal::test
