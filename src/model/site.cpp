#include "ccal/model/site.hpp"

#include <cmath>

namespace ccal {

Eigen::Vector3d Site::earth_rate_enu() const {
  if (!earth_rotation) return Eigen::Vector3d::Zero();
  return earth_rate * Eigen::Vector3d(0.0, std::cos(latitude), std::sin(latitude));
}

double normal_gravity(double latitude, double height) {
  // Somigliana: g = g_e (1 + k sin²φ) / sqrt(1 − e² sin²φ), WGS-84 constants (NIMA TR8350.2, Eq. 4-1).
  constexpr double g_equator = 9.7803253359;
  constexpr double k = 0.00193185265241;
  constexpr double e2 = 0.00669437999013;
  const double s2 = std::sin(latitude) * std::sin(latitude);
  return g_equator * (1.0 + k * s2) / std::sqrt(1.0 - e2 * s2) - 3.086e-6 * height;
}

}  // namespace ccal
