#include "ccal/intake/run_log.hpp"

#include <fmt/format.h>

#include <cmath>
#include <functional>
#include <map>
#include <numbers>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "run_log_reducer.hpp"

namespace ccal {

namespace {

// An encoder's fitted rate against the plan: beyond this fraction of the planned main-axis rate the log does
// not belong to the run as planned. Real speed errors and platform mismatches are ppm-sized; a log in degrees
// read as radians, the log of another g-level (rates differ by ≥ 10 % between the paper's levels), a stopped
// or reversed encoder are off by far more.
constexpr double kEncoderRateTolerance = 0.05;

// What an encoder rate `ratio` times the plan's most likely is, in the words of the layout it was read in: a
// ratio of 180/π is degrees read as radians, one of 1000^k or 60^k times in another unit than the one read.
std::string rate_cause(double ratio, const RunLogOptions& o) {
  const auto near = [&](double x) { return std::abs(std::abs(ratio) / x - 1) < 0.01; };
  if (near(180 / std::numbers::pi))
    return "encoder angles in degrees read as radians; accepted: angle_unit = \"deg\" (the option, or the "
           "[columns] key of the manifest or layout)";
  for (const double unit : {1e3, 1e6, 1e9, 60.0, 3600.0, 1e-3, 1e-6, 1e-9, 1 / 60.0, 1 / 3600.0})
    if (near(unit) && !o.columns.iso_time)
      return fmt::format("times in another unit than the one read ({:g} s); accepted: the time column's unit as "
                         "time_unit of the manifest's or layout's [columns] (s by default), or in its units row",
                         o.columns.time_scale);
  return fmt::format("{}the log of another run, or a stopped or reversed encoder",
                     o.angle_quantum > 0 ? "counts_per_revolution other than the encoder's, " : "");
}

void check_encoder_rate(std::string_view source, std::string_view run, std::string_view encoder,
                        double logged, double expected, double planned_rate, const RunLogOptions& o) {
  if (std::abs(logged - expected) <= kEncoderRateTolerance * std::abs(planned_rate)) return;
  const std::string ratio = expected != 0 ? fmt::format(", {:.4g} times the plan's", logged / expected) : "";
  throw InputError(fmt::format(
      "{}: run '{}': the {} encoder turns at {:.6g} rad/s, the plan at {:.6g} rad/s{} (accepted: within {:g} % "
      "of the main-axis rate {:.6g} rad/s); likely cause: {}",
      source, run, encoder, logged, expected, ratio, 100 * kEncoderRateTolerance, std::abs(planned_rate),
      expected != 0 ? rate_cause(logged / expected, o) : rate_cause(0, o)));
}

// Run `index` of the plan as its log shows it: its encoders' rates checked against the plan, the run as
// measured (its rate and phases), the platform's measured mismatch and, counter-rotating, how its control
// looks.
LoggedRun logged_run(const Config& config, const Experiment& ex, std::size_t index, ReducedLog log,
                     const RunLogOptions& options) {
  LoggedRun lr;
  lr.index = index;
  const Run& planned = config.plan.runs[index];
  lr.planned_rate = nominal_rate(planned, ex.geometry, ex.site);
  lr.log = std::move(log);
  if (lr.log.has_theta1)
    check_encoder_rate(lr.log.source, planned.name, "main-axis (theta1)", lr.log.theta1_rate, lr.planned_rate,
                       lr.planned_rate, options);
  if (lr.log.has_gamma)
    check_encoder_rate(lr.log.source, planned.name, "platform (gamma)", lr.log.gamma_rate,
                       planned.mode == PlatformMode::counter_rotating ? -lr.planned_rate : 0.0,
                       lr.planned_rate, options);
  lr.measured = measured_run(planned, lr.log, ex.geometry, ex.site);
  lr.rate = nominal_rate(lr.measured, ex.geometry, ex.site);
  lr.mismatch = measured_platform_mismatch(planned, lr.log);
  if (planned.mode == PlatformMode::counter_rotating) lr.control = platform_control_evidence(lr.log);
  return lr;
}

}  // namespace

ReducedLog reduce_run_log(const CsvTable& table, const RunLogOptions& options, double planned_rate) {
  detail::LogReducer reducer(table.source, options, planned_rate);
  reducer.header(table.header, table.header_line);
  std::vector<std::string_view> fields(table.header.size());
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    for (std::size_t k = 0; k < fields.size(); ++k) fields[k] = table.rows[i][k];
    reducer.row(fields.data(), table.row_lines[i]);
  }
  ReducedLog log = reducer.finish();
  log.sha256 = table.text_sha256;
  return log;
}

ReducedLog reduce_run_log_file(const std::filesystem::path& path, const RunLogOptions& options,
                               double planned_rate) {
  detail::LogReducer reducer(path.string(), options, planned_rate);
  std::string sha256;
  try {
    sha256 = stream_csv_file(path, reducer, options.format);
  } catch (const CsvError&) {  // a ragged row under a preamble's line read as the header: the header's problem
    reducer.throw_no_time();
    throw;
  }
  ReducedLog log = reducer.finish();
  log.sha256 = sha256;
  return log;
}

Run measured_run(const Run& planned, const ReducedLog& log, const Geometry& geometry, const Site& site) {
  Run run = planned;
  run.duration = log.duration;
  if (log.has_theta1) {
    run.g_level = log.theta1_rate * log.theta1_rate * geometry.R0 / site.g_unit();
    run.arm_azimuth = log.theta1_start;
  }
  if (log.has_gamma) {
    run.initial_phase = log.gamma_start;
    run.terminal_phase.reset();
  }
  return run;
}

double measured_platform_mismatch(const Run& planned, const ReducedLog& log) {
  if (!log.has_theta1 || !log.has_gamma || planned.mode != PlatformMode::counter_rotating) return 0.0;
  return -log.gamma_rate - log.theta1_rate;
}

void check_log_count(const IdentificationSpec& spec, std::size_t logs, std::string_view field) {
  if (logs < spec.free_terms.size())
    throw OptionError(std::string(field), "",
                      fmt::format("{} logged run(s) cannot determine {} free terms ({}); accepted: at least {} "
                                  "logs, of runs at different g-levels",
                                  logs, spec.free_terms.size(), fmt::join(spec.free_terms, ", "),
                                  spec.free_terms.size()));
}

namespace {

// A log's source name and its reduction (at the run's planned rate), one per logged run.
using LogSource = std::function<std::string(std::size_t)>;
using LogReader = std::function<ReducedLog(std::size_t, double)>;

// The configured ripple of a drive's channel, replaced by the measured one when there is one.
void set_ripple(Eigen::VectorXd& known, const ErrorLayout& layout, int channel,
                const std::vector<double>& ripple) {
  for (int k = 1; k <= layout.harmonic_order() && std::size_t(2 * k) <= ripple.size(); ++k) {
    known[layout.harmonic_index(channel, k, false)] = ripple[std::size_t(2 * k - 2)];
    known[layout.harmonic_index(channel, k, true)] = ripple[std::size_t(2 * k - 1)];
  }
}

std::vector<double> configured_ripple(const Eigen::VectorXd& known, const ErrorLayout& layout, int channel) {
  std::vector<double> r;
  for (int k = 1; k <= layout.harmonic_order(); ++k)
    for (bool sine : {false, true}) r.push_back(known[layout.harmonic_index(channel, k, sine)]);
  return r;
}

// The measured ripple of the drives (model.md §13.1): the main axis's from θ1's harmonics; the platform's
// from γ's, less what a phase-locked platform takes over from the main axis (−δ1, in the model's main ripple,
// measured or configured).
void measured_ripple(LoggedRun& lr, const Config& config, Eigen::VectorXd& known) {
  const ErrorLayout& layout = config.centrifuge.layout;
  if (!lr.log.theta1_harmonics.empty()) {
    lr.main_ripple = ripple_from_angle_harmonics(
        resolved_harmonics(lr.log.theta1_harmonics, lr.log.theta1_harmonic_sigma));
    set_ripple(known, layout, ch::ripple1, lr.main_ripple);
  }
  if (!lr.log.gamma_harmonics.empty() && lr.measured.mode == PlatformMode::counter_rotating) {
    std::vector<double> angle = resolved_harmonics(lr.log.gamma_harmonics, lr.log.gamma_harmonic_sigma);
    if (config.centrifuge.geometry.platform_control == PlatformControl::phase_locked) {
      const double psi0 = lr.measured.arm_azimuth + lr.measured.initial_phase.value_or(0.0);
      const std::vector<double> main = main_angle_error_in_gamma(
          angle_harmonics_from_ripple(configured_ripple(known, layout, ch::ripple1)), psi0);
      for (std::size_t i = 0; i < angle.size() && i < main.size(); ++i) angle[i] += main[i];
    }
    lr.platform_ripple = ripple_from_angle_harmonics(angle);
    set_ripple(known, layout, ch::ripple3, lr.platform_ripple);
  }
}

LogReduction model_logged_runs(const Config& config, const std::vector<std::size_t>& indices,
                               const LogSource& source, const LogReader& read, const RunLogOptions& options,
                               ModelMode mode) {
  const Experiment ex = config.experiment();
  check_log_count(config.identification, indices.size(),
                  "logs");                  // before reading any log: the cheaper mistake
  std::map<std::size_t, LoggedRun> by_run;  // plan order
  for (std::size_t i = 0; i < indices.size(); ++i) {
    const std::size_t index = indices[i];
    if (index >= config.plan.runs.size())
      throw InputError(fmt::format("{}: run index {} is outside the plan's {} runs", source(i), index,
                                   config.plan.runs.size()));
    if (by_run.count(index))
      throw InputError(fmt::format("{}: run '{}' is logged twice; accepted: one log per run", source(i),
                                   config.plan.runs[index].name));
    const double planned_rate = nominal_rate(config.plan.runs[index], ex.geometry, ex.site);
    by_run.emplace(index, logged_run(config, ex, index, read(i, planned_rate), options));
  }
  const IdentificationSpec& spec = config.identification;
  check_log_count(spec, by_run.size(), "logs");

  // The model of each run as measured: its own rate and phases, so the speed error is in the rate (Δω = 0 in
  // the model), a measured platform mismatch replaces the configured one and a measured ripple the
  // configured ripple of its drive.
  LogReduction r;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  Observations<double>& obs = r.observations;
  for (auto& [index, lr] : by_run) {
    Eigen::VectorXd known = spec.compensate ? config.centrifuge.errors : zero;
    if (lr.log.has_theta1) known[ch::domega] = 0.0;
    if (lr.log.has_theta1 && lr.log.has_gamma) known[ch::dOmega] = lr.mismatch;
    if (!lr.log.has_gamma) lr.mismatch = known[ch::dOmega];
    measured_ripple(lr, config, known);
    Experiment one = ex;
    one.plan.runs = {lr.measured};
    const Observations<double> row = observe<double>(one, known, known, spec, mode);
    const auto j = Eigen::Index(r.runs.size());
    if (j == 0) {
      const auto n = Eigen::Index(by_run.size());
      obs.columns = row.columns;
      obs.regressors.resize(n, row.regressors.cols());
      obs.output.resize(n);
      obs.known_rate.resize(n);
      obs.input.resize(n);
    }
    obs.runs.push_back(row.runs[0]);
    obs.regressors.row(j) = row.regressors.row(0);
    obs.output[j] = lr.log.mean_output;
    obs.known_rate[j] = row.known_rate[0];
    obs.input[j] = row.input[0];
    r.runs.push_back(std::move(lr));
  }
  return r;
}

RunLogOptions with_order(RunLogOptions o, const Config& config) {
  o.harmonic_order = config.centrifuge.layout.harmonic_order();
  return o;
}

}  // namespace

LogReduction reduce_logs(const Config& config, const std::vector<std::pair<std::size_t, CsvTable>>& logs,
                         const RunLogOptions& options, ModelMode mode) {
  std::vector<std::size_t> indices;
  for (const auto& log : logs) indices.push_back(log.first);
  const RunLogOptions o = with_order(options, config);
  return model_logged_runs(
      config, indices, [&](std::size_t i) { return logs[i].second.source; },
      [&](std::size_t i, double rate) { return reduce_run_log(logs[i].second, o, rate); }, o, mode);
}

LogReduction reduce_log_files(const Config& config,
                              const std::vector<std::pair<std::size_t, std::filesystem::path>>& logs,
                              const RunLogOptions& options, ModelMode mode) {
  std::vector<std::size_t> indices;
  for (const auto& log : logs) indices.push_back(log.first);
  const RunLogOptions o = with_order(options, config);
  return model_logged_runs(
      config, indices, [&](std::size_t i) { return logs[i].second.string(); },
      [&](std::size_t i, double rate) { return reduce_run_log_file(logs[i].second, o, rate); }, o, mode);
}

}  // namespace ccal
