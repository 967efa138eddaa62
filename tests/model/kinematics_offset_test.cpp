// An instrument off the platform axis (one of several on the base plane, model.md §4.2): the chain against the
// closed forms of a counter-rotating and of a fixed platform, its azimuth as a turn of the axes, and the
// derivatives with respect to Δx5, Δy5 at an offset place against differences in that place.
#include <gtest/gtest.h>

#include "kinematics_support.hpp"

namespace ccal::test {
namespace {

Geometry offset_geometry(double x5, double y5, double azimuth5) {
  Geometry geo{2.5, 0.0, 0.0, 0.0};
  geo.x5 = x5;
  geo.y5 = y5;
  geo.azimuth5 = azimuth5;
  return geo;
}

// Counter-rotating, no errors: θ1 + γ is constant, so the offset is a constant inertial vector and adds no
// acceleration; the instrument feels what one on the axis feels. Tolerance 1e-13 A: a handful of roundings of
// terms of size A (30 g here), the offset's own terms cancelling to round-off of Ω² x5 / g ≈ 1.2 g.
TEST(OffsetInstrument, OnACounterRotatingPlatformFeelsWhatOneOnTheAxisFeels) {
  const ErrorLayout layout(1);
  const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
  const Site site = paper_site(true);
  const double A = 30.0, w = rate_for(A, 2.5, site.g);
  for (double t : {0.0, 0.37, 101.3}) {
    const auto on_axis = outputs<double>(offset_geometry(0, 0, 0), layout, e, site, w, 0.4, 1.1,
                                         PlatformMode::counter_rotating, t);
    const auto off = outputs<double>(offset_geometry(0.1, -0.2, 0), layout, e, site, w, 0.4, 1.1,
                                     PlatformMode::counter_rotating, t);
    // The Earth's Coriolis force on the offset's velocity (none: the offset does not move) keeps them equal too.
    EXPECT_NEAR((off - on_axis).head<3>().norm(), 0.0, 1e-13 * A) << "t = " << t;
    EXPECT_NEAR((off - on_axis).tail<3>().norm(), 0.0, 1e-16);
  }
}

// Fixed platform at γ: u = (R0, 0) + Rz(γ)(x5, y5) turns with the arm, a = −Ω² u, so in frame 5
//   a_i = −(Ω²/g)(R0 cos γ + x5),  a_p = −(Ω²/g)(−R0 sin γ + y5),  a_o = 1.
// Tolerance 1e-13 A as above.
TEST(OffsetInstrument, OnAFixedPlatformRunsAtItsOwnRadius) {
  const ErrorLayout layout(1);
  const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
  const Site site = paper_site();
  const double A = 20.0, w = rate_for(A, 2.5, site.g), x5 = 0.15, y5 = -0.05;
  for (double gamma : {0.0, 1.1, std::numbers::pi}) {
    const auto y = outputs<double>(offset_geometry(x5, y5, 0), layout, e, site, w, 0.4, gamma,
                                   PlatformMode::fixed, 12.5);
    const double k = w * w / site.g;
    EXPECT_NEAR(y[0], -k * (2.5 * std::cos(gamma) + x5), 1e-13 * A) << "γ = " << gamma;
    EXPECT_NEAR(y[1], -k * (-2.5 * std::sin(gamma) + y5), 1e-13 * A) << "γ = " << gamma;
    EXPECT_NEAR(y[2], 1.0, 1e-13);
  }
}

// The azimuth turns the instrument's axes about z5: (a_i, a_p) of a turned instrument are those of an unturned
// one at the same place, rotated by −ψ; a_o and ω_OA unchanged, with every error of the machine but the
// instrument's own tilts (which act about its turned axes). Tolerance 1e-13 A.
TEST(OffsetInstrument, ItsAzimuthTurnsItsAxesAboutZ5) {
  const ErrorLayout layout(1);
  Eigen::VectorXd e = 1e-5 * Eigen::VectorXd::Ones(layout.size());
  e[ch::dthx5] = e[ch::dthy5] = 0;
  const Site site = paper_site(true);
  const double A = 10.0, w = rate_for(A, 2.5, site.g), psi = 0.7;
  const auto straight = outputs<double>(offset_geometry(0.1, 0.1, 0), layout, e, site, w, 0.2, 0.5,
                                        PlatformMode::counter_rotating, 3.0);
  const auto turned = outputs<double>(offset_geometry(0.1, 0.1, psi), layout, e, site, w, 0.2, 0.5,
                                      PlatformMode::counter_rotating, 3.0);
  const double c = std::cos(psi), s = std::sin(psi);
  EXPECT_NEAR(turned[0], c * straight[0] + s * straight[1], 1e-13 * A);
  EXPECT_NEAR(turned[1], -s * straight[0] + c * straight[1], 1e-13 * A);
  EXPECT_NEAR(turned[2], straight[2], 1e-13 * A);
  EXPECT_NEAR(turned[5], straight[5], 1e-15);
}

// The errors Δx5, Δy5 are displacements about the nominal place: their exact derivatives (AD) at an offset
// place equal central differences in the place itself, with a fixed platform where the place matters. Step
// 1e-4 m on u ≈ 2.5 m: truncation (h² u''' ~ 1e-8 relative of the curvature terms, which are linear in the
// place here) and round-off (1e-16 A / 1e-4 = 1e-11) stay below 1e-9 of the derivative, Ω²/g ≈ 8 g/m.
TEST(OffsetInstrument, ItsPlacesErrorsAreDerivativesInItsPlace) {
  const ErrorLayout layout(1);
  const Eigen::VectorXd e = Eigen::VectorXd::Zero(layout.size());
  const Site site = paper_site(true);
  const double w = rate_for(20.0, 2.5, site.g), h = 1e-4;
  const auto J = ad_jacobian(offset_geometry(0.1, -0.2, 0.3), layout, e, site, w, 0.2, 0.9, PlatformMode::fixed,
                             5.0);
  for (int which : {0, 1}) {
    auto at = [&](double d) {
      return outputs<double>(offset_geometry(0.1 + (which == 0 ? d : 0), -0.2 + (which == 1 ? d : 0), 0.3), layout,
                             e, site, w, 0.2, 0.9, PlatformMode::fixed, 5.0);
    };
    const Eigen::Matrix<double, 6, 1> difference = (at(h) - at(-h)) / (2 * h);
    const auto column = J.col(which == 0 ? ch::dx5 : ch::dy5);
    EXPECT_NEAR((column - difference).norm(), 0.0, 1e-9 * column.norm() + 1e-12) << (which == 0 ? "dx5" : "dy5");
    EXPECT_GT(column.head<2>().norm(), 1.0);  // the place matters here: Ω²/g ≈ 8 g/m
  }
}

}  // namespace
}  // namespace ccal::test
