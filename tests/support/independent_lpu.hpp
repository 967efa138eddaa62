#pragma once
// An LPU computed independently of the budget, the Monte Carlo's trial kernel and the allocation: the
// sensitivities by central differences of the plain double pipeline (observe with the converged default rule
// + identify_coefficients, re-identifying at each step), the standard uncertainties from bound and
// distribution written out (GUM 4.3.7/4.3.9), and the totals by JCGM 100 §5 with correlation groups (members
// of a group add linearly with their signs, groups in quadrature).
#include <Eigen/Core>
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "ccal/io/config_file.hpp"
#include "ccal/reduction/observe.hpp"

namespace ccal::test {

inline double sigma_from_bound(double bound, Distribution d) {
  switch (d) {
    case Distribution::normal:
      return bound;
    case Distribution::uniform:
      return bound / std::sqrt(3.0);
    case Distribution::triangular:
      return bound / std::sqrt(6.0);
    case Distribution::arcsine:
      return bound / std::numbers::sqrt2;
  }
  return 0.0;
}

// ∂K̂/∂e_s (free coefficients × sources, SI) by central differences with step h_s = the source's bound
// (second-order terms cancel; third-order ones are O(h²) ≈ 1e-10 relative for bounds of 1e-5).
inline Eigen::MatrixXd finite_difference_sensitivities(const Experiment& ex, const IdentificationSpec& spec,
                                                       const Eigen::VectorXd& at,
                                                       const Eigen::VectorXd& known,
                                                       const std::vector<Tolerance>& sources) {
  Eigen::MatrixXd J(Eigen::Index(spec.free_terms.size()), Eigen::Index(sources.size()));
  for (std::size_t s = 0; s < sources.size(); ++s) {
    const double h = sources[s].bound;
    Eigen::VectorXd plus = at, minus = at;
    plus[sources[s].parameter] += h;
    minus[sources[s].parameter] -= h;
    J.col(Eigen::Index(s)) = (identify_coefficients<double>(observe<double>(ex, plus, known, spec), spec) -
                              identify_coefficients<double>(observe<double>(ex, minus, known, spec), spec)) /
                             (2 * h);
  }
  return J;
}
inline Eigen::MatrixXd finite_difference_sensitivities(const Config& cfg,
                                                       const std::vector<Tolerance>& sources) {
  const Eigen::VectorXd& at = cfg.centrifuge.errors;
  const IdentificationSpec& spec = cfg.identification;
  const Eigen::VectorXd known = spec.compensate ? at : Eigen::VectorXd::Zero(at.size());
  return finite_difference_sensitivities(cfg.experiment(), spec, at, known, sources);
}

// The covariance Σ_G g_G g_Gᵀ from sensitivities J (coefficients × sources), each σ_s scaled by scale[s].
inline Eigen::MatrixXd lpu_covariance(const Eigen::MatrixXd& J, const std::vector<Tolerance>& sources,
                                      const std::vector<double>& scale = {}) {
  std::map<std::string, Eigen::VectorXd> groups;
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(J.rows(), J.rows());
  for (std::size_t s = 0; s < sources.size(); ++s) {
    const double sigma =
        sigma_from_bound(sources[s].bound, sources[s].distribution) * (scale.empty() ? 1.0 : scale[s]);
    const Eigen::VectorXd effect = J.col(Eigen::Index(s)) * sigma;
    if (sources[s].group.empty()) {
      cov += effect * effect.transpose();
    } else {
      auto [it, fresh] = groups.try_emplace(sources[s].group, Eigen::VectorXd::Zero(J.rows()));
      it->second += effect;
    }
  }
  for (const auto& [name, g] : groups) cov += g * g.transpose();
  return cov;
}

// Covariance of the free coefficients of a configuration for the given sources, bounds scaled by scale[s].
inline Eigen::MatrixXd independent_covariance(const Config& cfg, const std::vector<Tolerance>& sources,
                                              const std::vector<double>& scale = {}) {
  return lpu_covariance(finite_difference_sensitivities(cfg, sources), sources, scale);
}

}  // namespace ccal::test
