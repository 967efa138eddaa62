// Where gravity and the centripetal input land on IA, PA and OA for each of the four mountings (model.md §6),
// from closed forms written here: with no errors and the Earth switched off, the specific force in frame 5
// is f/g = −A x̂1 + ẑ0 (the arm pulls the instrument towards the main axis; at rest f = +g z0), and frame 5
// is the arm frame turned by γ about z, so its components are (−A cos γ, +A sin γ, 1). Each mounting takes
// its IA, PA, OA from ±x5, ±y5, ±z5 (model/plan.hpp), so every sign and every permutation is fixed here.
#include "ccal/model/plan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ccal/model/sensed_input.hpp"
#include "kinematics_support.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

using ccal::test::kPi;

struct Axes {
  Mounting mounting;
  // The instrument input (IA, PA, OA) for f5 = (x, y, z) in frame-5 components.
  Eigen::Vector3d (*from_frame5)(const Eigen::Vector3d&);
};

const Axes kAxes[] = {
    {Mounting::ia_horizontal, [](const Eigen::Vector3d& f) { return Eigen::Vector3d(f.x(), f.y(), f.z()); }},
    {Mounting::ia_reversed, [](const Eigen::Vector3d& f) { return Eigen::Vector3d(-f.x(), -f.y(), f.z()); }},
    {Mounting::pa_vertical, [](const Eigen::Vector3d& f) { return Eigen::Vector3d(f.x(), f.z(), -f.y()); }},
    {Mounting::ia_vertical, [](const Eigen::Vector3d& f) { return Eigen::Vector3d(f.z(), f.x(), f.y()); }},
};

CentrifugeModel error_free() { return CentrifugeModel(Geometry{2.5, 0.0, 0.0, 0.0}, 1); }

Run run_with(Mounting m, PlatformMode mode, double A, double phi0) {
  Run r;
  r.name = "r";
  r.g_level = A;
  r.duration = 100.0;
  r.mode = mode;
  r.initial_phase = phi0;
  r.mounting = m;
  return r;
}

TEST(Mountings, GravityAndCentripetalInputOnEveryAxisOfAFixedPlatform) {
  // Fixed platform, γ = φ0: φ0 = 0 puts x5 radially outward (f5 = (−A, 0, 1)), φ0 = π inward ((+A, 0, 1)),
  // φ0 = π/2 tangential ((0, +A, 1)). Each axis of each mounting therefore reads −A, +A, 0 or ±1 g exactly.
  // Tolerance 1e-12 g: round-off of cos/sin at multiples of π/2 times A = 10 (1e-15 relative).
  const Site site = paper_site(false);
  const double A = 10.0;
  for (const Axes& axes : kAxes)
    for (double phi0 : {0.0, kPi / 2, kPi, 1.1}) {
      const Eigen::Vector3d f5(-A * std::cos(phi0), A * std::sin(phi0), 1.0);
      const Eigen::Vector3d want = axes.from_frame5(f5);
      const auto r =
          evaluate_force(site, error_free(), run_with(axes.mounting, PlatformMode::fixed, A, phi0), 3.0);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(r.specific_force[k], want[k], 1e-12)
            << mounting_name(axes.mounting) << " φ0=" << phi0 << " axis "
            << "IPO"[k];
    }
}

TEST(Mountings, SpelledOutSignsOfThePublishedConvention) {
  // The same facts as single numbers, so that a sign error cannot hide in the table above: at φ0 = 0 on a
  // fixed platform (x5 outward, y5 tangential, z5 up):
  //   ia_horizontal: IA −A, PA 0, OA +1;   ia_reversed: IA +A, PA 0, OA +1;
  //   pa_vertical:   IA −A, PA +1 (up), OA 0;   ia_vertical: IA +1 (up), PA −A, OA 0.
  // and at φ0 = π/2 (x5 tangential, y5 inward) the inward pull +A appears on y5:
  //   pa_vertical: OA = −y5 reads −A;   ia_vertical: OA = y5 reads +A.
  const Site site = paper_site(false);
  const double A = 20.0, tol = 1e-12;  // round-off only (see above)
  auto f = [&](Mounting m, double phi0) {
    return evaluate_force(site, error_free(), run_with(m, PlatformMode::fixed, A, phi0), 0.0).specific_force;
  };
  EXPECT_NEAR(f(Mounting::ia_horizontal, 0)[0], -A, tol);
  EXPECT_NEAR(f(Mounting::ia_horizontal, 0)[2], 1.0, tol);
  EXPECT_NEAR(f(Mounting::ia_reversed, 0)[0], A, tol);
  EXPECT_NEAR(f(Mounting::pa_vertical, 0)[0], -A, tol);
  EXPECT_NEAR(f(Mounting::pa_vertical, 0)[1], 1.0, tol);
  EXPECT_NEAR(f(Mounting::pa_vertical, 0)[2], 0.0, tol);
  EXPECT_NEAR(f(Mounting::ia_vertical, 0)[0], 1.0, tol);
  EXPECT_NEAR(f(Mounting::ia_vertical, 0)[1], -A, tol);
  EXPECT_NEAR(f(Mounting::ia_vertical, 0)[2], 0.0, tol);
  EXPECT_NEAR(f(Mounting::pa_vertical, kPi / 2)[2], -A, tol);
  EXPECT_NEAR(f(Mounting::ia_vertical, kPi / 2)[2], A, tol);
  EXPECT_NEAR(f(Mounting::ia_vertical, kPi / 2)[0], 1.0, tol);
}

TEST(Mountings, CounterRotatingPlatformAtAnyInstant) {
  // Counter-rotating, γ(t) = φ0 − Ω t with Ω = √(A g / R0): the same closed form at γ(t) for t well into
  // the run (Ω t ≈ 600 rad, so the phase carries ~1e-13 rad of round-off: tolerance 1e-11 g at A = 30).
  const Site site = paper_site(false);
  const double A = 30.0, phi0 = 0.4, t = 97.3;
  const double rate = std::sqrt(A * site.g / 2.5);
  const double gamma = phi0 - rate * t;
  const Eigen::Vector3d f5(-A * std::cos(gamma), A * std::sin(gamma), 1.0);
  for (const Axes& axes : kAxes) {
    const auto r = evaluate_force(site, error_free(),
                                  run_with(axes.mounting, PlatformMode::counter_rotating, A, phi0), t);
    const Eigen::Vector3d want = axes.from_frame5(f5);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(r.specific_force[k], want[k], 1e-11) << mounting_name(axes.mounting) << " axis "
                                                       << "IPO"[k];
  }
}

TEST(Mountings, AngularRateOfAFixedPlatformLandsOnTheVerticalAxis) {
  // Fixed platform, Earth off: the instrument turns with the arm at Ω about z5 only, so ω5 = (0, 0, Ω):
  // ia_horizontal and ia_reversed read it on OA, pa_vertical on PA (+Ω), ia_vertical on IA (+Ω).
  // Tolerance 1e-13 rad/s: round-off on Ω ≈ 8.9 rad/s.
  const Site site = paper_site(false);
  const double A = 20.0;
  const double rate = std::sqrt(A * site.g / 2.5);
  for (const Axes& axes : kAxes) {
    const auto r =
        evaluate_force(site, error_free(), run_with(axes.mounting, PlatformMode::fixed, A, 0.7), 1.0);
    const Eigen::Vector3d want = axes.from_frame5(Eigen::Vector3d(0.0, 0.0, rate));
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(r.angular_rate[k], want[k], 1e-13) << mounting_name(axes.mounting) << " axis "
                                                     << "IPO"[k];
  }
}

TEST(Mountings, MatricesAreRightHandedAndOrthonormal) {
  // IA × PA = OA for every mounting (model/plan.hpp), exactly: entries are 0 and ±1.
  for (const Axes& axes : kAxes) {
    const Eigen::Matrix3d m = mounting_matrix(axes.mounting);
    EXPECT_EQ(m.col(0).cross(m.col(1)), m.col(2)) << mounting_name(axes.mounting);
    EXPECT_EQ(m.transpose() * m, Eigen::Matrix3d::Identity()) << mounting_name(axes.mounting);
  }
}

}  // namespace
}  // namespace ccal::test
