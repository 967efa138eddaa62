#include "ccal/model/plan.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ccal {

Eigen::Matrix3d mounting_matrix(Mounting mounting) {
  Eigen::Matrix3d M;
  switch (mounting) {
    case Mounting::ia_horizontal:
      M.setIdentity();
      break;
    case Mounting::ia_reversed:
      M << -1, 0, 0, 0, -1, 0, 0, 0, 1;
      break;
    case Mounting::pa_vertical:
      M << 1, 0, 0, 0, 0, -1, 0, 1, 0;
      break;
    case Mounting::ia_vertical:
      M << 0, 1, 0, 0, 0, 1, 1, 0, 0;
      break;
  }
  return M;
}

double nominal_rate(const Run& run, const Geometry& geometry, const Site& site) {
  return std::sqrt(run.g_level * site.g_unit() / geometry.R0);
}

double nominal_platform_rate(const Run& run, const Geometry& geometry, const Site& site) {
  return run.mode == PlatformMode::counter_rotating ? -nominal_rate(run, geometry, site) : 0.0;
}

double initial_phase(const Run& run, const Geometry& geometry, const Site& site) {
  if (run.initial_phase) return *run.initial_phase;
  if (!run.terminal_phase)
    throw std::invalid_argument("run '" + run.name + "' gives neither an initial nor a terminal phase");
  return angle_in_turn(*run.terminal_phase - nominal_platform_rate(run, geometry, site) * run.duration);
}

double angle_in_turn(double angle) {
  const double two_pi = 2 * std::numbers::pi;
  const double a = std::fmod(angle, two_pi);
  return a < 0 ? a + two_pi : a;
}

double initial_ia_azimuth(const Run& run, const Geometry& geometry, const Site& site) {
  return run.arm_azimuth + initial_phase(run, geometry, site);
}

std::string_view mounting_name(Mounting mounting) noexcept {
  switch (mounting) {
    case Mounting::ia_horizontal:
      return "ia_horizontal";
    case Mounting::ia_reversed:
      return "ia_reversed";
    case Mounting::pa_vertical:
      return "pa_vertical";
    case Mounting::ia_vertical:
      return "ia_vertical";
  }
  return "";
}

std::string_view platform_mode_name(PlatformMode mode) noexcept {
  return mode == PlatformMode::counter_rotating ? "counter_rotating" : "fixed";
}

}  // namespace ccal
