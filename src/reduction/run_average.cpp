#include "ccal/reduction/run_average.hpp"

#include <cmath>

namespace ccal {

double mean_cos_power(int k, double phi0, double omega_T) {
  if (omega_T == 0.0) return std::pow(std::cos(phi0), k);
  // I_k(x) = ∫₀ˣ cos^k: I_0 = x, I_1 = sin x, I_k = cos^{k−1}x sin x / k + (k−1)/k I_{k−2}.
  auto integral = [k](double x) {
    const double c = std::cos(x), s = std::sin(x);
    double i_prev = x, i_curr = s;  // I_0, I_1
    if (k == 0) return i_prev;
    for (int n = 2; n <= k; ++n) {
      const double next = std::pow(c, n - 1) * s / n + (n - 1.0) / n * i_prev;
      i_prev = i_curr;
      i_curr = next;
    }
    return i_curr;
  };
  return (integral(phi0) - integral(phi0 - omega_T)) / omega_T;
}

double nominal_power_mean(int k, double A, double phi0, double omega_T) {
  return std::pow(-A, k) * mean_cos_power(k, phi0, omega_T);
}

int polynomial_degree(const std::vector<TermSpec>& terms) {
  int degree = 0;
  for (const auto& t : terms) {
    switch (t.kind) {
      case TermKind::power:
        degree = std::max(degree, t.power);
        break;
      case TermKind::abs_square:
      case TermKind::ip:
      case TermKind::io:
      case TermKind::pp:
      case TermKind::oo:
      case TermKind::po:
        degree = std::max(degree, 2);
        break;
      default:
        degree = std::max(degree, 1);
        break;
    }
  }
  return degree;
}

bool has_non_smooth_term(const std::vector<TermSpec>& terms) {
  for (const auto& t : terms)
    if (t.kind == TermKind::abs_square) return true;
  return false;
}

}  // namespace ccal
