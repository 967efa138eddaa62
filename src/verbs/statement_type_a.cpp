#include "statement_type_a.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <optional>

#include "ccal/core/units.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/reduction/observe.hpp"

namespace ccal::verbs {
namespace {

// SI size of one unit of the residuals, if they are in a unit (a plain table's column name is none).
std::optional<double> residual_unit_si(const Identification& id) {
  try {
    return output_unit_si(id.residual_unit);
  } catch (const UnitError&) {
    return std::nullopt;
  }
}

// The plan's run of each row of the identification (by its label), if every row names one.
std::optional<std::vector<std::size_t>> plan_rows(const Config& config, const Identification& id) {
  std::vector<std::size_t> rows;
  for (const std::string& label : id.row_labels) {
    const auto& runs = config.plan.runs;
    const auto it = std::find_if(runs.begin(), runs.end(), [&](const Run& r) { return r.name == label; });
    if (it == runs.end()) return std::nullopt;
    rows.push_back(std::size_t(it - runs.begin()));
  }
  if (rows.size() != std::size_t(id.design.rows())) return std::nullopt;
  return rows;
}

// What the known [errors] the model leaves out do to each row's mean (residuals' unit): ȳ(truth with them,
// model without) − ȳ(neither), of the plan's runs. Deterministic, so the residuals' check removes its share
// M·Δy before comparing the scatter with the noise (0 when the model compensates them, or there are none).
Eigen::VectorXd known_error_means(const Config& config, ModelMode mode, const std::vector<std::size_t>& rows,
                                  double unit_si) {
  Eigen::VectorXd shift = Eigen::VectorXd::Zero(Eigen::Index(rows.size()));
  const Eigen::VectorXd& errors = config.centrifuge.errors;
  if (config.identification.compensate || (errors.array() == 0.0).all()) return shift;
  const Experiment ex = config.experiment();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(errors.size());
  const Eigen::VectorXd with = observe<double>(ex, errors, zero, config.identification, mode).output;
  const Eigen::VectorXd without = observe<double>(ex, zero, zero, config.identification, mode).output;
  for (std::size_t j = 0; j < rows.size(); ++j)
    shift[Eigen::Index(j)] = (with[Eigen::Index(rows[j])] - without[Eigen::Index(rows[j])]) / unit_si;
  return shift;
}

}  // namespace

// σ_j of each row's mean (residuals' unit): white output noise N²/T, the pulse count's two ends each
// rounded within one quantum q (a triangular error of half-width q/T: q²/(6T²)), and each drive's rate noise
// (docs/model.md §3.2).
Eigen::VectorXd run_noise(const Config& config, const ccal::BudgetDetail& b, const std::vector<std::size_t>& rows,
                          const std::vector<double>& durations, double unit_si) {
  const InstrumentModel& ins = config.instrument;
  Eigen::VectorXd sd(Eigen::Index(rows.size()));
  for (std::size_t j = 0; j < rows.size(); ++j) {
    const double T = durations.size() == rows.size() ? durations[j] : config.plan.runs[rows[j]].duration;
    double variance = ins.noise_density * ins.noise_density / T + ins.quantum * ins.quantum / (6 * T * T);
    for (const RateNoiseBudget& n : b.rate_noise) variance += n.run_sd[Eigen::Index(rows[j])] * n.run_sd[Eigen::Index(rows[j])];
    sd[Eigen::Index(j)] = std::sqrt(variance) / unit_si;
  }
  return sd;
}

// The Type B inputs' effects on each row's mean as independent components (rows × components, residuals'
// unit): the budget's output Jacobian of the plan's runs at the configured errors, times each input's u.
Eigen::MatrixXd run_effects(const Config& config, const ccal::BudgetDetail& b, const std::vector<std::size_t>& rows,
                            double unit_si) {
  if (b.sources.empty()) return Eigen::MatrixXd::Zero(Eigen::Index(rows.size()), 0);
  std::vector<int> parameters;
  for (const SourceBudget& s : b.sources) parameters.push_back(s.parameter);
  const OutputJacobian jacobian = output_jacobian(config.experiment(), config.identification, parameters,
                                                  config.centrifuge.errors, b.mode, {}, DerivativeMethod::automatic,
                                                  false);
  Eigen::MatrixXd e(Eigen::Index(rows.size()), Eigen::Index(parameters.size()));
  for (std::size_t j = 0; j < rows.size(); ++j)
    for (std::size_t s = 0; s < parameters.size(); ++s)
      e(Eigen::Index(j), Eigen::Index(s)) =
          jacobian.total(Eigen::Index(rows[j]), Eigen::Index(s)) * b.sources[s].standard_uncertainty / unit_si;
  return independent_effects(b, e);
}

double type_a_dof(double known_variance, double estimated_variance, double dof) {
  if (!(estimated_variance > 0) || !std::isfinite(dof)) return kInfiniteDof;
  const double total = known_variance + estimated_variance;
  return dof * total * total / (estimated_variance * estimated_variance);
}

TypeAParts evaluate_type_a(const Config& config, const Identification& id, const ccal::BudgetDetail& b,
                           const std::vector<double>& durations) {
  const FitResult& fit = id.fit;
  TypeAParts parts;
  parts.evaluation.dof = fit.dof;
  const auto nk = Eigen::Index(fit.names.size());
  if (id.weighted) {  // σ given with the observations, taken as known
    parts.known = fit.covariance;
    parts.estimated = Eigen::MatrixXd::Zero(nk, nk);
    return parts;
  }
  const std::optional<double> unit_si = residual_unit_si(id);
  const std::optional<std::vector<std::size_t>> rows = plan_rows(config, id);
  const bool noisy = config.instrument.noise_density > 0 || config.instrument.quantum > 0 || !b.rate_noise.empty();
  if (!unit_si || !rows || !noisy || fit.dof <= 0) {  // the fit's scatter, ν = n − p
    parts.known = Eigen::MatrixXd::Zero(nk, nk);
    parts.estimated = fit.covariance;
    parts.dof = fit.dof;
    return parts;
  }
  TypeAEvaluation& ev = parts.evaluation;
  ev.from_noise_model = true;
  const Eigen::MatrixXd& H = id.design;
  const Eigen::MatrixXd pinv = H.completeOrthogonalDecomposition().pseudoInverse();  // H⁺ of the fit
  const Eigen::VectorXd sd = run_noise(config, b, *rows, durations, *unit_si);
  ev.run_sd.assign(sd.data(), sd.data() + sd.size());
  parts.known = pinv * sd.cwiseAbs2().asDiagonal() * pinv.transpose();

  // The residuals r = M y, M = I − H H⁺, against V = M (Σ + D Dᵀ) Mᵀ: S = rᵀ W r with W = Σ⁻¹ has mean
  // E = tr(W V) and, for normal r, variance 2 tr((W V)²); S is taken as a χ²_f scaled by a of the same two.
  const auto n = H.rows();
  const Eigen::MatrixXd M = Eigen::MatrixXd::Identity(n, n) - H * pinv;
  const Eigen::MatrixXd D = run_effects(config, b, *rows, *unit_si);
  const Eigen::MatrixXd sigma = Eigen::MatrixXd(sd.cwiseAbs2().asDiagonal()) + D * D.transpose();
  const Eigen::VectorXd w = sd.cwiseAbs2().cwiseInverse();
  const Eigen::MatrixXd WV = w.asDiagonal() * (M * sigma * M.transpose());
  const Eigen::VectorXd r = fit.residuals - M * known_error_means(config, b.mode, *rows, *unit_si);
  ev.statistic = r.dot(w.asDiagonal() * r);
  ev.expected = WV.trace();
  const double variance = 2 * (WV * WV).trace();
  if (ev.expected > 0 && variance > 0) {
    const double scale = variance / (2 * ev.expected), f = 2 * ev.expected * ev.expected / variance;
    ev.p_value = boost::math::cdf(boost::math::complement(boost::math::chi_squared(f), ev.statistic / scale));
  }
  parts.estimated = Eigen::MatrixXd::Zero(nk, nk);
  if (ev.p_value < kResidualCheckLevel && ev.statistic > ev.expected) {
    ev.excess = true;
    ev.excess_variance = (ev.statistic - ev.expected) / (w.asDiagonal() * M).trace();
    parts.estimated = ev.excess_variance * pinv * pinv.transpose();
    parts.dof = fit.dof;
  }
  return parts;
}

}  // namespace ccal::verbs
