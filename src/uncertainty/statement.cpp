#include "ccal/uncertainty/statement.hpp"

#include <fmt/format.h>

#include <algorithm>
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

CoefficientStatement state_coefficient(const StatementInput& input, double p, std::optional<double> stated_factor) {
  CoefficientStatement s;
  s.input = input;
  s.corrected = input.estimate + input.correction;
  s.combined = std::hypot(input.type_a.u, input.type_b.u);
  s.effective_dof = welch_satterthwaite({input.type_a, input.type_b});
  s.dof_for_k = std::isfinite(s.effective_dof) ? std::floor(s.effective_dof * (1 + 1e-12)) : kInfiniteDof;
  s.coverage_factor = student_coverage_factor(p, s.effective_dof);
  if (stated_factor) {
    s.coverage_factor = *stated_factor;
    s.method = IntervalMethod::coverage_factor;
    s.stated = StatedCoverage{normal_coverage_probability(*stated_factor),
                              student_coverage_probability(*stated_factor, s.effective_dof)};
  }
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

namespace {

// The power of ten of the last digit written for a U of `digits` significant digits (a U that rounds up to a
// power of ten keeps `digits` digits: 0.0996 → 0.10), or none for a U that is 0 or not finite, or an estimate
// beyond 10¹⁵ of that digit (past which a count is no longer exact in a double).
std::optional<int> rounding_place(double estimate, double expanded, int digits) {
  const double step = std::isfinite(expanded) && expanded > 0 && digits >= 1
                          ? std::pow(10.0, std::floor(std::log10(expanded)) - (digits - 1))
                          : 0;
  if (!(step > 0) || !std::isfinite(estimate) || std::abs(estimate) / step > 1e15) return std::nullopt;
  int place = int(std::lround(std::log10(step)));
  if (std::round(expanded / std::pow(10.0, place)) >= std::pow(10.0, digits)) ++place;
  return place;
}

std::string plain(double v) { return fmt::format("{:.8g}", v); }

}  // namespace

RoundedFigures round_figures(double estimate, double expanded, int digits) {
  RoundedFigures r;
  r.place = rounding_place(estimate, expanded, digits);
  if (!r.place) {
    r.estimate = plain(estimate);
    r.expanded = plain(expanded);
    r.low = plain(estimate - expanded);
    r.high = plain(estimate + expanded);
    return r;
  }
  const double unit = std::pow(10.0, *r.place);
  const auto e = std::llround(estimate / unit), u = std::llround(expanded / unit);
  r.estimate = count_at_place(e, *r.place);
  r.expanded = count_at_place(u, *r.place);
  // The interval of the figures as written, so that the certificate reads y − U and y + U exactly.
  r.low = count_at_place(e - u, *r.place);
  r.high = count_at_place(e + u, *r.place);
  return r;
}

RoundedFigures round_interval(double estimate, double low, double high, int digits) {
  const double half = (high - low) / 2;
  RoundedFigures r;
  r.place = rounding_place(estimate, half, digits);
  if (r.place && std::max(std::abs(low), std::abs(high)) / std::pow(10.0, *r.place) > 1e15) r.place.reset();
  if (!r.place) {
    r.estimate = plain(estimate);
    r.expanded = plain(half);
    r.low = plain(low);
    r.high = plain(high);
    return r;
  }
  const double unit = std::pow(10.0, *r.place);
  const auto at = [&](double v) { return count_at_place(std::llround(v / unit), *r.place); };
  r.estimate = at(estimate);
  r.expanded = at(half);
  r.low = at(low);
  r.high = at(high);
  return r;
}

RoundedFigures round_figures(const CoefficientStatement& s) {
  return s.method == IntervalMethod::monte_carlo ? round_interval(s.corrected, s.low, s.high)
                                                 : round_figures(s.corrected, s.expanded);
}

namespace {

// The §8 validation of the statement's interval y ∓ U against the Monte Carlo's of the same quantity.
OutputSummary validated(const CoefficientStatement& s, OutputSummary mc) {
  mc.has_lpu = true;
  mc.lpu_std = s.combined;
  mc.lpu_expanded = s.expanded;
  mc.validation_delta = numerical_tolerance(s.combined, 2);
  mc.d_low = std::abs(s.corrected - s.expanded - mc.low_symmetric);
  mc.d_high = std::abs(s.corrected + s.expanded - mc.high_symmetric);
  mc.validated = mc.d_low <= mc.validation_delta && mc.d_high <= mc.validation_delta;
  return mc;
}

}  // namespace

std::uint64_t trials_to_settle(const CoefficientStatement& s, const OutputSummary& mc, std::uint64_t trials) {
  if (s.method != IntervalMethod::student_t) return 0;
  const ValidationDiagnosis d = validation_diagnosis(validated(s, mc), trials);
  return d.explained_by_sampling ? std::max(d.trials_needed, trials + 1) : 0;
}

void check_by_monte_carlo(CoefficientStatement& s, OutputSummary summary, std::uint64_t trials) {
  OutputSummary mc = validated(s, std::move(summary));
  s.monte_carlo_trials = trials;
  // A failure within three standard errors of the Monte Carlo's ends is M's, not the LPU's: no verdict.
  if (s.method == IntervalMethod::student_t && !mc.validated &&
      !validation_diagnosis(mc, trials).explained_by_sampling) {
    s.method = IntervalMethod::monte_carlo;
    s.low = mc.low_symmetric;
    s.high = mc.high_symmetric;
    s.expanded = (s.high - s.low) / 2;
    s.coverage_factor = s.combined > 0 ? s.expanded / s.combined : 0.0;
    s.significant = s.low > 0 || s.high < 0;
  }
  s.monte_carlo = std::move(mc);
}

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
