#pragma once
// Physical and conversion constants, in SI (m, s, rad). Angle factors are written as π divided by an
// integer, so each is the correctly rounded value of the exact ratio rather than an accumulation of
// several roundings (e.g. arcsec is π/648000, not deg/3600).
#include <numbers>

namespace ccal::constants {

inline constexpr double pi = std::numbers::pi;
inline constexpr double deg = pi / 180.0;            // rad per degree
inline constexpr double degrees_per_rad = 180.0 / pi;  // deg per rad, for output in degrees
inline constexpr double arcmin = pi / 10800.0;       // rad per arc minute
inline constexpr double arcsec = pi / 648000.0;      // rad per arc second
inline constexpr double rpm = pi / 30.0;             // rad/s per revolution per minute (2π rad / 60 s)
inline constexpr double standard_gravity = 9.80665;  // m/s², exact by definition (3rd CGPM, 1901)
inline constexpr double earth_rotation_rate = 7.2921150e-5;  // rad/s, WGS-84 nominal mean value

}  // namespace ccal::constants
