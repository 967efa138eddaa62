#pragma once
// The test site: latitude, local gravity and Earth rotation (docs/model.md §1).

#include <Eigen/Core>

namespace ccal {

struct Site {
  double latitude = 0.798488132;     // rad; 45.75° N (Harbin), the paper's site as reconstructed
  double g = 9.8;                    // local gravity magnitude [m/s²]; the paper's value (model.md A2)
  // The g the g-levels and the instrument's coefficients are in [m/s²]: 0 for the local g (the default, as the
  // paper has it), kStandardGravity for standard gravity g_n ([site] g_unit = "standard").
  double unit_g = 0;
  double g_unit() const { return unit_g > 0 ? unit_g : g; }
  bool earth_rotation = true;        // Coriolis force and Earth rate on the instrument
  double earth_rate = 7.2921150e-5;  // WGS-84 [rad/s]
  // With earth_rotation on, its two effects can be switched off one at a time: this is how an analyst's
  // model that leaves one of them uncompensated is represented (the budget's compensation-choice rows).
  bool apply_coriolis = true;    // the Coriolis force 2 ω_ie × v in the specific force
  bool sense_earth_rate = true;  // ω_ie in the instrument's inertial angular rate

  // Earth's angular velocity in the geographic frame 0 (x East, y North, z Up), zero if switched off.
  Eigen::Vector3d earth_rate_enu() const;
  // ω_ie as it enters the Coriolis force, and as the instrument senses it (each zero if switched off).
  Eigen::Vector3d coriolis_rate_enu() const {
    return apply_coriolis ? earth_rate_enu() : Eigen::Vector3d::Zero();
  }
  Eigen::Vector3d sensed_rate_enu() const {
    return sense_earth_rate ? earth_rate_enu() : Eigen::Vector3d::Zero();
  }
};

// Standard gravity g_n (CGPM 1901), m/s².
inline constexpr double kStandardGravity = 9.80665;

// Normal gravity on the WGS-84 ellipsoid (Somigliana's closed form) with the free-air gradient
// −3.086e-6 s⁻² per metre of height; the default for a site whose g is not measured.
double normal_gravity(double latitude, double height = 0.0);

}  // namespace ccal
