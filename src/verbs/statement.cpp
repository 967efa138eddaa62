#include "ccal/verbs/statement.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccal/core/errors.hpp"
#include "ccal/setup/input_description.hpp"
#include "ccal/core/units.hpp"
#include "ccal/intake/measured_inputs.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/simulate.hpp"
#include "statement_montecarlo.hpp"
#include "statement_type_a.hpp"

namespace ccal::verbs {
namespace {

// The tolerances' effects as independent components (coefficients × m, SI; uncertainty/budget.hpp), without
// the drives' rate noise. u_B is the norm of a row, the Type B covariance G Gᵀ (docs/model.md §10.1).
Eigen::MatrixXd type_b_groups(const ccal::BudgetDetail& b) { return independent_effects(b); }

// The modelled output of each run, stated from the coefficients' covariance parts (see CalibrationStatement).
void state_outputs(const Config& config, const Identification& id, const TypeAParts& a, double p,
                   std::optional<double> k, CalibrationStatement& st) {
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
    const double known = std::max(0.0, h.dot(a.known * h)), estimated = std::max(0.0, h.dot(a.estimated * h));
    in.type_a = {std::sqrt(known + estimated), type_a_dof(known, estimated, a.dof)};
    in.type_b = {std::sqrt(std::max(0.0, h.dot(st.covariance_b * h))), kInfiniteDof};
    st.outputs.push_back(state_coefficient(in, p, k));
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

}  // namespace

OptionTable<StatementOptions> options_of(std::type_identity<StatementOptions>) { return kStatementRows; }

Config with_measured_inputs(const Config& config, const std::vector<MeasuredInput>& measured) {
  Config c = config;
  for (const MeasuredInput& m : measured) {
    const auto t = std::find_if(c.tolerances.begin(), c.tolerances.end(),
                                [&](const Tolerance& x) { return x.id == m.id; });
    if (t == c.tolerances.end()) continue;  // an input without a tolerance was not charged before either
    t->bound = m.standard_uncertainty;
    t->distribution = Distribution::normal;
    t->group.clear();
    std::erase_if(c.correlations, [&](const Correlation& r) { return r.first == m.id || r.second == m.id; });
  }
  // What the encoders measured: the time base then acts on that rate, an encoder's error on that ripple.
  for (const MeasuredInput& m : measured) {
    c.chain.main_rate_measured = c.chain.main_rate_measured || m.id == "domega";
    c.chain.platform_rate_measured = c.chain.platform_rate_measured || m.id == "dOmega";
    c.chain.main_ripple_measured = c.chain.main_ripple_measured || m.id.starts_with("ripple1_");
    c.chain.platform_ripple_measured = c.chain.platform_ripple_measured || m.id.starts_with("ripple3_");
  }
  return c;
}

CalibrationStatement expected_statement(const Config& config, double p, std::optional<ModelMode> mode) {
  Config quiet = config;  // the noise is the Type A part's to state, not the observations' to carry
  quiet.instrument.noise_density = 0;
  quiet.instrument.quantum = 0;
  SimulateOptions so;
  so.mode = mode;
  const SimulateResult sim = simulate(quiet, so);
  StatementOptions o;
  o.coverage_probability = p;
  o.mode = mode;
  o.statement_trials = 0;
  return calibration_statement(config, sim.identification, o, "plan", expected_measured_inputs(config));
}

TestEvidence test_evidence(const std::optional<ObservationsHeader>& header, const Identification& id) {
  TestEvidence e;
  if (!header) return e;
  e.measured = header->measured;
  for (const std::string& row : id.row_labels) {
    const auto log = std::find_if(header->logs.begin(), header->logs.end(),
                                  [&](const ObservationsHeader::Log& l) { return l.run == row; });
    if (log == header->logs.end() || !(log->duration > 0)) return {e.measured, {}};
    e.durations.push_back(log->duration);
  }
  return e;
}

namespace {

// The Type B part's table of inputs: each tolerance's u, how it was obtained, and its effect on each
// coefficient in the fit's units.
std::vector<StatementSource> statement_sources(const Config& config, const ccal::BudgetDetail& b,
                                               const std::vector<MeasuredInput>& measured,
                                               const std::vector<std::size_t>& budget_row,
                                               const std::vector<double>& to_fit) {
  std::vector<StatementSource> out;
  for (std::size_t s = 0; s < b.sources.size(); ++s) {
    const SourceBudget& src = b.sources[s];
    StatementSource line;
    line.id = src.id;
    // Shown in the unit its tolerance was written in, else the input's own display unit (rad, um, ppm, K).
    const InputDescription d = describe_input(config, src.parameter);
    line.unit = config.tolerances[s].unit.empty() ? d.display_unit : config.tolerances[s].unit;
    line.unit_si = unit_in_si(d, line.unit);
    line.standard_uncertainty = src.standard_uncertainty;
    const auto m = std::find_if(measured.begin(), measured.end(), [&](const MeasuredInput& x) { return x.id == src.id; });
    line.measured = m != measured.end();
    if (line.measured)
      line.basis = fmt::format("measured in this test ({}{})", m->how,
                               m->resolved ? "" : "; not resolved, within the fit's resolution");
    else
      line.basis = fmt::format("from its tolerance ({})", distribution_name(src.distribution));
    for (std::size_t k = 0; k < budget_row.size(); ++k)
      line.effect.push_back(src.effect[Eigen::Index(budget_row[k])] * to_fit[k]);
    line.group = config.tolerances[s].group;  // cleared for a measured input (with_measured_inputs)
    out.push_back(std::move(line));
  }
  return out;
}

// The statement's options checked, and its coverage probability: a stated k gives a normal quantity's p, the
// p the statement names and its Monte Carlo check reports at.
double statement_probability(const StatementOptions& o) {
  check_options(o, option_table<StatementOptions>());
  rows::check_coverage_choice(o.coverage_probability, o.coverage_factor);
  // A stated k gives a normal quantity's p: the p the statement names and its Monte Carlo check reports at.
  const double p = o.coverage_factor ? normal_coverage_probability(*o.coverage_factor)
                                     : o.coverage_probability.value_or(kDefaultCoverageProbability);
  if (o.trials() > 0) {
    check_thread_count(o.threads.value_or(0), "threads");
    check_coverage_interval(std::uint64_t(o.trials()), p, "statement_trials");
  }
  return p;
}

// Type A from the fit's scatter needs degrees of freedom (a weighted fit has its σ).
void check_type_a_defined(const Identification& id, std::string_view field) {
  if (!id.weighted && id.fit.dof <= 0)
    throw OptionError(
        std::string(field), "",
        fmt::format("the fit has no degrees of freedom ({} observations for {} free terms), so "
                    "its Type A uncertainty is undefined; accepted: at least one observation more "
                    "than free terms",
                    id.fit.residuals.size(), id.fit.names.size()));
}

// What the statement names of its configuration: the file, its fingerprints, and its [certificate]'s fields.
void describe_configuration(const Config& config, CalibrationStatement& st) {
  st.budget_config = config.source;
  st.config_sha256 = config.text_sha256;
  st.setup_sha256 = config.setup_sha256;
  if (config.certificate) {
    st.instrument = config.certificate->instrument;
    st.serial_number = config.certificate->serial_number;
    st.date_of_calibration = config.certificate->date_of_calibration;
    st.certificate_number = config.certificate->number;
    st.revision = config.certificate->revision;
    st.replaces = config.certificate->replaces;
  }
}

// The budget's sensitivities hold for its own free terms: the fit must free the same ones.
void check_same_terms(const FitResult& fit, const ccal::BudgetDetail& b, const Config& config,
                      std::string_view field) {
  std::vector<std::string> fitted = fit.names, budgeted = b.coefficients;
  std::sort(fitted.begin(), fitted.end());
  std::sort(budgeted.begin(), budgeted.end());
  if (fitted != budgeted)
    throw OptionError(std::string(field), "",
                      fmt::format("the fit's free terms ({}) are not those of {} ({}); accepted: a "
                                  "configuration whose [identification] terms are the fit's",
                                  fmt::join(fit.names, ", "), config.source, fmt::join(b.coefficients, ", ")));
}

// The correlation of the corrected estimates, from their covariance and combined uncertainties (1 on the
// diagonal, 0 off it, where an uncertainty is 0).
Eigen::MatrixXd correlation_of_statement(const CalibrationStatement& st) {
  Eigen::MatrixXd correlation = st.covariance;
  const auto nk = st.covariance.rows();
  for (Eigen::Index r = 0; r < nk; ++r)
    for (Eigen::Index c = 0; c < nk; ++c) {
      const double scale =
          st.coefficients[std::size_t(r)].combined * st.coefficients[std::size_t(c)].combined;
      correlation(r, c) = scale > 0 ? st.covariance(r, c) / scale : (r == c ? 1.0 : 0.0);
    }
  return correlation;
}

}  // namespace

CalibrationStatement calibration_statement(const Config& original, const Identification& id,
                                           const StatementOptions& o, std::string_view field,
                                           const std::vector<MeasuredInput>& measured,
                                           const std::vector<double>& durations) {
  const double p = statement_probability(o);
  const FitResult& fit = id.fit;
  check_type_a_defined(id, field);
  // What the test measured is charged at its measurement's uncertainty, not at its tolerance.
  const Config config = with_measured_inputs(original, measured);
  BudgetOptions bo;
  bo.mode = o.mode;
  bo.compare_with_paper = false;
  const BudgetResult budget = verbs::budget(config, bo);
  const ccal::BudgetDetail& b = budget.budget;
  const Eigen::MatrixXd groups = type_b_groups(b);

  CalibrationStatement st;
  describe_configuration(config, st);
  st.mode = b.mode;
  st.coverage_probability = p;
  st.coverage_factor = o.coverage_factor;
  st.compensated = config.identification.compensate;
  st.known_errors = int((config.centrifuge.errors.array() != 0.0).count());
  check_same_terms(fit, b, config, field);
  const TypeAParts a = evaluate_type_a(config, id, b, durations);
  st.type_a = a.evaluation;
  const auto nk = Eigen::Index(fit.names.size());
  Eigen::MatrixXd g_fit(nk, groups.cols());  // the groups' effects in the fit's order and units
  std::vector<double> to_fit_of(fit.names.size());
  std::vector<std::size_t> budget_row(fit.names.size());
  for (std::size_t k = 0; k < fit.names.size(); ++k) {
    const auto found = std::find(b.coefficients.begin(), b.coefficients.end(), fit.names[k]);
    const auto j = std::size_t(found - b.coefficients.begin());
    budget_row[k] = j;
    const auto i = Eigen::Index(k);
    // SI → the budget's display unit → the fit's unit.
    const double to_fit = b.display_scale[j] * unit_factor(b.units[j], id.units[k], fit.names[k], field);
    to_fit_of[k] = to_fit;
    StatementInput in;
    in.coefficient = fit.names[k];
    in.unit = id.units[k];
    in.estimate = fit.value[i];
    in.correction = budget.known_error_bias.size() ? -budget.known_error_bias[Eigen::Index(j)] * to_fit : 0.0;
    const double known = a.known(i, i), estimated = a.estimated(i, i);
    in.type_a = {std::sqrt(known + estimated), type_a_dof(known, estimated, a.dof)};
    g_fit.row(i) = groups.row(Eigen::Index(j)) * to_fit;
    in.type_b = {g_fit.row(i).norm(), kInfiniteDof};
    st.coefficients.push_back(state_coefficient(in, p, o.coverage_factor));
  }
  st.inputs = statement_sources(config, b, measured, budget_row, to_fit_of);
  st.input_correlations = config.correlations;  // a measured input's pairs removed (with_measured_inputs)
  st.covariance_a = a.known + a.estimated;
  st.covariance_b = g_fit * g_fit.transpose();
  st.covariance = st.covariance_a + st.covariance_b;
  st.correlation = correlation_of_statement(st);
  state_outputs(config, id, a, p, o.coverage_factor, st);
  check_statement_by_monte_carlo(config, id, to_fit_of, a, o, st);
  return st;
}

void refuse_statement_options_unasked(const StatementOptions& o, std::string_view field, bool with_mode) {
  std::optional<std::pair<std::string, std::string>> given;  // the first given: its field and value
  if (o.coverage_probability) given.emplace("coverage_probability", fmt::format("{}", *o.coverage_probability));
  else if (o.coverage_factor) given.emplace("coverage_factor", fmt::format("{}", *o.coverage_factor));
  else if (with_mode && o.mode) given.emplace("mode", std::string(mode_name(*o.mode)));
  else if (o.statement_trials) given.emplace("statement_trials", fmt::format("{}", *o.statement_trials));
  else if (o.seed) given.emplace("seed", fmt::format("{}", *o.seed));
  else if (o.threads) given.emplace("threads", fmt::format("{}", *o.threads));
  if (!given) return;
  throw OptionError(given->first, given->second,
                    fmt::format("is an option of the calibration statement, which is not asked for; accepted: "
                                "{} with {}, or {} left out",
                                OptionError::name(given->first), OptionError::name(field),
                                OptionError::name(given->first)));
}

}  // namespace ccal::verbs
