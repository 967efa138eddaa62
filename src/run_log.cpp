#include "ccal/run_log.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <numbers>

#include "ccal/errors.hpp"

namespace ccal {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

double wrapped(double angle) {
  const double a = std::fmod(angle, kTwoPi);
  return a < 0 ? a + kTwoPi : a;
}

// The least-squares line through (t_k, a_k) of unwrapped angles: slope, value at t_0, value at t_last, and
// the RMS residual. Times are centred on their mean for a well-conditioned solution.
struct Line {
  double slope = 0, start = 0, end = 0, rms = 0;
};
Line fit_line(const Eigen::VectorXd& t, const Eigen::VectorXd& a) {
  const double tm = t.mean(), am = a.mean();
  const Eigen::VectorXd dt = t.array() - tm, da = a.array() - am;
  const double slope = dt.dot(da) / dt.squaredNorm();
  Line l;
  l.slope = slope;
  l.start = am + slope * (t[0] - tm);
  l.end = am + slope * (t[t.size() - 1] - tm);
  l.rms = std::sqrt((da - slope * dt).squaredNorm() / double(t.size()));
  return l;
}

// The encoder column unwrapped: each step mapped to (−π, π]. The samples must be less than half a revolution
// apart at the planned rate (with a 1/4 margin for a rate error), or the unwrapping would alias.
Eigen::VectorXd unwrapped(const CsvTable& table, std::string_view column, const Eigen::VectorXd& time,
                          double scale, double planned_rate) {
  const std::size_t k = *table.find(column);
  Eigen::VectorXd a = table.numbers(column, "the encoder reduction") * scale;
  for (Eigen::Index i = 1; i < a.size(); ++i) {
    const double step_time = time[i] - time[i - 1];
    if (std::abs(planned_rate) * step_time > 0.75 * std::numbers::pi)
      throw table.error_at(
          std::size_t(i), k,
          fmt::format("samples {:.6g} s apart turn the joint by {:.3g} rad at the planned rate; "
                      "accepted: less than 0.75π rad between encoder samples",
                      step_time, std::abs(planned_rate) * step_time));
    double step = std::remainder(a[i] - a[i - 1], kTwoPi);
    if (step == -std::numbers::pi) step = std::numbers::pi;
    a[i] = a[i - 1] + step;
  }
  return a;
}

// An encoder's fitted rate against the plan: beyond this fraction of the planned main-axis rate the log does not
// belong to the run as planned. Real speed errors and platform mismatches are ppm-sized; a log in degrees read
// as radians, the log of another g-level (rates differ by ≥ 10 % between the paper's levels), a stopped or
// reversed encoder are off by far more.
constexpr double kEncoderRateTolerance = 0.05;

void check_encoder_rate(std::string_view source, std::string_view run, std::string_view encoder,
                        double logged, double expected, double planned_rate) {
  if (std::abs(logged - expected) <= kEncoderRateTolerance * std::abs(planned_rate)) return;
  throw InputError(fmt::format(
      "{}: run '{}': the {} encoder turns at {:.6g} rad/s, the plan at {:.6g} rad/s (accepted: within {:g} % "
      "of the main-axis rate {:.6g} rad/s); likely cause: encoder angles in degrees without --angle-unit "
      "deg, the log of another run, or a stopped or reversed encoder",
      source, run, encoder, logged, expected, 100 * kEncoderRateTolerance, std::abs(planned_rate)));
}

}  // namespace

ReducedLog reduce_run_log(const CsvTable& table, const RunLogOptions& options, double planned_rate) {
  ReducedLog r;
  r.source = table.source;
  r.samples = table.rows.size();
  const auto time_column = table.find("time");
  const Eigen::VectorXd t = table.numbers("time", "every run log");
  if (r.samples < 2)
    throw CsvError(
        table.source, table.header_line, int(*time_column + 1), "time",
        fmt::format("{} sample(s); accepted: at least two, the first and last of the run", r.samples));
  for (std::size_t i = 1; i < r.samples; ++i)
    if (!(t[Eigen::Index(i)] > t[Eigen::Index(i - 1)]))
      throw table.error_at(i, *time_column,
                           fmt::format("time {} s does not follow {} s; accepted: strictly increasing times",
                                       t[Eigen::Index(i)], t[Eigen::Index(i - 1)]));
  r.duration = t[t.size() - 1] - t[0];
  if (!std::isfinite(r.duration))
    throw CsvError(table.source, table.row_lines.back(), int(*time_column + 1), "time",
                   fmt::format("the span {} s to {} s overflows; accepted: times of a run, in s", t[0],
                               t[t.size() - 1]));

  const auto pulses = table.find("pulses"), output = table.find("output");
  if (pulses.has_value() == output.has_value())
    throw CsvError(table.source, table.header_line, 0, pulses ? "pulses" : "output",
                   pulses ? "both 'pulses' and 'output' columns; accepted: exactly one of them"
                          : fmt::format("no output column; accepted: 'pulses' (cumulative count) or 'output' "
                                        "(the instrument's output); the columns are {}",
                                        fmt::join(table.header, ", ")));
  if (pulses) {
    if (!(options.pulse_weight > 0))
      throw CsvError(table.source, table.header_line, int(*pulses + 1), "pulses",
                     "a pulse count needs the pulse weight (the instrument's quantum, or --pulse-weight); "
                     "accepted: a positive integrated output per pulse");
    const Eigen::VectorXd p = table.numbers("pulses", "the output mean");
    r.pulses = true;
    r.mean_output = (p[p.size() - 1] - p[0]) * options.pulse_weight / r.duration;
  } else {
    const Eigen::VectorXd y = table.numbers("output", "the output mean") * options.output_scale;
    double integral = 0;
    for (Eigen::Index i = 1; i < y.size(); ++i) integral += 0.5 * (y[i] + y[i - 1]) * (t[i] - t[i - 1]);
    r.mean_output = integral / r.duration;
  }

  // The fit squares the means: beyond 1e150 (SI) its sums overflow, and the failure would surface far from
  // the log.
  if (!(std::abs(r.mean_output) <= 1e150)) {
    const std::size_t k = pulses ? *pulses : *output;
    throw CsvError(table.source, table.header_line, int(k + 1), table.header[k],
                   fmt::format("the mean output over the log, {:.6g} (SI), overflows the fit; accepted: the "
                               "instrument's output in its output unit, or a pulse count, below 1e150",
                               r.mean_output));
  }
  if (table.find("theta1")) {
    const Line l = fit_line(t, unwrapped(table, "theta1", t, options.angle_scale, planned_rate));
    r.has_theta1 = true;
    r.theta1_rate = l.slope;
    r.theta1_start = wrapped(l.start);
    r.theta1_rms = l.rms;
  }
  if (table.find("gamma")) {
    const Line l = fit_line(t, unwrapped(table, "gamma", t, options.angle_scale, planned_rate));
    r.has_gamma = true;
    r.gamma_rate = l.slope;
    r.gamma_start = wrapped(l.start);
    r.gamma_end = wrapped(l.end);
    r.gamma_rms = l.rms;
  }
  return r;
}

Run measured_run(const Run& planned, const ReducedLog& log, const Geometry& geometry, const Site& site) {
  Run run = planned;
  run.duration = log.duration;
  if (log.has_theta1) {
    run.g_level = log.theta1_rate * log.theta1_rate * geometry.R0 / site.g;
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

void check_log_count(const IdentificationSpec& spec, std::size_t logs, std::string_view where) {
  if (logs < spec.free_terms.size())
    throw InputError(fmt::format(
        "{}: {} logged run(s) cannot determine {} free terms ({}); accepted: at least {} "
        "logs, of runs at different g-levels",
        where, logs, spec.free_terms.size(), fmt::join(spec.free_terms, ", "), spec.free_terms.size()));
}

LogReduction reduce_logs(const Config& config, const std::vector<std::pair<std::size_t, CsvTable>>& logs,
                         const RunLogOptions& options, ModelMode mode) {
  const Experiment ex = config.experiment();
  check_log_count(config.identification, logs.size(), "logs");  // before reading any log: the cheaper mistake
  std::map<std::size_t, LoggedRun> by_run;  // plan order
  for (const auto& [index, table] : logs) {
    if (index >= config.plan.runs.size())
      throw InputError(fmt::format("{}: run index {} is outside the plan's {} runs", table.source, index,
                                   config.plan.runs.size()));
    if (by_run.count(index))
      throw InputError(fmt::format("{}: run '{}' is logged twice; accepted: one log per run", table.source,
                                   config.plan.runs[index].name));
    LoggedRun lr;
    lr.index = index;
    const Run& planned = config.plan.runs[index];
    lr.planned_rate = nominal_rate(planned, ex.geometry, ex.site);
    lr.log = reduce_run_log(table, options, lr.planned_rate);
    if (lr.log.has_theta1)
      check_encoder_rate(table.source, planned.name, "main-axis (theta1)", lr.log.theta1_rate, lr.planned_rate,
                         lr.planned_rate);
    if (lr.log.has_gamma)
      check_encoder_rate(table.source, planned.name, "platform (gamma)", lr.log.gamma_rate,
                         planned.mode == PlatformMode::counter_rotating ? -lr.planned_rate : 0.0,
                         lr.planned_rate);
    lr.measured = measured_run(planned, lr.log, ex.geometry, ex.site);
    lr.rate = nominal_rate(lr.measured, ex.geometry, ex.site);
    lr.mismatch = measured_platform_mismatch(planned, lr.log);
    by_run.emplace(index, std::move(lr));
  }
  const IdentificationSpec& spec = config.identification;
  check_log_count(spec, by_run.size(), "logs");

  // The model of each run as measured: its own rate and phases, so the speed error is in the rate (Δω = 0 in
  // the model) and a measured platform mismatch replaces the configured one.
  LogReduction r;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  Observations<double>& obs = r.observations;
  for (auto& [index, lr] : by_run) {
    Eigen::VectorXd known = spec.compensate ? config.centrifuge.errors : zero;
    if (lr.log.has_theta1) known[domega] = 0.0;
    if (lr.log.has_theta1 && lr.log.has_gamma) known[dOmega] = lr.mismatch;
    if (!lr.log.has_gamma) lr.mismatch = known[dOmega];
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

}  // namespace ccal
