#include "ccal/uncertainty/coverage.hpp"

#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <stdexcept>

#include "ccal/core/errors.hpp"
#include "ccal/setup/tolerance.hpp"

namespace ccal {

std::string_view coverage_method_name(CoverageMethod method) {
  switch (method) {
    case CoverageMethod::normal: return "normal";
    case CoverageMethod::student_t: return "Student t";
    case CoverageMethod::monte_carlo: return "Monte Carlo";
    case CoverageMethod::stated: return "stated k";
  }
  return "normal";
}

double normal_coverage_factor(double p) {
  if (!(p > 0 && p < 1))
    throw InputError(fmt::format("coverage probability: {} is not in (0, 1); e.g. 0.95", p));
  return normal_erf_quantile(p);
}

double normal_coverage_probability(double k) {
  if (!(k > 0 && std::isfinite(k)))
    throw InputError(fmt::format("coverage factor: {} is not a finite k > 0; e.g. 2", k));
  return std::erf(k / std::numbers::sqrt2);
}

double student_coverage_factor(double p, double dof) {
  if (!(p > 0 && p < 1)) throw std::invalid_argument("coverage probability outside (0, 1)");
  if (!(dof >= 1)) throw std::invalid_argument("degrees of freedom below 1");
  if (!std::isfinite(dof)) return normal_erf_quantile(p);
  // GUM G.4.1 note 1: a non-integer ν_eff is truncated to the next lower integer (the relative guard keeps an
  // integer ν that arrives as 4.999999999999 at 5).
  const double whole = std::floor(dof * (1 + 1e-12));
  return boost::math::quantile(boost::math::students_t_distribution<double>(whole), (1 + p) / 2);
}

double student_coverage_probability(double k, double dof) {
  if (!(k > 0 && std::isfinite(k))) throw std::invalid_argument("coverage factor not a finite k > 0");
  if (!(dof >= 1)) throw std::invalid_argument("degrees of freedom below 1");
  if (!std::isfinite(dof)) return normal_coverage_probability(k);
  const double whole = std::floor(dof * (1 + 1e-12));  // as student_coverage_factor
  return 2 * boost::math::cdf(boost::math::students_t_distribution<double>(whole), k) - 1;
}

Coverage normal_coverage(double p, std::optional<double> stated_factor) {
  Coverage c;
  if (stated_factor) {
    c.factor = *stated_factor;
    c.probability = normal_coverage_probability(c.factor);
    c.method = CoverageMethod::stated;
  } else {
    c.factor = normal_coverage_factor(p);
    c.probability = p;
  }
  return c;
}

std::string coverage_text(const Coverage& c) {
  const std::string k = fmt::format("{:.3g}", c.factor), p = fmt::format("{:.4g} %", 100 * c.probability);
  switch (c.method) {
    case CoverageMethod::normal: return fmt::format("k = {}, p = {}", k, p);
    case CoverageMethod::stated: return fmt::format("k = {} (stated), p = {} for a normal quantity", k, p);
    case CoverageMethod::student_t: return fmt::format("k = {} (Student t), p = {}", k, p);
    case CoverageMethod::monte_carlo: return fmt::format("p = {} (Monte Carlo interval)", p);
  }
  return k;
}

}  // namespace ccal
