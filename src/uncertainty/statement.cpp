#include "ccal/uncertainty/statement.hpp"

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
  return s;
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
