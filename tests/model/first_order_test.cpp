// First-order closed forms against the exact chain: model.md §6.1 V5/V5b coefficients, the linearisation
// identity (closed-form perturbation = AD Jacobian), and second-order convergence of exact − first order.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <iostream>
#include <map>
#include <random>

#include "ccal/model/first_order.hpp"
#include "kinematics_support.hpp"

namespace ccal::test {
namespace {

struct Coefficients {
  double c0, cc, cs;
};

// a_i sensitivity of one parameter as c0 + cc cos γ + cs sin γ, fitted over one revolution of a
// counter-rotating run (8 instants). `residual` is the largest misfit: the form is exact for static errors.
template <class Sensitivity>
Coefficients fit_harmonics(Sensitivity sensitivity_at, double w, double phi0, double* residual) {
  const double period = 2 * std::numbers::pi / w;
  Eigen::MatrixXd H(8, 3);
  Eigen::VectorXd y(8);
  for (int k = 0; k < 8; ++k) {
    const double t = k * period / 8, gamma = phi0 - w * t;
    H.row(k) << 1.0, std::cos(gamma), std::sin(gamma);
    y[k] = sensitivity_at(t);
  }
  const Eigen::Vector3d c = H.colPivHouseholderQr().solve(y);
  *residual = (H * c - y).lpNorm<Eigen::Infinity>();
  return {c[0], c[1], c[2]};
}

class V5 : public ::testing::Test {
 protected:
  const Geometry geo{2.5, 0.20, 0.05, 0.0};
  const ErrorLayout layout{1};
  const Site site = paper_site(false);
  const double w = rate_for(20.0, 2.5, 9.8);  // A = 20 g
  const double phi0 = 0.3;

  Coefficients exact(int channel, bool frozen, double* residual) const {
    const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
    return fit_harmonics(
        [&](double t) {
          return ad_jacobian(geo, layout, e, site, w, 0.0, phi0, PlatformMode::counter_rotating, t,
                             ChainOptions{frozen})(0, channel);
        },
        w, phi0, residual);
  }
};

TEST_F(V5, ExactAndFrozenCoefficientsOfEverySource) {
  // model.md §6.1 V5 (A = 20 g, R0 = 2.5 m, L = 0.20 m, l = 0.05 m, φ0 = 0.3, arm on x0 at t = 0).
  // Derivatives are exact (AD); the only error is round-off in the 8-point fit: tolerance 1e-10 g/unit.
  struct Row {
    int channel;
    Coefficients exact, frozen;
  };
  const double s = std::sin(0.3), c = std::cos(0.3);
  const std::vector<Row> rows = {
      {ch::dthz5, {0, 0, 20}, {0, 0, 20}},     {ch::dy2t, {0, 0, -8}, {0, 0, -8}},
      {ch::dy3t, {0, 0, -8}, {0, 0, -8}},      {ch::dR_s, {0, -8, 0}, {0, -8, 0}},
      {ch::dthy2t, {0, -3, 0}, {0, -3, 0}},    {ch::dthy3t, {0, -3, 0}, {0, -3, 0}},
      {ch::dthx3t, {0, 0, 3}, {0, 0, 3}},      {ch::dthy4, {-1.0, 0, 0}, {-1.4, 0, 0}},
      {ch::dthy5, {-1.0, 0, 0}, {-1.0, 0, 0}}, {ch::dx5, {0, 0, 0}, {-8, 0, 0}},
      {ch::dthx1t, {s, 0, 0}, {s, 0, 0}},      {ch::dthy1t, {-c, 0, 0}, {-c, 0, 0}},
  };
  for (const Row& row : rows) {
    for (bool frozen : {false, true}) {
      double residual = 0;
      const Coefficients got = exact(row.channel, frozen, &residual);
      const Coefficients& want = frozen ? row.frozen : row.exact;
      const std::string what = std::string(channels()[row.channel].id) + (frozen ? " frozen" : " exact");
      EXPECT_NEAR(got.c0, want.c0, 1e-10) << what;
      EXPECT_NEAR(got.cc, want.cc, 1e-10) << what;
      EXPECT_NEAR(got.cs, want.cs, 1e-10) << what;
      EXPECT_LT(residual, 1e-10) << what << ": not of the form c0 + cc cos γ + cs sin γ";
    }
  }
}

TEST_F(V5, HorizontalAxisDynamicErrorsAtFixedBetaActLikeTheirStaticTwins) {
  // β is constant, so Δθz2(β), Δy2(β), Δx2(β), Δθy2(β) are constants equal to their c0 coefficient.
  const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
  const auto J = ad_jacobian(geo, layout, e, site, w, 0.0, phi0, PlatformMode::counter_rotating, 0.4);
  EXPECT_NEAR(J(0, layout.harmonic_index(ch::dthz2, 0, false)), J(0, ch::dthz5), 1e-12);
  EXPECT_NEAR(J(0, layout.harmonic_index(ch::dy2, 0, false)), J(0, ch::dy2t), 1e-12);
  EXPECT_NEAR(J(0, layout.harmonic_index(ch::dx2, 0, false)), J(0, ch::dR_s), 1e-12);
  EXPECT_NEAR(J(0, layout.harmonic_index(ch::dthy2, 0, false)), J(0, ch::dthy2t), 1e-12);
}

TEST_F(V5, CoriolisIsACosGammaTermOfTheCentripetalSign) {
  // Earth on minus Earth off: −(2 ω_e R0 Ω sin φ / g) cos γ = −2.3597e-4 g × cos γ at 45.75° N (model.md E
  // notes). The difference also holds O(ω_e²R0/g) ≈ 1e-9 g terms; tolerance 5e-9 g.
  const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
  const Site earth = paper_site(true);
  const double amplitude = 2 * earth.earth_rate * geo.R0 * w * std::sin(earth.latitude) / earth.g;
  EXPECT_NEAR(amplitude, 2.3597e-4, 5e-8);  // model.md quotes 5 digits
  for (double t : {0.0, 0.2, 0.5}) {
    const double gamma = phi0 - w * t;
    const double with =
        outputs<double>(geo, layout, e, earth, w, 0.0, phi0, PlatformMode::counter_rotating, t)[0];
    const double without =
        outputs<double>(geo, layout, e, site, w, 0.0, phi0, PlatformMode::counter_rotating, t)[0];
    EXPECT_NEAR(with - without, -amplitude * std::cos(gamma), 5e-9);
  }
}

TEST(V5b, WithoutLeverArmsTheFrozenChainIsThePaperForm) {
  // model.md V5b: L = l = 0, frozen-γ: Δθy2t cc = −1, Δθx3t cs = +1, Δθy4 c0 = −1, and every paper item
  // equals paper_first_order at every instant. Both are first-order exact: tolerance 1e-11 g/unit.
  const Geometry geo{2.5, 0.0, 0.0, 0.0};
  const ErrorLayout layout(2);
  const Site site = paper_site(false);
  const double w = rate_for(20.0, geo.R0, site.g);
  const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
  for (double t : {0.0, 0.13, 0.29}) {
    const auto J = ad_jacobian(geo, layout, e, site, w, 0.0, 0.3, PlatformMode::counter_rotating, t, {true});
    const RunMotion<double> run = run_motion<double>(w, 0.0, 0.3, PlatformMode::counter_rotating, 0.0, e);
    const auto paper = paper_first_order(geo, layout, site, run.at(t), {.lever_arms = true});
    const double gamma = 0.3 - w * t;
    EXPECT_NEAR(J(0, ch::dthy2t), -std::cos(gamma), 1e-11);
    EXPECT_NEAR(J(0, ch::dthx3t), std::sin(gamma), 1e-11);
    EXPECT_NEAR(J(0, ch::dthy4), -1.0, 1e-11);
    for (int i = 0; i < layout.size(); ++i) {
      const int ch = layout.parameter_channel(i);
      const Channel& c = channels()[ch];
      if (c.link == Link::main_sleeve || c.link == Link::main_axis || c.link == Link::drive) continue;
      if (c.kind == ErrorKind::translation_z || ch == ch::dthx4 || ch == ch::dthx5 || ch == ch::dy5) continue;
      EXPECT_NEAR(J(0, i), paper.sensitivity(0, i), 1e-11) << layout.parameter_id(i) << " t=" << t;
    }
  }
}

TEST(ExactFirstOrder, ClosedFormPerturbationEqualsTheJacobianOfTheExactChain) {
  // The small-twist closed form and AD through the exact chain are independent derivations of the same
  // linearisation: all six outputs, every parameter (harmonic order 3), both platform modes, a tilted
  // horizontal axis, Earth rotation on. Tolerance 1e-11 per unit (round-off on lever arms of a few metres
  // times rates of 10 rad/s squared).
  for (double beta : {0.0, 0.3}) {
    const Geometry geo{2.5, 0.2, 0.05, beta};
    const ErrorLayout layout(3);
    const Site site = paper_site(true);
    const double w = rate_for(15.0, geo.R0, site.g);
    const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
    for (PlatformMode mode : {PlatformMode::counter_rotating, PlatformMode::fixed}) {
      const RunMotion<double> run = run_motion<double>(w, 0.4, 1.3, mode, beta, e);
      for (double t : {0.0, 2.71}) {
        const auto J = ad_jacobian(geo, layout, e, site, w, 0.4, 1.3, mode, t);
        const auto fo = exact_first_order(geo, layout, site, run, mode, t);
        const auto nominal = outputs<double>(geo, layout, e, site, w, 0.4, 1.3, mode, t);
        EXPECT_LT((fo.nominal - nominal).norm(), 1e-12);
        for (int i = 0; i < layout.size(); ++i) {
          // Drive columns (rates and ripple) for β ≠ 0 come from central differences (step 1e-7): tolerance
          // 1e-6 there.
          const bool fd = beta != 0.0 && channels()[layout.parameter_channel(i)].link == Link::drive;
          EXPECT_LT((J.col(i) - fo.sensitivity.col(i)).norm(), fd ? 1e-6 : 1e-11)
              << layout.parameter_id(i) << " beta=" << beta << " mode=" << int(mode) << " t=" << t;
        }
      }
    }
  }
}

// Natural scale of a parameter for the convergence test: 1 rad, R0, Ω, R0/Ω² for arm stretch, 1 for a ripple.
double natural_scale(const ErrorLayout& layout, int i, double R0, double w) {
  switch (layout.parameter_unit(i)) {
    case SourceUnit::rad:
      return 1.0;
    case SourceUnit::m:
      return R0;
    case SourceUnit::rad_per_s:
      return w;
    case SourceUnit::m_per_rad_per_s_squared:
      return R0 / (w * w);
    case SourceUnit::relative:  // a relative rate ripple
      return 1.0;
  }
  return 1.0;
}

TEST(ExactFirstOrder, ResidualOfTheLinearisationShrinksAsEpsilonSquared) {
  // For every source, r(ε) = |exact(ε) − nominal − ε·sensitivity| must be O(ε²): halving ε quarters it.
  // Which sources are exactly linear is decided here from the physics, not from the residual: a translation
  // (static or dynamic, and the arm stretch c·θ̇1², linear in c) shifts the instrument rigidly, so position,
  // velocity and acceleration are linear in it and r is round-off: below 1e-12 g (the outputs are ~20 g and
  // ~9 rad/s, a few ulps each). Every rotation and drive error with an effect is genuinely nonlinear: r must
  // stand above round-off (1e-11) at ε = 1e-2 … 1e-4 of the natural scale and r(ε)/r(ε/2) lie in [3.8, 4.2]
  // (a third-order term changes it by O(ε)). A wrong sensitivity leaves a first-order residual, ratio 2.
  const Geometry geo{2.5, 0.2, 0.05, 0.0};
  const ErrorLayout layout(2);
  const Site site = paper_site(true);
  const double w = rate_for(20.0, geo.R0, site.g);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(layout.size());
  int quadratic = 0;
  for (PlatformMode mode : {PlatformMode::counter_rotating, PlatformMode::fixed}) {
    const RunMotion<double> run = run_motion<double>(w, 0.2, 0.9, mode, 0.0, zero);
    const double t = 1.234;
    const auto fo = exact_first_order(geo, layout, site, run, mode, t);
    for (int i = 0; i < layout.size(); ++i) {
      const double scale = natural_scale(layout, i, geo.R0, w);
      auto residual = [&](double eps) {
        Eigen::VectorXd e = zero;
        e[i] = eps * scale;
        const auto y = outputs<double>(geo, layout, e, site, w, 0.2, 0.9, mode, t);
        return (y - fo.nominal - fo.sensitivity.col(i) * e[i]).norm();
      };
      const ErrorKind k = channels()[layout.parameter_channel(i)].kind;
      const bool rigid_shift = k == ErrorKind::translation_x || k == ErrorKind::translation_y ||
                               k == ErrorKind::translation_z || k == ErrorKind::arm_stretch;
      const double linear = (fo.sensitivity.col(i) * scale).norm();
      if (rigid_shift || linear == 0.0) {
        // linear == 0: e.g. a cos/sin pair's sine coefficient where sin kq = 0, or ΔΩ on a fixed platform.
        for (double eps : {1e-2, 1e-3})
          EXPECT_LT(residual(eps), 1e-12) << layout.parameter_id(i) << " eps=" << eps;
        continue;
      }
      for (double eps : {1e-2, 1e-3, 1e-4}) {
        const double r1 = residual(eps), r2 = residual(eps / 2);
        EXPECT_GT(r2, 1e-11) << layout.parameter_id(i) << " eps=" << eps;
        EXPECT_NEAR(r1 / r2, 4.0, 0.2) << layout.parameter_id(i) << " eps=" << eps << " r1=" << r1;
      }
      ++quadratic;
    }
  }
  // Both modes together check 2 × (rotations and drive errors with an effect): at least the static rotations
  // (10), the two drive rates on the counter-rotating platform, and the wobbles' c0 terms.
  EXPECT_GE(quadratic, 20);
  std::cout << "sources with a checked ε² residual (both modes): " << quadratic << "\n";
}

TEST(PaperForm, NumbersOfModelMdSection22) {
  // Spot values of the paper's first-order form at A = 20 g, L = 0.2 m, l = 0.05 m (model.md §2.2 check):
  // −3 for θy, +3 for θx, −1.4 for Δθy4 with lever arms; −1, +1, −1 without. Exact arithmetic: 1e-12.
  const Geometry geo{2.5, 0.2, 0.05, 0.0};
  const ErrorLayout layout(1);
  const Site site = paper_site(false);
  const double w = rate_for(20.0, geo.R0, site.g);
  JointState<double> j{0.0, w, 0.0, 0.0, 0.0, -w};  // γ = 0: cos γ = 1
  auto with = paper_first_order(geo, layout, site, j, {.lever_arms = true});
  auto without = paper_first_order(geo, layout, site, j, {.lever_arms = false});
  EXPECT_NEAR(with.sensitivity(0, ch::dthy3t), -3.0, 1e-12);
  EXPECT_NEAR(without.sensitivity(0, ch::dthy3t), -1.0, 1e-12);
  EXPECT_NEAR(with.sensitivity(0, ch::dthy4), -1.4, 1e-12);
  EXPECT_NEAR(without.sensitivity(0, ch::dthy4), -1.0, 1e-12);
  j.gamma = std::numbers::pi / 2;  // sin γ = 1
  with = paper_first_order(geo, layout, site, j, {.lever_arms = true});
  EXPECT_NEAR(with.sensitivity(0, ch::dthx3t), 3.0, 1e-12);
  EXPECT_NEAR(with.sensitivity(3, ch::dthx3t), w, 1e-12);
}

}  // namespace
}  // namespace ccal::test
