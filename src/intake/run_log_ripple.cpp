// The drives' rate ripple as the encoders measure it, and the platform's control as its angle shows it
// (docs/model.md §13.1, §13.2).
#include <algorithm>
#include <cmath>

#include "ccal/intake/run_log.hpp"

namespace ccal {

std::vector<double> ripple_from_angle_harmonics(const std::vector<double>& angle) {
  std::vector<double> r(angle.size());
  for (std::size_t i = 0; i + 1 < angle.size(); i += 2) {
    const double k = double(i / 2 + 1);
    r[i] = k * angle[i + 1];   // ck = k Ŝk
    r[i + 1] = -k * angle[i];  // sk = −k Ĉk
  }
  return r;
}

std::vector<double> angle_harmonics_from_ripple(const std::vector<double>& ripple) {
  std::vector<double> a(ripple.size());
  for (std::size_t i = 0; i + 1 < ripple.size(); i += 2) {
    const double k = double(i / 2 + 1);
    a[i] = -ripple[i + 1] / k;  // Ĉk = −sk/k
    a[i + 1] = ripple[i] / k;   // Ŝk = ck/k
  }
  return a;
}

// δ1 = Σ Ĉk cos kθ1 + Ŝk sin kθ1 with θ1 = ψ0 − γ:
//   cos kθ1 = cos kψ0 cos kγ + sin kψ0 sin kγ,   sin kθ1 = sin kψ0 cos kγ − cos kψ0 sin kγ.
std::vector<double> main_angle_error_in_gamma(const std::vector<double>& theta1_angle, double psi0) {
  std::vector<double> g(theta1_angle.size());
  for (std::size_t i = 0; i + 1 < theta1_angle.size(); i += 2) {
    const double k = double(i / 2 + 1), c = std::cos(k * psi0), s = std::sin(k * psi0);
    const double C = theta1_angle[i], S = theta1_angle[i + 1];
    g[i] = C * c + S * s;
    g[i + 1] = C * s - S * c;
  }
  return g;
}

std::string_view control_look_name(ControlLook look) {
  switch (look) {
    case ControlLook::speed:
      return "speed";
    case ControlLook::phase_locked:
      return "phase_locked";
    case ControlLook::undetermined:
      return "undetermined";
    case ControlLook::not_tested:
      break;
  }
  return "not tested";
}

std::vector<double> resolved_harmonics(const std::vector<double>& angle, double sigma) {
  std::vector<double> out = angle;
  const double threshold = std::max(kRippleSignificance * sigma, kRippleResolutionFloor);
  for (std::size_t i = 0; i + 1 < out.size(); i += 2)
    if (!(std::hypot(out[i], out[i + 1]) > threshold)) out[i] = out[i + 1] = 0.0;
  return out;
}

ControlEvidence platform_control_evidence(const ReducedLog& log) {
  ControlEvidence e;
  if (!log.has_theta1 || !log.has_gamma || log.theta1_harmonics.empty() || log.gamma_harmonics.empty())
    return e;
  // What a phase-locked platform's angle carries: p = −δ1 in γ's harmonics, ψ0 = θ1(t0) + γ(t0).
  const std::vector<double> main =
      main_angle_error_in_gamma(log.theta1_harmonics, log.theta1_start + log.gamma_start);
  const std::vector<double>& g = log.gamma_harmonics;
  double pp = 0, gp = 0;
  for (std::size_t i = 0; i < std::min(g.size(), main.size()); ++i) {  // p = −main
    pp += main[i] * main[i];
    gp -= g[i] * main[i];
  }
  e.main_in_gamma = std::sqrt(pp);
  const double sigma = std::hypot(log.theta1_harmonic_sigma, log.gamma_harmonic_sigma);
  // |p| must exceed kRippleSignificance standard errors of λ·|p|: λ's error is then below 0.1, and the
  // decision at λ = 1/2 five standard errors from either mode.
  e.threshold = std::max(kRippleSignificance * sigma, kRippleResolutionFloor);
  e.look = ControlLook::undetermined;
  if (!(e.main_in_gamma > e.threshold)) return e;
  e.following = gp / pp;
  e.look = e.following > 0.5 ? ControlLook::phase_locked : ControlLook::speed;
  return e;
}

}  // namespace ccal
