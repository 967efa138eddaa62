#include "ccal/verbs/reduce.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>

#include "ccal/core/errors.hpp"
#include "ccal/intake/measured_inputs.hpp"
#include "ccal/core/options.hpp"
#include "ccal/core/units.hpp"
#include "ccal/io/observation_csv.hpp"
#include "reduce_instruments.hpp"
#include "run_check.hpp"

namespace ccal::verbs {

namespace {

// A log file that cannot be opened, refused as the reader refuses it.
void check_readable(const std::string& name) {
  std::error_code ec;
  if (std::ifstream(name, std::ios::binary) && !std::filesystem::is_directory(name, ec)) return;
  throw FileNotFound<CsvError>(name, 0, 0, "", unreadable_file_problem(name));
}

// A warning for each run whose encoders contradict the configured platform control.
void warn_about_control(const Config& cfg, ReduceResult& r) {
  const PlatformControl configured = cfg.centrifuge.geometry.platform_control;
  const std::string_view name = configured == PlatformControl::speed ? "speed" : "phase_locked";
  for (const LoggedRun& lr : r.logs.runs) {
    const ControlLook look = lr.control.look;
    if (look != ControlLook::speed && look != ControlLook::phase_locked) continue;
    if ((look == ControlLook::speed) == (configured == PlatformControl::speed)) continue;
    r.warnings.push_back(fmt::format(
        "run '{}': the encoders look like platform_control = \"{}\" (the platform angle carries lambda = "
        "{:.3g} of the main axis's ripple), the configuration has \"{}\" (model.md §13.2)",
        lr.measured.name, control_look_name(look), lr.control.following, name));
  }
}

// A log that spans less than kMinimumLogShare of its run's planned duration: the mean is over what was logged
// (and the statement's Type A part uses that span), but a log cut short, or the log of a shorter run, should not
// pass unseen.
constexpr double kMinimumLogShare = 0.9;
void warn_about_short_logs(const Config& cfg, ReduceResult& r) {
  for (const LoggedRun& lr : r.logs.runs) {
    const double planned = cfg.plan.runs[lr.index].duration;
    if (!(planned > 0) || lr.log.duration >= kMinimumLogShare * planned) continue;
    r.warnings.push_back(fmt::format(
        "run '{}': the log spans {:.6g} s of the planned {:.6g} s ({:.3g} %, below {:g} %); the run's mean is that "
        "of the span logged: check that the log is whole and of this run",
        lr.measured.name, lr.log.duration, planned, 100 * lr.log.duration / planned, 100 * kMinimumLogShare));
  }
}

// Two runs whose logs have the same bytes (one SHA-256) are one log given twice, a slip of the copy or of the
// manifest: its mean read at two g-levels would fit a curvature that is not there (K3 = 10.6 for 0.003).
// A problem of one log, where it was named: at its manifest's line (the key of its run), else as the option's.
[[noreturn]] void refuse_log(const LogFile& log, std::string item, std::string problem) {
  if (log.manifest.empty()) throw OptionError("logs", std::move(item), std::move(problem));
  const std::string key = "runs." + log.run;
  throw LocatedInputError(
      fmt::format("{}:{}:{}: {}: {} {}", log.manifest, log.line, log.column, key, item, problem), log.manifest,
      log.line, log.column, key, item + " " + problem);
}

// Checked twice: by path before reading (one file named for two runs), by the bytes' SHA-256 after (a copy).
// `named`: each run's LogFile by its index in the plan.
[[noreturn]] void throw_repeated_log(const Config& cfg, const std::map<std::size_t, LogFile>& named,
                                     std::size_t run, std::size_t earlier_run, std::string_view how) {
  const std::string &file = named.at(run).path, &earlier_file = named.at(earlier_run).path;
  refuse_log(named.at(run), fmt::format("run '{}'", cfg.plan.runs[run].name),
             fmt::format("has the same log as run '{}' ({}); accepted: each run's own log",
                         cfg.plan.runs[earlier_run].name,
                         file == earlier_file ? fmt::format("{} {}", file, how)
                                              : fmt::format("{} and {} {}", earlier_file, file, how)));
}

void refuse_repeated_paths(const Config& cfg, const std::map<std::size_t, LogFile>& named) {
  for (auto k = named.begin(); k != named.end(); ++k)
    for (auto j = named.begin(); j != k; ++j) {  // j before k in the plan
      std::error_code ec;
      if (std::filesystem::equivalent(j->second.path, k->second.path, ec))
        throw_repeated_log(cfg, named, k->first, j->first, "is named for both");
    }
}

void refuse_repeated_logs(const Config& cfg, const std::map<std::size_t, LogFile>& named, const ReduceResult& r) {
  std::map<std::string, std::size_t> first_of;  // SHA-256 → position in r.logs.runs
  for (std::size_t k = 0; k < r.logs.runs.size(); ++k) {
    const auto [it, fresh] = first_of.emplace(r.logs.runs[k].log.sha256, k);
    if (fresh || r.logs.runs[k].log.sha256.empty()) continue;
    throw_repeated_log(cfg, named, r.logs.runs[k].index, r.logs.runs[it->second].index,
                       fmt::format("hold the same bytes, SHA-256 {}…", r.logs.runs[k].log.sha256.substr(0, 12)));
  }
}

// Each run's mean against the nominal instrument's reading there (run_check.hpp): a warning per run beyond
// kRunCheckLimit u, or with strict_runs the refusal of the first, located where its log was named, naming the
// others.
void check_nominal_readings(const Config& cfg, const std::map<std::size_t, LogFile>& named, bool strict,
                            ReduceResult& r) {
  const std::vector<RunCheck> checks = check_runs(cfg, r.logs, r.mode);
  std::vector<const RunCheck*> beyond;
  for (const RunCheck& c : checks)
    if (c.beyond) beyond.push_back(&c);
  if (beyond.empty()) return;
  if (!strict) {
    for (const RunCheck* c : beyond) r.warnings.push_back(run_check_finding(cfg, checks, *c));
    return;
  }
  std::string also;
  for (std::size_t k = 1; k < beyond.size(); ++k)
    also += fmt::format("{}'{}'", k == 1 ? "; so are runs " : ", ", cfg.plan.runs[beyond[k]->index].name);
  const std::string finding = run_check_finding(cfg, checks, *beyond.front());
  const std::string name = fmt::format("run '{}'", cfg.plan.runs[beyond.front()->index].name);
  // The finding is "run '…': …": its run is the refusal's item (a manifest's key, or the log option's value).
  refuse_log(named.at(beyond.front()->index), name + ":",
             fmt::format("{}{}; accepted: each run's own log (to see the fit anyway: the runs' check as a "
                         "warning, not strict)",
                         finding.substr(name.size() + 2), also));
}

}  // namespace

std::vector<std::string> ripple_ids(const Config& cfg, std::string_view channel) {
  std::vector<std::string> ids;
  for (int k = 1; k <= cfg.centrifuge.layout.harmonic_order(); ++k)
    for (const char* part : {"c", "s"}) ids.push_back(fmt::format("{}_{}{}", channel, part, k));
  return ids;
}

namespace {

// The strict_runs row's help, its limit written from kRunCheckLimit at compile time (the constant's one home).
constexpr auto kStrictRunsLimit = static_cast<unsigned long long>(kRunCheckLimit);
static_assert(kRunCheckLimit >= 1 && double(kStrictRunsLimit) == kRunCheckLimit,
              "the strict_runs help writes the limit as a whole number");
constexpr std::string_view kStrictRunsHead = "Refuse a run whose log's mean is more than ";
constexpr std::string_view kStrictRunsTail =
    " standard uncertainties from what the nominal instrument reads at that run (a swapped or mislabelled log), "
    "instead of warning";
constexpr std::size_t strict_runs_digits() {
  std::size_t n = 1;
  for (auto x = kStrictRunsLimit; x >= 10; x /= 10) ++n;
  return n;
}
constexpr auto kStrictRunsHelp = [] {
  std::array<char, kStrictRunsHead.size() + strict_runs_digits() + kStrictRunsTail.size()> text{};
  std::size_t at = 0;
  for (const char c : kStrictRunsHead) text[at++] = c;
  at += strict_runs_digits();
  auto x = kStrictRunsLimit;
  for (std::size_t k = at; k-- > kStrictRunsHead.size(); x /= 10) text[k] = char('0' + x % 10);
  for (const char c : kStrictRunsTail) text[at++] = c;
  return text;
}();

constexpr auto kReduceRows = join_rows(
    std::to_array<OptionSpec<ReduceOptions>>({
        {"angle_unit", enum_member<&ReduceOptions::angle_unit>(kAngleUnitNames), "UNIT",
         "Unit of the encoder columns: rad or deg"},
        {"pulse_weight", &ReduceOptions::pulse_weight, "W",
         "Integrated output per pulse, in the output unit × s (e.g. deg for deg/s); default: the instrument's "
         "quantum"},
        {"strict_runs", &ReduceOptions::strict_runs, "", {kStrictRunsHelp.data(), kStrictRunsHelp.size()}},
        rows::mode<&ReduceOptions::mode>("Model of the regressors: exact (full chain) or paper; default: "
                                         "[identification] mode of the configuration"),
        {"statement", &ReduceOptions::statement, "",
         "Also the calibration statement (JCGM 100 §7): Type A from the fit, Type B from the configuration's "
         "tolerances, the correction for known [errors], u_c, nu_eff, k, U, interval"},
    }),
    // The statement's rows but its mode, which is the reduction's.
    lifted_rows<&ReduceOptions::statement_options, kStatementRows, 0, kStatementModeRow>(),
    lifted_rows<&ReduceOptions::statement_options, kStatementRows, kStatementModeRow + 1>());

}  // namespace

OptionTable<ReduceOptions> options_of(std::type_identity<ReduceOptions>) { return kReduceRows; }

namespace {
OptionError pulse_weight_refused(std::string value, const std::string& output_unit) {
  return OptionError(
      "pulse_weight", std::move(value),
      fmt::format("is not a positive weight; accepted: the integrated output per pulse, a positive "
                  "number in {}·s or with a unit of that kind, e.g. 2.5e-5",
                  output_unit));
}
// A test of several's logs, read for one [instrument]: refused, naming the columns and what is accepted.
void refuse_instrument_columns(const Config& cfg, const ReduceOptions& o) {
  if (o.layout.instruments.empty()) return;
  std::vector<std::string> ids;
  for (const auto& column : o.layout.instruments) ids.push_back(column.id);
  throw InputError(fmt::format(
      "{}: [instruments] names the output columns of instruments {}, and {} has one [instrument]; accepted: "
      "the "
      "configuration of that test ([[instruments]]), or [columns] pulses = \"…\" (or output) naming this "
      "instrument's column",
      o.logs.empty() || o.logs.front().manifest.empty() ? std::string("the log layout")
                                                        : o.logs.front().manifest,
      fmt::join(ids, ", "), cfg.source));
}

// Each log with its run's index in the plan (`named`: each log by that index): a run named once, its file
// readable, and as many logs as the identification needs (a manifest's [runs] too short said so).
std::vector<std::pair<std::size_t, std::filesystem::path>> selected_logs(
    const Config& cfg, const ReduceOptions& o, std::map<std::size_t, LogFile>& named) {
  std::vector<std::pair<std::size_t, std::filesystem::path>> logs;
  for (const LogFile& log : o.logs) {
    std::size_t index = 0;
    try {
      index = select_run(cfg.plan, log.run, "logs");
    } catch (const OptionError& e) {
      if (log.manifest.empty()) throw;
      refuse_log(log, fmt::format("'{}'", log.run), std::string(e.problem()));
    }
    if (named.count(index))
      refuse_log(log, fmt::format("run '{}'", cfg.plan.runs[index].name),
                 "is logged twice; accepted: one log per run");
    named[index] = log;
    check_readable(log.path);  // a missing file before the count of logs, as when logs were read whole
    logs.emplace_back(index, log.path);
  }
  try {
    check_log_count(cfg.identification, logs.size(), "logs");
  } catch (const OptionError& e) {  // logs a manifest named: its [runs] is short, not an option
    if (o.logs.empty() || o.logs.front().manifest.empty()) throw;
    throw InputError(fmt::format("{}: [runs]: {}", o.logs.front().manifest, e.problem()));
  }
  return logs;
}

}  // namespace

double pulse_weight_from_text(const Config& cfg, std::string_view text) {
  const std::string& output = cfg.instrument.output_unit;
  constexpr std::string_view kName = "the pulse weight";
  const Dimension dim = parse_unit(pulse_as_rad(output)).dim * kind::time;
  double weight = 0;
  try {
    weight = parse_real_option("pulse_weight", text);  // a bare number: in the output unit × s
  } catch (const OptionError&) {
    try {
      weight = parse_as(pulse_as_rad(text), dim, kName) / output_unit_si(output);
    } catch (const UnitError& e) {
      // "the pulse weight: '1 m': unit 'm' is a length, expected an angle (accepted: rad, …, arcsec)"
      std::string what = e.what();
      if (what.starts_with(kName)) what.erase(0, kName.size() + 2);
      throw OptionError("pulse_weight", "",
                        fmt::format("{}; or a bare number in {}·s, e.g. 2.5e-5", what, output));
    }
  }
  // Refused here, as typed ("-2.5e-5 deg"): the check in run_log_options sees only the number.
  if (!(std::isfinite(weight) && weight > 0)) throw pulse_weight_refused(std::string(text), output);
  return weight;
}

RunLogOptions run_log_options(const Config& cfg, const ReduceOptions& o) {
  RunLogOptions lo;
  // The output column in the output unit, or the volts across a sampling resistor (A per V = 1/R).
  lo.output_scale = cfg.instrument.sampling_resistor > 0 ? 1.0 / cfg.instrument.sampling_resistor
                                                          : output_unit_si(cfg.instrument.output_unit);
  lo.angle_scale = o.angle_unit == AngleUnit::deg ? std::numbers::pi / 180 : 1.0;
  lo.columns = o.layout.columns;
  lo.format = o.layout.format;
  lo.max_gap = o.layout.max_gap;
  lo.time_unit_stated = o.layout.time_unit;
  lo.angle_unit_stated = !o.layout.angle_unit.empty()  ? o.layout.angle_unit
                         : o.angle_unit != AngleUnit::rad ? std::string(kAngleUnitNames[std::size_t(o.angle_unit)])
                                                          : std::string();
  lo.output_unit = cfg.instrument.sampling_resistor > 0 ? "V" : cfg.instrument.output_unit;
  if (!o.layout.angle_unit.empty()) {
    if (o.angle_unit != AngleUnit::rad)
      throw OptionError(
          "angle_unit", std::string(kAngleUnitNames[std::size_t(o.angle_unit)]),
          fmt::format("and the manifest's angle_unit '{}' are two answers for the encoders' unit; "
                      "accepted: one of them (the manifest's, leaving this option out)",
                      o.layout.angle_unit));
    lo.angle_scale = o.layout.angle_scale;
    if (o.layout.counts_per_revolution > 0) {
      lo.angle_quantum = o.layout.angle_scale;
      // A count rounded down stands for the middle of its count: (c + 1/2)·2π/cpr.
      if (o.layout.count_rounding == CountRounding::floor) lo.angle_offset = 0.5 * o.layout.angle_scale;
    }
  }
  lo.pulse_weight = cfg.instrument.quantum;
  if (o.pulse_weight) {
    if (!(std::isfinite(*o.pulse_weight) && *o.pulse_weight > 0))
      throw pulse_weight_refused(option_number_text(*o.pulse_weight), cfg.instrument.output_unit);
    lo.pulse_weight = *o.pulse_weight * output_unit_si(cfg.instrument.output_unit);
  }
  return lo;
}

std::vector<LogFile> manifest_logs(const LogManifest& manifest) {
  std::vector<LogFile> logs;
  for (const LogManifest::Entry& entry : manifest.runs)
    logs.push_back({entry.run, entry.file.string(), manifest.source, entry.line, entry.column});
  return logs;
}

ReduceResult reduce(const Config& cfg, const ReduceOptions& o) {
  check_options(o, option_table<ReduceOptions>());
  if (!o.statement) refuse_statement_options_unasked(o.statement_options, "statement", false);
  if (!cfg.instruments.empty()) return reduce_instruments(cfg, o);
  refuse_instrument_columns(cfg, o);
  ReduceResult r;
  r.config = cfg;
  r.mode = o.mode.value_or(cfg.mode);
  r.output_unit_si = output_unit_si(cfg.instrument.output_unit);
  const RunLogOptions lo = run_log_options(cfg, o);
  std::map<std::size_t, LogFile> named;  // by the run's index in the plan
  const auto logs = selected_logs(cfg, o, named);
  refuse_repeated_paths(cfg, named);
  r.logs = reduce_log_files(cfg, logs, lo, r.mode);  // each log streamed in one pass
  for (const LoggedRun& lr : r.logs.runs) r.files.push_back(named[lr.index].path);
  refuse_repeated_logs(cfg, named, r);
  std::vector<Run> measured;
  std::vector<double> rates;
  for (const LoggedRun& lr : r.logs.runs) {
    measured.push_back(lr.measured);
    rates.push_back(lr.rate);
  }
  const DataResolution resolution =
      run_resolution(measured, rates, r.logs.observations, cfg.identification, cfg.instrument);
  // The logs' files and fingerprints go into the observations file's header, for the provenance of a result.
  // So do the inputs the logs measured, which the calibration statement of that file charges (identify, report).
  std::vector<ObservationsHeader::Log> fingerprints;
  for (std::size_t k = 0; k < r.logs.runs.size(); ++k)
    fingerprints.push_back({cfg.plan.runs[r.logs.runs[k].index].name, r.logs.runs[k].log.sha256, r.files[k],
                            r.logs.runs[k].log.duration});
  const std::vector<MeasuredInput> measured_by_logs = measured_inputs(cfg, r.logs);
  r.identification = identify_observations(r.logs.observations, cfg.identification, cfg.instrument,
                                           cfg.source, &resolution, cfg.numbers_sha256, fingerprints, measured_by_logs);
  r.warnings = r.identification.id.observability.warnings;
  warn_about_control(cfg, r);
  warn_about_short_logs(cfg, r);
  check_nominal_readings(cfg, named, o.strict_runs, r);
  if (o.statement) {
    std::vector<double> durations;
    for (const LoggedRun& lr : r.logs.runs) durations.push_back(lr.log.duration);
    StatementOptions so = o.statement_options;
    so.mode = r.mode;  // the statement's budget in the reduction's kinematics
    r.statement = calibration_statement(cfg, r.identification.id, so, "statement", measured_by_logs, durations);
  }
  return r;
}

}  // namespace ccal::verbs
