// The law of propagation of uncertainty (JCGM 100 §5) for a Monte Carlo model: sensitivities by central
// differences, then the inputs' correlations (groups, [[correlations]]) through one factor of their matrix.
#include <Eigen/Core>

#include "ccal/core/errors.hpp"
#include "ccal/setup/input_correlation.hpp"
#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal {

LinearPropagation propagate_linear(const std::vector<Tolerance>& sources,
                                   const std::vector<Correlation>& correlations, int n_outputs,
                                   const TrialFunction& trial, double step_fraction) {
  if (n_outputs < 1) throw InputError("LPU: the model must have at least one output");
  if (!(step_fraction > 0)) throw InputError("LPU: the step fraction must be > 0");
  check_source_bounds(sources);
  const auto n = Eigen::Index(sources.size());
  std::vector<double> draws(sources.size(), 0.0);
  std::vector<double> out(std::size_t(n_outputs), 0.0);
  const auto evaluate = [&] {
    trial(draws, out);
    return Eigen::Map<const Eigen::VectorXd>(out.data(), n_outputs).eval();
  };
  LinearPropagation lp;
  lp.estimate = evaluate();
  lp.sensitivities = Eigen::MatrixXd::Zero(n_outputs, n);
  Eigen::MatrixXd contribution = Eigen::MatrixXd::Zero(n_outputs, n);  // c_ij·u_j
  for (Eigen::Index j = 0; j < n; ++j) {
    const Tolerance& t = sources[std::size_t(j)];
    const double u = standard_uncertainty(t.bound, t.distribution);
    if (!(u > 0)) continue;
    const double h = step_fraction * u;
    draws[std::size_t(j)] = h;
    const Eigen::VectorXd plus = evaluate();
    draws[std::size_t(j)] = -h;
    const Eigen::VectorXd minus = evaluate();
    draws[std::size_t(j)] = 0.0;
    lp.sensitivities.col(j) = (plus - minus) / (2 * h);
    contribution.col(j) = lp.sensitivities.col(j) * u;
  }
  // Cov = E R Eᵀ = (E F)(E F)ᵀ with E the contributions c_ij u_j and R = F Fᵀ; with groups alone F is the
  // group indicator: the members of a group add linearly, independent sources and groups in quadrature.
  Eigen::MatrixXd by_factor;
  if (correlations.empty()) {
    const CorrelationGroups groups = correlation_groups(sources);
    by_factor = Eigen::MatrixXd::Zero(n_outputs, groups.count);
    for (Eigen::Index j = 0; j < n; ++j) by_factor.col(groups.of[std::size_t(j)]) += contribution.col(j);
  } else {
    by_factor = contribution * input_correlation(sources, correlations).factor;
  }
  lp.covariance = by_factor * by_factor.transpose();
  lp.std_uncertainty = lp.covariance.diagonal().cwiseSqrt();
  return lp;
}

}  // namespace ccal
