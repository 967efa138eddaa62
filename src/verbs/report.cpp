#include "ccal/verbs/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <set>
#include <utility>

#include "ccal/core/errors.hpp"
#include "ccal/model/instrument.hpp"
#include "ccal/setup/input_description.hpp"
#include "ccal/uncertainty/allocate.hpp"
#include "ccal/verbs/force.hpp"

namespace ccal::verbs {
namespace {

constexpr auto kReportRows = join_rows(std::to_array<OptionSpec<ReportOptions>>({
    rows::mode<&ReportOptions::mode>("Kinematics: exact or paper; default: the configuration's "
                                     "[identification] mode"),
    {"run", &ReportOptions::run, "J",
     "Run whose sensed input is drawn (name or 1-based index); default: the highest g-level"},
    {"input_points", &ReportOptions::input_points, "N", "Instants of the sensed-input curve",
     OptionRange::between(2, 100000)},
    rows::coverage_factor(&ReportOptions::coverage_factor),
    rows::statement_trials(&ReportOptions::statement_trials),
    {"history_db", &ReportOptions::history_db, "FILE",
     "History store: the calibrations of the [certificate]'s serial number in it, charted with their drift"},
    {"engineering", &ReportOptions::engineering, "",
     "The engineering report (budget, Monte Carlo, paper comparison, sensed input, provenance) instead of the "
     "calibration certificate that observations with a [certificate] table give"},
}),
    // The Monte Carlo section's options, as `ccal montecarlo`'s (its kinematics are the report's mode).
    lifted_rows<&ReportOptions::monte_carlo, kPropagationRows>());

std::size_t highest_g_run(const TestPlan& plan) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < plan.runs.size(); ++k)
    if (plan.runs[k].g_level > plan.runs[best].g_level) best = k;
  return best;
}

// The run's exact input at evenly spaced instants of a window: the whole run, or, when the platform turns
// more than 3 times in it, its first 3 revolutions (a longer window would only alias the curve).
SensedInputSeries sensed_input(const Config& config, const ReportOptions& o) {
  if (config.plan.runs.empty()) throw InputError(config.source + ": the test plan has no runs");
  SensedInputSeries s;
  s.run_index = o.run.empty() ? highest_g_run(config.plan) : select_run(config.plan, o.run, "run");
  const Run& run = config.plan.runs[s.run_index];
  s.run_name = run.name;
  s.g_level = run.g_level;
  s.duration = run.duration;
  s.platform_rate = std::abs(nominal_platform_rate(run, config.centrifuge.geometry, config.site));
  const double revolutions = s.platform_rate > 0 ? 3 * 2 * std::numbers::pi / s.platform_rate : run.duration;
  s.window = std::min(run.duration, revolutions);
  ForceOptions fo;
  fo.run = std::to_string(s.run_index + 1);
  for (int k = 0; k < o.input_points; ++k) {
    fo.time = s.window * double(k) / double(o.input_points - 1);
    const SensedInputBreakdown b = force(config, fo).input;  // the instrument's exact input at t
    s.time.push_back(fo.time);
    s.ia.push_back(b.specific_force[0]);
    s.pa.push_back(b.specific_force[1]);
    s.oa.push_back(b.specific_force[2]);
    s.ia_first_order.push_back(b.first_order_f_ia);
  }
  for (const double t : {0.0, s.window / 2, s.window}) {
    fo.time = t;
    s.instants.push_back(force(config, fo));
  }
  return s;
}

// The allocation's and the design's targets, parsed as the verbs will parse them, so that a bad one is
// refused (naming the report's option) before the long computations start.
void check_targets(const Config& config, const ReportOptions& o) {
  std::vector<std::string> units;
  for (const auto& id : config.identification.free_terms)
    units.push_back(coefficient_unit(config.instrument.output_unit, id, config.instrument.g_symbol));
  if (o.allocate) {
    if (o.allocate->targets.empty())
      throw OptionError("allocate_targets", "", "none given; the allocation needs at least one target, e.g. K3=2e-3");
  }
  // Each list checked under its own option's name (the verbs it is passed to would name theirs, --target).
  const auto check = [&](const std::vector<std::string>& targets, const char* field) {
    std::set<std::string> seen;
    for (const auto& t : targets) {
      const AllocationTarget a = parse_allocation_target(t, config.identification.free_terms, units, field);
      if (!seen.insert(a.coefficient).second)
        throw OptionError(field, a.coefficient, "has two targets; accepted: one target per coefficient");
    }
  };
  if (o.allocate) check(o.allocate->targets, "allocate_targets");
  if (o.design) check(o.design->targets, "design_targets");
}

// The observations identified, and their calibration statement with the configuration's budget (`ccal
// identify OBS.csv --statement --config CONFIG`); an error of the file or of its terms is refused naming the
// observations option.
IdentifyResult identify_observations(const Config& config, const ReportOptions& o) {
  const StatementOptions so = report_sections(o).identify.statement_options;
  try {
    // A plain table needs terms and columns the report has no options for: say so, not identify's terms.
    if (!observations_header(*o.observations))
      throw OptionError(
          "observations", o.observations->source,
          fmt::format("has no '# ccal observations' line, so it is not an observations file of ccal; accepted: "
                      "the observations simulate or reduce writes ({}); a plain table is identified with its "
                      "terms and a statement by identify ({} with {})",
                      OptionError::name("observations_out"), OptionError::name("statement"),
                      OptionError::name("config")));
    check_observations_configuration(*o.observations, config, "observations");
    IdentifyResult r = identify(*o.observations, {});
    const TestEvidence evidence = test_evidence(observations_header(*o.observations), r.identification);
    r.statement = calibration_statement(config, r.identification, so, "observations", evidence.measured,
                                        evidence.durations);
    return r;
  } catch (const OptionError& e) {
    if (e.field() == "observations") throw;
    throw OptionError("observations", "", e.what());
  } catch (const InputError& e) {
    throw OptionError("observations", "", e.what());  // what names the file where it is the file's fault
  }
}

// The statement's inputs with the kind of standard each rests on.
std::vector<TracedInput> traced_inputs(const Config& config, const CalibrationStatement& statement) {
  std::vector<TracedInput> traced;
  for (const StatementSource& s : statement.inputs) {
    const auto t = std::ranges::find(config.tolerances, s.id, &Tolerance::id);
    traced.push_back({s.id, t == config.tolerances.end() ? s.id : describe_input(config, t->parameter).traceability});
  }
  return traced;
}

}  // namespace

OptionTable<ReportOptions> options_of(std::type_identity<ReportOptions>) { return kReportRows; }

bool gives_certificate(const Config& config, const ReportOptions& o) {
  return o.observations && config.certificate && !o.engineering;
}

ReportResult report(const Config& config, const ReportOptions& o) {
  require_one_instrument(config, "report");
  check_options(o, option_table<ReportOptions>());
  rows::check_coverage_choice(o.monte_carlo.coverage_probability, o.coverage_factor);
  // The statement's check runs only on observations: without them the option would be passed over in silence.
  if (!o.observations && o.statement_trials)  // at its default value too: the option is refused, not its value
    throw OptionError("statement_trials", std::to_string(*o.statement_trials),
                      fmt::format("checks the statement of observations, and none are given; accepted: {} with {}, "
                                  "or {} left out",
                                  OptionError::name("statement_trials"), OptionError::name("observations"),
                                  OptionError::name("statement_trials")));
  check_targets(config, o);
  ReportResult r;
  r.config = config;
  if (o.observations) {
    r.observed = identify_observations(config, o);
    const Eigen::VectorXd means = o.observations->numbers(r.observed->spec.output, "the certificate's runs");
    r.observed_means.assign(means.data(), means.data() + means.size());
  }
  if (!o.history_db.empty()) {
    if (!config.certificate || config.certificate->serial_number.empty())
      throw OptionError(
          "history_db", o.history_db,
          fmt::format("needs the serial number whose history to show; accepted: a configuration "
                      "with [certificate] serial_number ({} has none)",
                      config.source));
    const std::string& serial = config.certificate->serial_number;
    if (!HistoryStore::open(o.history_db, HistoryStore::Access::read).records(serial).empty()) {
      r.history = history_show(serial, {o.history_db, ""});
      r.history->db = std::filesystem::path(o.history_db).filename().string();  // a report names no folder
    }
  }
  const ReportSections sections = report_sections(o);
  r.budget = budget(config, sections.budget);
  // The allocation and the design before the Monte Carlo, so that a target they refuse stops the report
  // early.
  if (sections.allocate) r.allocation = allocate(config, *sections.allocate);
  if (sections.design) {
    r.design = design(config, *sections.design);
    ForceOptions fo;
    for (std::size_t k = 0; k < config.plan.runs.size(); ++k) {
      fo.run = std::to_string(k + 1);
      r.configured_runs.push_back(force(config, fo));
    }
  }
  r.certificate = gives_certificate(config, o);
  if (r.certificate) {
    r.traceability = traceability_lines(*config.certificate, traced_inputs(config, *r.observed->statement));
    if (std::string gaps = traceability_gaps_text(r.traceability); !gaps.empty())
      r.warnings.push_back(std::move(gaps));
    return r;
  }  // the certificate shows neither the tolerances' Monte Carlo nor the sensed input
  r.monte_carlo = monte_carlo(config, sections.monte_carlo);
  r.sensed_input = sensed_input(config, o);
  return r;
}

ReportSections report_sections(const ReportOptions& o) {
  ReportSections s;
  const PropagationOptions& mc = o.monte_carlo;
  s.budget.mode = o.mode;
  s.budget.coverage_probability = mc.coverage_probability;
  s.budget.coverage_factor = o.coverage_factor;
  s.monte_carlo = {mc, o.mode};
  s.monte_carlo.propagation.keep_samples = false;  // the report draws the histograms of the JSON, not the values
  s.allocate = o.allocate;
  if (s.allocate && !s.allocate->mode) s.allocate->mode = o.mode;
  s.design = o.design;
  s.identify.statement = true;
  StatementOptions& st = s.identify.statement_options;
  st.mode = o.mode;
  st.coverage_probability = mc.coverage_probability;
  st.coverage_factor = o.coverage_factor;
  st.statement_trials = o.statement_trials;
  // Set only where not the unset value's: the "same as" identify command names only what differs from it.
  if (mc.seed != kDefaultSeed) st.seed = mc.seed;
  if (mc.threads != 0) st.threads = mc.threads;
  return s;
}

AllocateOptions report_allocation(std::vector<std::string> targets, const ReportOptions& o) {
  AllocateOptions a;
  a.targets = std::move(targets);
  a.coverage_probability = o.monte_carlo.coverage_probability.value_or(kDefaultCoverageProbability);
  a.seed = o.monte_carlo.seed;
  a.threads = o.monte_carlo.threads;
  return a;
}

DesignOptions report_design(std::vector<std::string> targets, const ReportOptions& o) {
  DesignOptions d;
  d.targets = std::move(targets);
  d.coverage_probability = o.monte_carlo.coverage_probability;
  d.coverage_factor = o.coverage_factor;
  d.threads = o.monte_carlo.threads;
  return d;
}

}  // namespace ccal::verbs
