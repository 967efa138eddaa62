// The exact chain: nominal values, scaling laws, the factored fast path, AD against finite differences, and
// the angular-rate signs of model.md §2.2 and §5.1.
#include <gtest/gtest.h>

#include <random>

#include "kinematics_support.hpp"

namespace ccal::test {
namespace {

TEST(ExactChain, ErrorFreeGivesCentripetalAndGravity) {
  // a_i = −A cos γ, a_p = +A sin γ, a_o = +1 g, no inertial rate with the Earth switched off.
  // Tolerance 1e-13 g: a handful of roundings on numbers of size A = 30.
  const Geometry geo{2.5, 0.2, 0.05, 0.0};
  const ErrorLayout layout(2);
  const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
  const Site site = paper_site();
  for (double A : {5.0, 30.0}) {
    const double w = rate_for(A, geo.R0, site.g);
    for (double t : {0.0, 0.37, 101.3}) {
      const auto y = outputs<double>(geo, layout, e, site, w, 0.4, 1.1, PlatformMode::counter_rotating, t);
      const double gamma = 1.1 - w * t;
      EXPECT_NEAR(y[0], -A * std::cos(gamma), 1e-13 * A);
      EXPECT_NEAR(y[1], A * std::sin(gamma), 1e-13 * A);
      EXPECT_NEAR(y[2], 1.0, 1e-14);
      EXPECT_NEAR(y.tail<3>().norm(), 0.0, 1e-14);
    }
  }
}

TEST(ExactChain, LogDerivativesOfAccelerationAreOneForRadiusAndTwoForRate) {
  // a = Ω² R / g: ∂ln a/∂ln R = 1, ∂ln a/∂ln Ω = 2. Fixed platform with the IA radial (γ = π: pointing inward
  // so a_i = +A). The AD derivative is exact, so the tolerance is round-off (1e-13).
  const Geometry geo{2.5, 0.0, 0.0, 0.0};
  const ErrorLayout layout(1);
  const Site site = paper_site();
  const double w = rate_for(20.0, geo.R0, site.g);
  const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
  const auto J = ad_jacobian(geo, layout, e, site, w, 0.0, std::numbers::pi, PlatformMode::fixed, 0.0);
  const auto y = outputs<double>(geo, layout, e, site, w, 0.0, std::numbers::pi, PlatformMode::fixed, 0.0);
  EXPECT_NEAR(y[0], 20.0, 1e-12);
  EXPECT_NEAR(J(0, ch::dR_s) * geo.R0 / y[0], 1.0, 1e-13);
  EXPECT_NEAR(J(0, ch::domega) * w / y[0], 2.0, 1e-13);
}

Eigen::VectorXd random_errors(const ErrorLayout& layout, double angle, double length, unsigned seed,
                              bool dynamic) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd e(layout.size());
  for (int i = 0; i < layout.size(); ++i) {
    const int ch = layout.parameter_channel(i);
    const bool is_dynamic = channels()[ch].joint != Joint::none;
    const SourceUnit unit = layout.parameter_unit(i);
    double scale = unit == SourceUnit::rad ? angle : unit == SourceUnit::m ? length : 0.0;
    if (ch == ch::arm_stretch) scale = length / 100.0;
    if (ch == ch::domega || ch == ch::dOmega) scale = angle;
    e[i] = (is_dynamic && !dynamic) ? 0.0 : scale * u(rng);
  }
  return e;
}

TEST(StaticChain, AgreesWithTheGeneralRecursion) {
  // Two independent compositions of the same exact chain (factored closed form vs link-by-link recursion)
  // with large static errors (1e-3 rad, 1 mm) and a tilted horizontal axis. Tolerance 2e-13 g and
  // 1e-15 rad/s: round-off on inputs of size 30 g and 10 rad/s.
  const Geometry geo{2.5, 0.2, 0.05, 0.05};
  const ErrorLayout layout(1);
  Eigen::VectorXd e = random_errors(layout, 1e-3, 1e-3, 7, false);
  for (bool earth : {false, true}) {
    for (bool frozen : {false, true}) {
      const Site site = paper_site(earth);
      const ChainOptions options{frozen};
      const double w = rate_for(30.0, geo.R0, site.g) + e[ch::domega];
      const double gamma_rate = -(w + e[ch::dOmega]);
      const StaticChain<double> chain(geo, layout, e, site, w, geo.beta, options);
      for (double t : {0.0, 0.11, 7.9}) {
        JointState<double> j{0.3 + w * t, w, geo.beta, 0.0, 2.0 + gamma_rate * t, gamma_rate};
        const auto s = exact_state<double>(geo, layout, e, site, j, options);
        const auto fast = chain(j.theta1, j.gamma, j.theta1_rate, j.gamma_rate);
        EXPECT_NEAR((s.specific_force - fast.specific_force).norm(), 0.0, 2e-13) << earth << frozen << t;
        EXPECT_NEAR((s.angular_rate - fast.angular_rate).norm(), 0.0, 1e-14) << earth << frozen << t;
      }
    }
  }
}

TEST(ExactChain, AutomaticDerivativesMatchCentralDifferences) {
  // Every parameter, including harmonics of order 2 and the drive errors, at a point with errors of 1e-4.
  // Central differences with step h = 1e-6 (in the parameter's unit scaled below) have truncation error
  // O(h² f‴) ≈ 1e-12 and round-off ε·|f|/h ≈ 3e-15·30/1e-6 ≈ 1e-8 g; tolerance 5e-7 g per unit (absolute on
  // the derivative) covers both.
  const Geometry geo{2.5, 0.2, 0.05, 0.0};
  const ErrorLayout layout(2);
  const Site site = paper_site(true);
  const Eigen::VectorXd e0 = random_errors(layout, 1e-4, 1e-4, 11, true);
  const double w = rate_for(20.0, geo.R0, site.g);
  for (PlatformMode mode : {PlatformMode::counter_rotating, PlatformMode::fixed}) {
    const double t = 3.3;
    const auto J = ad_jacobian(geo, layout, e0, site, w, 0.2, 0.7, mode, t);
    for (int i = 0; i < layout.size(); ++i) {
      const double h = 1e-6;
      Eigen::VectorXd ep = e0, em = e0;
      ep[i] += h;
      em[i] -= h;
      const Eigen::Matrix<double, 6, 1> fd = (outputs<double>(geo, layout, ep, site, w, 0.2, 0.7, mode, t) -
                                              outputs<double>(geo, layout, em, site, w, 0.2, 0.7, mode, t)) /
                                             (2 * h);
      const double scale = 1.0 + J.col(i).norm();
      EXPECT_LT((J.col(i) - fd).norm(), 5e-7 * scale) << layout.parameter_id(i);
    }
  }
}

TEST(ExactChain, ZeroErrorsGiveNominalValuesToRoundOff) {
  // The Jacobian machinery at zero errors must not disturb the values: AD values equal double values exactly
  // up to round-off (1e-14 relative).
  const Geometry geo{2.5, 0.2, 0.05, 0.0};
  const ErrorLayout layout(3);
  const Site site = paper_site(true);
  const double w = rate_for(25.0, geo.R0, site.g);
  VecX<AD> e(layout.size());
  for (int i = 0; i < layout.size(); ++i) e[i] = make_dual(0.0, i % kDualWidth);
  const auto y_ad = outputs<AD>(geo, layout, e, site, w, 0.0, 0.3, PlatformMode::counter_rotating, 12.0);
  const auto y = outputs<double>(geo, layout, Eigen::VectorXd::Zero(layout.size()), site, w, 0.0, 0.3,
                                 PlatformMode::counter_rotating, 12.0);
  for (int r = 0; r < 6; ++r) EXPECT_NEAR(y_ad[r].value(), y[r], 1e-14 * (1 + std::abs(y[r])));
}

TEST(AngularRate, TiltSensitivitiesHaveThePaperSigns) {
  // model.md §5.1: ∂ω_IA/∂θx = +Ω sin γ and ∂ω_IA/∂θy = −Ω cos γ for the platform tilts (Δθx3t; Δθy2t,
  // Δθy3t), and 0 for Δθy4, Δθy5, Δθx1t, Δθz5. Exact AD derivatives at zero errors: tolerance 1e-12 rad/s.
  const Geometry geo{2.5, 0.2, 0.05, 0.0};
  const ErrorLayout layout(1);
  const Site site = paper_site();
  const double w = rate_for(20.0, geo.R0, site.g);
  const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
  for (double t : {0.0, 0.1, 0.25}) {
    const double gamma = 0.3 - w * t;
    const auto J = ad_jacobian(geo, layout, e, site, w, 0.0, 0.3, PlatformMode::counter_rotating, t);
    EXPECT_NEAR(J(3, ch::dthx3t), w * std::sin(gamma), 1e-12);
    EXPECT_NEAR(J(3, ch::dthy2t), -w * std::cos(gamma), 1e-12);
    EXPECT_NEAR(J(3, ch::dthy3t), -w * std::cos(gamma), 1e-12);
    for (int zero : {int(ch::dthy4), int(ch::dthy5), int(ch::dthx1t), int(ch::dthz5)}) EXPECT_NEAR(J(3, zero), 0.0, 1e-12);
  }
}

TEST(AngularRate, CounterRotatingPlatformDoesNotTurnInertially) {
  // With ΔΩ = 0 the platform holds its inertial heading: the instrument senses the Earth rate only,
  // ω_ie = ω_e (0, cos φ, sin φ) in ENU with ω_e = 7.2921150e-5 rad/s (WGS-84) at φ = 45.75° N, resolved on
  // IA = (cos ψ, sin ψ, 0), PA = (−sin ψ, cos ψ, 0), OA = up, where ψ = θ1(0) + φ0 = 0.3 rad is the IA's
  // azimuth from East: (ω_e cos φ sin ψ, ω_e cos φ cos ψ, ω_e sin φ). With a mismatch ΔΩ the OA component is
  // −ΔΩ more. Tolerance 1e-15 rad/s: cancellation of Ω − Ω ≈ 9 rad/s; swapping cos φ and sin φ moves each
  // component by ≥ 4e-7 rad/s, a latitude error of 0.01° by 1e-8 rad/s.
  const Geometry geo{2.5, 0.2, 0.05, 0.0};
  const ErrorLayout layout(1);
  const Site site = paper_site(true);
  const double we = 7.2921150e-5, cos_lat = std::cos(45.75 * kDeg), sin_lat = std::sin(45.75 * kDeg);
  const double psi = 0.3;
  const double w = rate_for(30.0, geo.R0, site.g);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
  auto y = outputs<double>(geo, layout, e, site, w, 0.0, 0.3, PlatformMode::counter_rotating, 5.0);
  EXPECT_NEAR(y[3], we * cos_lat * std::sin(psi), 1e-15);
  EXPECT_NEAR(y[4], we * cos_lat * std::cos(psi), 1e-15);
  EXPECT_NEAR(y[5], we * sin_lat, 1e-15);
  e[ch::dOmega] = 2e-6;
  y = outputs<double>(geo, layout, e, site, w, 0.0, 0.3, PlatformMode::counter_rotating, 5.0);
  EXPECT_NEAR(y[5], we * sin_lat - 2e-6, 1e-15);
}

}  // namespace
}  // namespace ccal::test

namespace ccal::test {
namespace {

TEST(DynamicChain, AgreesWithTheGeneralRecursion) {
  // The precomposed chain against the link-by-link recursion with every error, harmonic order 3, errors of
  // 1e-3 (100× the paper's tolerances), a tilted horizontal axis, both platform modes, frozen or not.
  // Round-off on 30 g and 10 rad/s: tolerances 2e-13 g and 1e-14 rad/s.
  // Also with some joints' error channels exactly zero, which the chain skips: a main-axis tilt (dthx1), the
  // platform's whole runout (dx3, dy3, dz3, its translation skipped) and a platform tilt (dthy3).
  const Geometry geo{2.5, 0.2, 0.05, 0.05};
  const ErrorLayout layout(3);
  Eigen::VectorXd some_zero = random_errors(layout, 1e-3, 1e-3, 17, true);
  for (const int channel : {ch::dthx1, ch::dx3, ch::dy3, ch::dz3, ch::dthy3})
    some_zero.segment(layout.harmonic_index(channel, 0, false), 2 * layout.harmonic_order() + 1).setZero();
  for (const Eigen::VectorXd& e : {random_errors(layout, 1e-3, 1e-3, 17, true), some_zero})
    for (bool frozen : {false, true}) {
      const Site site = paper_site(true);
      const ChainOptions options{frozen};
      const double w = rate_for(30.0, geo.R0, site.g) + e[ch::domega];
      const DynamicChain<double> chain(geo, layout, e, site, w, geo.beta, options);
      for (double gamma_rate : {-(w + e[ch::dOmega]), 0.0})
        for (double t : {0.0, 0.11, 7.9}) {
          const JointState<double> j{0.3 + w * t, w, geo.beta, 0.0, 2.0 + gamma_rate * t, gamma_rate};
          const auto s = exact_state<double>(geo, layout, e, site, j, options);
          const auto fast = chain(j);
          EXPECT_NEAR((s.specific_force - fast.specific_force).norm(), 0.0, 2e-13) << frozen << t;
          EXPECT_NEAR((s.angular_rate - fast.angular_rate).norm(), 0.0, 1e-14) << frozen << t;
        }
    }
}

}  // namespace
}  // namespace ccal::test
