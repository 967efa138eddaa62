#pragma once
// Shared set-ups for the kinematics tests: the paper's geometry and the V5 operating point of model.md §6.1.
#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <random>
#include <unsupported/Eigen/AutoDiff>

#include "ccal/core/scalar.hpp"
#include "ccal/model/centrifuge.hpp"
#include "ccal/model/kinematics.hpp"
#include "ccal/model/site.hpp"
#include "test_constants.hpp"

namespace ccal::test {

using AD = Dual;

inline Site paper_site(bool earth = false) {
  Site s;
  s.latitude = 45.75 * kDeg;
  s.g = 9.8;
  s.earth_rotation = earth;
  return s;
}

// Main-axis rate giving A g at radius R0: A = Ω² R0 / g.
// Normal random errors of every parameter of the layout: angles ~ scale rad, lengths ~ 10·scale m, arm
// stretch ~ 1e-2·scale m/(rad/s)², Δω ~ scale rad/s; ΔΩ is left at zero (set it where a test wants it).
inline Eigen::VectorXd random_errors(const ErrorLayout& layout, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::VectorXd e(layout.size());
  for (int i = 0; i < layout.size(); ++i) {
    const SourceUnit u = layout.parameter_unit(i);
    e[i] = n(rng) * (u == SourceUnit::m                         ? 10 * scale
                     : u == SourceUnit::m_per_rad_per_s_squared ? 1e-2 * scale
                                                                : scale);
  }
  e[ch::dOmega] = 0.0;
  return e;
}

inline double rate_for(double A, double R0, double g) { return std::sqrt(A * g / R0); }

// The six sensed outputs (f_IA, f_PA, f_OA [g], ω_IA, ω_PA, ω_OA [rad/s]) of the exact chain for errors e,
// with the joint motion of the run perturbed by the drive errors in e (rates and ripple).
template <class S>
Eigen::Matrix<S, 6, 1> outputs(const Geometry& geo, const ErrorLayout& layout, const VecX<S>& e,
                               const Site& site, double rate, double theta1_0, double phi0, PlatformMode mode,
                               double t, const ChainOptions& options = {}) {
  const RunMotion<S> run = run_motion<S>(rate, theta1_0, phi0, mode, geo, layout, e);
  const auto s = exact_state<S>(geo, layout, e, site, run.at(S(t)), options);
  Eigen::Matrix<S, 6, 1> y;
  y << s.specific_force, s.angular_rate;
  return y;
}

// Jacobian of the six outputs with respect to every error parameter, by forward-mode AD at errors e0, in
// passes of kDualWidth directions.
inline Eigen::Matrix<double, 6, Eigen::Dynamic> ad_jacobian(const Geometry& geo, const ErrorLayout& layout,
                                                            const Eigen::VectorXd& e0, const Site& site,
                                                            double rate, double theta1_0, double phi0,
                                                            PlatformMode mode, double t,
                                                            const ChainOptions& options = {}) {
  const int n = layout.size();
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, n);
  for (int first = 0; first < n; first += kDualWidth) {
    VecX<AD> e(n);
    for (int i = 0; i < n; ++i)
      e[i] = make_dual(e0[i], i >= first && i < first + kDualWidth ? i - first : -1);
    const auto y = outputs<AD>(geo, layout, e, site, rate, theta1_0, phi0, mode, t, options);
    for (int r = 0; r < 6; ++r)
      for (int k = 0; k < kDualWidth && first + k < n; ++k) J(r, first + k) = y[r].derivatives()[k];
  }
  return J;
}

}  // namespace ccal::test
