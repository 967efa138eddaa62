#include "ccal/uncertainty/statement.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "ccal/reduction/observe.hpp"

namespace ccal {

double welch_satterthwaite(const std::vector<UncertaintyPart>& parts) {
  double variance = 0, denominator = 0;
  for (const UncertaintyPart& part : parts) {
    if (!(part.u >= 0)) throw std::invalid_argument("welch_satterthwaite: a standard uncertainty below 0");
    if (part.u == 0) continue;
    if (!(part.dof > 0)) throw std::invalid_argument("welch_satterthwaite: degrees of freedom not above 0");
    variance += part.u * part.u;
    if (std::isfinite(part.dof)) denominator += std::pow(part.u, 4) / part.dof;
  }
  if (denominator == 0) return kInfiniteDof;  // every part known exactly (or nothing uncertain)
  return variance * variance / denominator;
}

CoefficientStatement state_coefficient(const StatementInput& input, double p) {
  CoefficientStatement s;
  s.input = input;
  s.corrected = input.estimate + input.correction;
  s.combined = std::hypot(input.type_a.u, input.type_b.u);
  s.effective_dof = welch_satterthwaite({input.type_a, input.type_b});
  s.dof_for_k = std::isfinite(s.effective_dof) ? std::floor(s.effective_dof * (1 + 1e-12)) : kInfiniteDof;
  s.coverage_factor = student_coverage_factor(p, s.effective_dof);
  s.expanded = s.coverage_factor * s.combined;
  s.low = s.corrected - s.expanded;
  s.high = s.corrected + s.expanded;
  s.significant = s.low > 0 || s.high < 0;
  return s;
}

namespace {

// n × 10^place written in full ("-43", -3 → "-0.043"; 12, 2 → "1200"); "0" for 0, never "-0".
std::string count_at_place(long long n, int place) {
  const std::string sign = n < 0 ? "-" : "";
  std::string digits = std::to_string(n < 0 ? -n : n);
  if (place >= 0) return sign + (n == 0 ? digits : digits + std::string(std::size_t(place), '0'));
  const auto decimals = std::size_t(-place);
  if (digits.size() <= decimals) digits.insert(0, decimals + 1 - digits.size(), '0');
  return sign + digits.substr(0, digits.size() - decimals) + "." + digits.substr(digits.size() - decimals);
}

}  // namespace

RoundedFigures round_figures(double estimate, double expanded, int digits) {
  RoundedFigures r;
  const double step = std::isfinite(expanded) && expanded > 0 && digits >= 1
                          ? std::pow(10.0, std::floor(std::log10(expanded)) - (digits - 1))
                          : 0;
  // Past 10^15 steps a count is no longer exact in a double: no place either.
  if (!(step > 0) || !std::isfinite(estimate) || std::abs(estimate) / step > 1e15) {
    const auto plain = [](double v) { return fmt::format("{:.8g}", v); };
    r.estimate = plain(estimate);
    r.expanded = plain(expanded);
    r.low = plain(estimate - expanded);
    r.high = plain(estimate + expanded);
    return r;
  }
  int place = int(std::lround(std::log10(step)));
  // 0.0996 rounds to 0.100: one place coarser keeps `digits` digits.
  if (std::round(expanded / std::pow(10.0, place)) >= std::pow(10.0, digits)) ++place;
  const double unit = std::pow(10.0, place);
  const auto e = std::llround(estimate / unit), u = std::llround(expanded / unit);
  r.place = place;
  r.estimate = count_at_place(e, place);
  r.expanded = count_at_place(u, place);
  // The interval of the figures as written, so that the certificate reads y − U and y + U exactly.
  r.low = count_at_place(e - u, place);
  r.high = count_at_place(e + u, place);
  return r;
}

RoundedFigures round_figures(const CoefficientStatement& s) { return round_figures(s.corrected, s.expanded); }

Eigen::VectorXd known_error_shift(const Config& config, ModelMode mode) {
  const Eigen::VectorXd& errors = config.centrifuge.errors;
  if (config.identification.compensate || (errors.array() == 0.0).all()) return {};
  const Experiment ex = config.experiment();
  const IdentificationSpec& spec = config.identification;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(errors.size());
  const Eigen::VectorXd with =
      identify_coefficients<double>(observe<double>(ex, errors, zero, spec, mode), spec);
  const Eigen::VectorXd without =
      identify_coefficients<double>(observe<double>(ex, zero, zero, spec, mode), spec);
  return with - without;
}

}  // namespace ccal
