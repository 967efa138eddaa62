#include "ccal/verbs/statement.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"
#include "ccal/verbs/budget.hpp"
#include "statement_montecarlo.hpp"

namespace ccal::verbs {
namespace {

// The tolerances' effects as independent components (coefficients × m, SI; uncertainty/budget.hpp), without
// the drives' rate noise. u_B is the norm of a row, the Type B covariance G Gᵀ (docs/model.md §10.1).
Eigen::MatrixXd type_b_groups(const ccal::BudgetResult& b) { return independent_effects(b); }

// The modelled output of each run, stated from the coefficients' covariance parts (see CalibrationStatement).
void state_outputs(const Config& config, const Identification& id, double p, CalibrationStatement& st) {
  const std::vector<Run>& runs = config.plan.runs;
  const Eigen::Index nk = id.design.cols();
  Eigen::VectorXd correction(nk);
  for (Eigen::Index k = 0; k < nk; ++k) correction[k] = st.coefficients[std::size_t(k)].input.correction;
  for (Eigen::Index r = 0; r < id.design.rows(); ++r) {
    const Eigen::VectorXd h = id.design.row(r).transpose();
    StatementInput in;
    in.coefficient = id.row_labels.empty() ? fmt::format("{}", r + 1) : id.row_labels[std::size_t(r)];
    in.unit = id.residual_unit;
    in.estimate = id.modelled[r];
    in.correction = h.dot(correction);
    // Quadratic forms of PSD matrices, ≥ 0 up to round-off: clamped so that the square root exists.
    in.type_a = {std::sqrt(std::max(0.0, h.dot(st.covariance_a * h))),
                 st.coefficients.empty() ? kInfiniteDof : st.coefficients.front().input.type_a.dof};
    in.type_b = {std::sqrt(std::max(0.0, h.dot(st.covariance_b * h))), kInfiniteDof};
    st.outputs.push_back(state_coefficient(in, p));
    const auto run = std::find_if(runs.begin(), runs.end(), [&](const Run& x) { return x.name == in.coefficient; });
    st.g_levels.push_back(run != runs.end() ? run->g_level : std::numeric_limits<double>::quiet_NaN());
  }
}

// Factor from the budget's display unit of a coefficient to the fit's unit for it.
double unit_factor(const std::string& from, const std::string& to, const std::string& term,
                   std::string_view field) {
  if (from == to) return 1;
  try {
    const Quantity a = parse_unit(from), b = parse_unit(to);
    if (a.dim == b.dim) return a.value_si / b.value_si;
  } catch (const UnitError&) {
  }
  throw OptionError(std::string(field), "",
                    fmt::format("{} is in '{}' in the fit and in '{}' in the configuration's budget; "
                                "accepted: a fit whose output unit is the configuration's output_unit",
                                term, to, from));
}

constexpr OptionSpec<StatementOptions> kStatementRows[] = {
    rows::coverage_probability(&StatementOptions::coverage_probability,
                               "Coverage probability p of the statement's intervals, in [0.5, 1)"),
    rows::mode<&StatementOptions::mode>("Kinematics of the statement's budget: exact or paper; default: the "
                                        "configuration's [identification] mode"),
    rows::statement_trials(&StatementOptions::statement_trials),
    rows::seed(&StatementOptions::seed, "Seed of the statement's Monte Carlo check"),
    rows::threads(&StatementOptions::threads),
};

}  // namespace

OptionTable<StatementOptions> options_of(std::type_identity<StatementOptions>) { return kStatementRows; }

CalibrationStatement calibration_statement(const Config& config, const Identification& id,
                                           const StatementOptions& o, std::string_view field) {
  check_options(o, option_table<StatementOptions>());
  if (o.statement_trials > 0) {
    check_thread_count(o.threads, "threads");
    check_coverage_interval(std::uint64_t(o.statement_trials), o.coverage_probability, "statement_trials");
  }
  const FitResult& fit = id.fit;
  if (!id.weighted && fit.dof <= 0)
    throw OptionError(std::string(field), "",
                      fmt::format("the fit has no degrees of freedom ({} observations for {} free terms), so "
                                  "its Type A uncertainty is undefined; accepted: at least one observation more "
                                  "than free terms",
                                  fit.residuals.size(), fit.names.size()));
  BudgetOptions bo;
  bo.mode = o.mode;
  bo.compare_with_paper = false;
  const BudgetResult budget = verbs::budget(config, bo);
  const ccal::BudgetResult& b = budget.budget;
  const Eigen::MatrixXd groups = type_b_groups(b);

  CalibrationStatement st;
  st.budget_config = config.source;
  st.config_sha256 = config.text_sha256;
  if (config.certificate) {
    st.instrument = config.certificate->instrument;
    st.serial_number = config.certificate->serial_number;
    st.date_of_calibration = config.certificate->date_of_calibration;
  }
  st.mode = b.mode;
  st.coverage_probability = o.coverage_probability;
  st.compensated = config.identification.compensate;
  st.known_errors = int((config.centrifuge.errors.array() != 0.0).count());
  // The budget's sensitivities hold for its own free terms: the fit must free the same ones.
  std::vector<std::string> fitted = fit.names, budgeted = b.coefficients;
  std::sort(fitted.begin(), fitted.end());
  std::sort(budgeted.begin(), budgeted.end());
  if (fitted != budgeted)
    throw OptionError(std::string(field), "",
                      fmt::format("the fit's free terms ({}) are not those of {} ({}); accepted: a "
                                  "configuration whose [identification] terms are the fit's",
                                  fmt::join(fit.names, ", "), config.source, fmt::join(b.coefficients, ", ")));
  const auto nk = Eigen::Index(fit.names.size());
  Eigen::MatrixXd g_fit(nk, groups.cols());  // the groups' effects in the fit's order and units
  std::vector<double> to_fit_of(fit.names.size());
  for (std::size_t k = 0; k < fit.names.size(); ++k) {
    const auto found = std::find(b.coefficients.begin(), b.coefficients.end(), fit.names[k]);
    const auto j = std::size_t(found - b.coefficients.begin());
    const auto i = Eigen::Index(k);
    // SI → the budget's display unit → the fit's unit.
    const double to_fit = b.display_scale[j] * unit_factor(b.units[j], id.units[k], fit.names[k], field);
    to_fit_of[k] = to_fit;
    StatementInput in;
    in.coefficient = fit.names[k];
    in.unit = id.units[k];
    in.estimate = fit.value[i];
    in.correction = budget.known_error_bias.size() ? -budget.known_error_bias[Eigen::Index(j)] * to_fit : 0.0;
    in.type_a = {fit.std_error[i], id.weighted ? kInfiniteDof : double(fit.dof)};
    g_fit.row(i) = groups.row(Eigen::Index(j)) * to_fit;
    in.type_b = {g_fit.row(i).norm(), kInfiniteDof};
    st.coefficients.push_back(state_coefficient(in, o.coverage_probability));
  }
  st.covariance_a = fit.covariance;
  st.covariance_b = g_fit * g_fit.transpose();
  st.covariance = st.covariance_a + st.covariance_b;
  st.correlation = st.covariance;
  for (Eigen::Index r = 0; r < nk; ++r)
    for (Eigen::Index c = 0; c < nk; ++c) {
      const double scale = st.coefficients[std::size_t(r)].combined * st.coefficients[std::size_t(c)].combined;
      st.correlation(r, c) = scale > 0 ? st.covariance(r, c) / scale : (r == c ? 1.0 : 0.0);
    }
  state_outputs(config, id, o.coverage_probability, st);
  check_statement_by_monte_carlo(config, id, to_fit_of, o, st);
  return st;
}

}  // namespace ccal::verbs
