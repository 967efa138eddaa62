#include "ccal/budget.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "ccal/scalar.hpp"
#include "ccal/units.hpp"

namespace ccal {

namespace {

// ∂K̂/∂e for the given parameters: one Dual pass per kDualWidth parameters through the truth reduction; the
// model side (design, known rate, fixed terms) is computed once in double.
Eigen::MatrixXd jacobian(const Experiment& ex, const IdentificationSpec& spec,
                         const std::vector<int>& parameters, const Eigen::VectorXd& at,
                         const Eigen::VectorXd& known, ModelMode mode, const ReductionOptions& reduction) {
  const Observations<double> model = observe<double>(ex, at, known, spec, mode, reduction);
  const auto nfree = Eigen::Index(spec.free_terms.size());
  const Eigen::MatrixXd H = model.regressors.leftCols(nfree);
  // H⁺ by the column-scaled QR of solve_least_squares applied to the identity (the design is data here).
  const Eigen::Index runs = H.rows();
  Eigen::MatrixXd pinv(nfree, runs);
  for (Eigen::Index j = 0; j < runs; ++j)
    pinv.col(j) = solve_least_squares<double>(H, Eigen::VectorXd::Unit(runs, j));

  Eigen::MatrixXd J(nfree, Eigen::Index(parameters.size()));
  const int n = ex.layout.size();
  for (std::size_t first = 0; first < parameters.size(); first += kDualWidth) {
    VecX<Dual> e(n);
    for (int i = 0; i < n; ++i) e[i] = make_dual(at[i], -1);
    for (int k = 0; k < kDualWidth && first + std::size_t(k) < parameters.size(); ++k)
      e[parameters[first + std::size_t(k)]].derivatives()[k] = 1.0;
    Eigen::MatrixXd dy(runs, kDualWidth);
    for (Eigen::Index j = 0; j < runs; ++j) {
      const ccal::Run& run = ex.plan.runs[std::size_t(j)];
      const RunAverage<Dual> avg =
          mode == ModelMode::exact
              ? average_run<Dual>(ex.geometry, ex.layout, e, ex.site, run, &ex.instrument, {}, reduction)
              : detail::paper_average<Dual>(ex, e, run, &ex.instrument, {}, spec.paper_cross_terms);
      dy.row(j) = avg.output.derivatives().transpose();
    }
    const Eigen::MatrixXd dk = pinv * dy;
    for (int k = 0; k < kDualWidth && first + std::size_t(k) < parameters.size(); ++k)
      J.col(Eigen::Index(first) + k) = dk.col(k);
  }
  return J;
}

}  // namespace

std::string coefficient_unit(std::string_view output_unit, std::string_view term_id) {
  const TermSpec term = parse_term(term_id).value();
  const int order = term.kind == TermKind::power ? term.power : (term.kind == TermKind::rate ? 0 : 1);
  std::string unit(output_unit);
  if (term.kind == TermKind::power || term.kind == TermKind::p || term.kind == TermKind::o) {
    if (order == 1) unit += "/g";
    if (order > 1) unit += "/g^" + std::to_string(order);
  } else if (term.kind != TermKind::rate) {
    unit += "/g^2";
  }
  return unit;
}

SensitivityTable sensitivities(const Experiment& ex, const IdentificationSpec& spec,
                               const std::vector<int>& parameters, const Eigen::VectorXd& at,
                               const Eigen::VectorXd& known, ModelMode mode,
                               const ReductionOptions& reduction) {
  SensitivityTable t;
  t.coefficients = spec.free_terms;
  t.parameters = parameters;
  t.total = jacobian(ex, spec, parameters, at, known, mode, reduction);
  Experiment force_only = ex;
  force_only.instrument.rate_gain = 0.0;
  t.force_path = jacobian(force_only, spec, parameters, at, known, mode, reduction);
  t.rate_path = t.total - t.force_path;
  return t;
}

std::vector<CompensationChoice> compensation_choices(const Experiment& ex, const IdentificationSpec& spec,
                                                     const Eigen::VectorXd& at, const Eigen::VectorXd& known,
                                                     ModelMode mode, bool with_paper,
                                                     const ReductionOptions& reduction) {
  std::vector<CompensationChoice> out;
  if (!ex.site.earth_rotation) return out;
  auto bias = [&](ModelMode m, bool coriolis) {
    Experiment model = ex;
    (coriolis ? model.site.apply_coriolis : model.site.sense_earth_rate) = false;
    const auto with =
        identify_coefficients<double>(observe<double>(ex, ex, at, known, spec, m, reduction), spec);
    const auto without =
        identify_coefficients<double>(observe<double>(ex, model, at, known, spec, m, reduction), spec);
    return Eigen::VectorXd(without - with);
  };
  for (bool coriolis : {false, true}) {
    CompensationChoice c;
    c.id = coriolis ? "coriolis" : "earth_rate";
    c.description = coriolis ? "Coriolis force 2 w_ie x v left out of the model"
                             : "Earth rate on the instrument left out of the model";
    c.bias = bias(mode, coriolis);
    if (with_paper) c.paper_bias = bias(ModelMode::paper, coriolis);
    out.push_back(std::move(c));
  }
  return out;
}

BudgetResult compute_budget(const Config& config, const BudgetOptions& options) {
  const Experiment ex = config.experiment();
  const IdentificationSpec& spec = config.identification;
  const Eigen::VectorXd& at = config.centrifuge.errors;
  const Eigen::VectorXd known = spec.compensate ? at : Eigen::VectorXd::Zero(at.size());

  std::vector<int> parameters;
  for (const Tolerance& t : config.tolerances) parameters.push_back(t.parameter);
  const SensitivityTable table =
      sensitivities(ex, spec, parameters, at, known, options.mode, options.reduction);
  SensitivityTable paper;
  const bool compare = options.mode == ModelMode::exact && options.compare_with_paper;
  if (compare) paper = sensitivities(ex, spec, parameters, at, known, ModelMode::paper, options.reduction);

  BudgetResult r;
  r.mode = options.mode;
  r.coefficients = spec.free_terms;
  r.coverage_factor = options.coverage_factor;
  const auto nk = Eigen::Index(r.coefficients.size());
  for (const auto& id : r.coefficients) {
    r.units.push_back(coefficient_unit(config.instrument.output_unit, id));
    r.display_scale.push_back(to_unit(1.0, config.instrument.output_unit));
  }

  // Contributions, grouped sums, totals.
  std::vector<std::string> groups;
  Eigen::MatrixXd group_effect = Eigen::MatrixXd::Zero(nk, 0);
  for (std::size_t s = 0; s < config.tolerances.size(); ++s) {
    const Tolerance& t = config.tolerances[s];
    SourceBudget b;
    b.parameter = t.parameter;
    b.id = t.id;
    b.group = t.group;
    b.distribution = t.distribution;
    b.bound = t.bound;
    b.standard_uncertainty = standard_uncertainty(t.bound, t.distribution);
    b.sensitivity = table.total.col(Eigen::Index(s));
    b.effect = b.sensitivity * b.standard_uncertainty;
    b.effect_force = table.force_path.col(Eigen::Index(s)) * b.standard_uncertainty;
    b.effect_rate = table.rate_path.col(Eigen::Index(s)) * b.standard_uncertainty;
    if (compare) b.paper_effect = paper.total.col(Eigen::Index(s)) * b.standard_uncertainty;
    const std::string key = t.group.empty() ? "#" + t.id : t.group;
    auto it = std::find(groups.begin(), groups.end(), key);
    if (it == groups.end()) {
      groups.push_back(key);
      group_effect.conservativeResize(nk, group_effect.cols() + 1);
      group_effect.col(group_effect.cols() - 1) = b.effect;
    } else {
      group_effect.col(it - groups.begin()) += b.effect;
    }
    r.sources.push_back(std::move(b));
  }
  r.covariance = group_effect * group_effect.transpose();
  r.standard_uncertainty = r.covariance.diagonal().cwiseSqrt();
  r.expanded_uncertainty = r.coverage_factor * r.standard_uncertainty;
  r.correlation = Eigen::MatrixXd::Identity(nk, nk);
  for (Eigen::Index i = 0; i < nk; ++i)
    for (Eigen::Index j = 0; j < nk; ++j)
      if (i != j && r.standard_uncertainty[i] > 0 && r.standard_uncertainty[j] > 0)
        r.correlation(i, j) = r.covariance(i, j) / (r.standard_uncertainty[i] * r.standard_uncertainty[j]);

  // Exact vs paper: flagged where they differ by more than the factor (or in sign) and the larger of the two
  // matters, i.e. reaches 1e-3 of the coefficient's total standard uncertainty (a factor between two
  // negligible numbers is no finding).
  if (compare) {
    for (SourceBudget& b : r.sources) {
      for (Eigen::Index k = 0; k < nk; ++k) {
        const double x = std::abs(b.effect[k]), p = std::abs(b.paper_effect[k]);
        const double big = std::max(x, p), small = std::min(x, p);
        const bool material = big >= 1e-3 * r.standard_uncertainty[k] && big > 0.0;
        const bool opposite = b.effect[k] * b.paper_effect[k] < 0;
        b.disagrees.push_back(material && (opposite || big > options.disagreement_factor * small));
      }
    }
  }

  std::vector<double> largest(r.sources.size(), 0.0);
  for (std::size_t s = 0; s < r.sources.size(); ++s) {
    SourceBudget& b = r.sources[s];
    b.share = Eigen::VectorXd::Zero(nk);
    for (Eigen::Index k = 0; k < nk; ++k) {
      const double var = r.covariance(k, k);
      b.share[k] = var > 0 ? b.effect[k] * b.effect[k] / var : 0.0;
    }
    largest[s] = b.share.size() ? b.share.maxCoeff() : 0.0;
  }
  std::vector<std::size_t> order(r.sources.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return largest[a] > largest[b]; });
  for (std::size_t pos = 0; pos < order.size(); ++pos) r.sources[order[pos]].rank = int(pos) + 1;
  r.compensation = compensation_choices(ex, spec, at, known, options.mode, compare, options.reduction);
  return r;
}

}  // namespace ccal
