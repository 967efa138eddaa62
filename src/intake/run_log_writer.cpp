// Run logs written from the model (intake/run_log_writer.hpp).
#include "ccal/intake/run_log_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"
#include "ccal/intake/iso_time.hpp"

namespace ccal {

namespace {

constexpr double kTwoPi = 2 * std::numbers::pi;

double wrapped(double a) { return std::fmod(std::fmod(a, kTwoPi) + kTwoPi, kTwoPi); }

// The machine's ripple c1, s1, …, cN, sN of a drive (a channel of the layout).
std::vector<double> ripple_of(const Config& cfg, const Eigen::VectorXd& errors, int channel) {
  const ErrorLayout& layout = cfg.centrifuge.layout;
  std::vector<double> out;
  for (int k = 1; k <= layout.harmonic_order(); ++k)
    for (const bool sine : {false, true}) out.push_back(errors[layout.harmonic_index(channel, k, sine)]);
  return out;
}

// δ(q) = Σ (ck sin kq − sk cos kq)/k (docs/model.md §3.1).
double angle_error(const std::vector<double>& ripple, double q) {
  double d = 0;
  for (std::size_t i = 0; i + 1 < ripple.size(); i += 2) {
    const double k = double(i / 2 + 1);
    d += (ripple[i] * std::sin(k * q) - ripple[i + 1] * std::cos(k * q)) / k;
  }
  return d;
}

// An encoder reading in the layout's unit: in counts the count of the angle, wrapped to one revolution, rounded
// as the layout's count_rounding says (down, or to the nearest); in an angle unit the angle itself.
std::string encoder_text(double angle, const LogLayout& layout) {
  if (layout.angle_unit == "counts") {
    const double counts = angle / layout.angle_scale;
    const auto n = static_cast<long long>(layout.count_rounding == CountRounding::floor ? std::floor(counts)
                                                                                        : std::nearbyint(counts));
    return fmt::format("{}", n % layout.counts_per_revolution);
  }
  return fmt::format("{:.17g}", angle / layout.angle_scale);
}

// The cells of a row (or the header, or the units row) joined as the layout's format writes them: its
// delimiter (one blank for whitespace), its decimal separator.
void append_row(std::string& text, const std::vector<std::string>& cells, const CsvFormat& f, bool numbers) {
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (k > 0) text += f.delimiter;
    if (numbers && f.decimal == ',') {
      for (const char c : cells[k]) text += c == '.' ? ',' : c;
    } else {
      text += cells[k];
    }
  }
  text += '\n';
}

// The origin of a log's timestamps (time_unit = "iso8601"): the reduction reads from the first sample, so any.
constexpr std::int64_t kTimestampOrigin = 1796033700LL * 1000000000;  // 2026-11-30T10:15:00Z

// An encoder's angle error at its joint's angle q: Σ c_k cos kq + s_k sin kq (c1, s1, c2, …).
double encoder_error(const std::vector<double>& terms, double q) {
  double e = 0;
  for (std::size_t i = 0; i + 1 < terms.size(); i += 2) {
    if (terms[i] == 0 && terms[i + 1] == 0) continue;
    const double k = double(i / 2 + 1);
    e += terms[i] * std::cos(k * q) + terms[i + 1] * std::sin(k * q);
  }
  return e;
}

}  // namespace

std::string run_log_file_name(const std::string& run) {
  std::string out = run;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-') c = '_';
  return out + ".csv";
}

double default_log_step(const Config& config) {
  double fastest = 0;
  const Experiment ex = config.experiment();
  for (const Run& run : config.plan.runs)
    fastest = std::max(fastest, nominal_rate(run, ex.geometry, ex.site));
  return std::min(0.1, kTwoPi / 8 / std::max(fastest, 1e-9));  // eight samples a revolution at least
}

namespace {

// How one instrument's output is written: a cumulative count of its quanta w, or its mean in its output unit.
struct OutputWriting {
  double w = 0;     // output SI × s per pulse (0: the output itself)
  double unit = 1;  // SI size of the output unit, without a quantum (a current across a sampling resistor: in V)
  std::string unit_name;
};

OutputWriting output_writing(const InstrumentModel& instrument) {
  OutputWriting o;
  o.w = instrument.quantum;
  o.unit = o.w > 0                             ? 1.0
           : instrument.sampling_resistor > 0 ? 1.0 / instrument.sampling_resistor
                                              : parse_unit(instrument.output_unit).value_si;
  o.unit_name = o.w > 0 ? "counts" : instrument.sampling_resistor > 0 ? "V" : instrument.output_unit;
  return o;
}

// Two runs whose names differ only where a file name has '_' would write one file.
void check_log_file_names(const std::vector<Run>& runs) {
  for (std::size_t a = 0; a < runs.size(); ++a)
    for (std::size_t b = 0; b < a; ++b)
      if (run_log_file_name(runs[a].name) == run_log_file_name(runs[b].name))
        throw InputError(
            fmt::format("run logs: runs '{}' and '{}' would both be logged to {} (a file name keeps "
                        "letters, digits, '.' and '-' and makes anything else '_'); accepted: run "
                        "names that differ in those",
                        runs[b].name, runs[a].name, run_log_file_name(runs[a].name)));
}

// The measuring chain of a simulated machine (config.chain.errors): the clock's τ, and each encoder's angle
// error e(q) = Σ c_k cos kq + s_k sin kq.
struct ChainReadings {
  double tau = 0;
  std::vector<double> encoder1, encoder3;
};

ChainReadings chain_readings(const Config& config) {
  ChainReadings c;
  c.encoder1.assign(std::size_t(2 * config.centrifuge.layout.harmonic_order()), 0.0);
  c.encoder3 = c.encoder1;
  for (const auto& [code, value] : config.chain.errors) {
    const ChainInput in = chain_input(code);
    if (in.kind == ChainKind::time_base) c.tau = value;
    if (in.kind != ChainKind::encoder) continue;
    const EncoderTerm t = encoder_term(in.index);
    std::vector<double>& terms = t.drive == 1 ? c.encoder1 : c.encoder3;
    const auto at = std::size_t(2 * (t.harmonic - 1) + (t.is_sine ? 1 : 0));
    if (at < terms.size()) terms[at] = value;
  }
  return c;
}

// The logs' inputs: one output at least, each with a mean per run of the plan, and errors of the layout.
void check_log_inputs(const Config& config, const Eigen::VectorXd& e,
                      const std::vector<LoggedOutput>& outputs) {
  const auto& runs = config.plan.runs;
  if (outputs.empty()) throw InputError("run logs: no instrument's output to log");
  for (const LoggedOutput& o : outputs)
    if (o.run_means.size() != runs.size())
      throw InputError(
          fmt::format("run logs: {} run means for a plan of {} runs", o.run_means.size(), runs.size()));
  if (e.size() != config.centrifuge.errors.size())
    throw InputError(fmt::format("run logs: {} machine errors for a layout of {}", e.size(),
                                 config.centrifuge.errors.size()));
}

// The sampling step: positive, and at most a quarter revolution of the run (at `rate`, rad/s), so that the
// encoder angles can be unwrapped.
void check_log_step(double step, double rate, const std::string& run) {
  if (!(step > 0) || !std::isfinite(step))
    throw InputError(fmt::format("run logs: step: {:g} s is not a positive time; accepted: a positive step of at "
                                 "most a quarter revolution of every run, e.g. 0.05 s",
                                 step));
  if (rate * step > 0.25 * kTwoPi)
    throw InputError(fmt::format("run logs: step: {:g} s is more than a quarter revolution of run '{}'; accepted: a "
                                 "step of at most {:.3g} s for this run",
                                 step, run, 0.25 * kTwoPi / rate));
}

// The logs' header row and units row: time, each output's column, the two encoders.
std::pair<std::vector<std::string>, std::vector<std::string>> log_header(
    const LogLayout& layout, const std::vector<LoggedOutput>& outputs,
    const std::vector<OutputWriting>& writing) {
  const LogColumns& c = layout.columns;
  std::vector<std::string> header{c.time}, units{layout.time_unit.empty() ? "s" : layout.time_unit};
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    header.push_back(outputs[k].column);
    units.push_back(writing[k].unit_name);
  }
  const std::string angle_unit = layout.angle_unit.empty() ? "rad" : layout.angle_unit;
  header.insert(header.end(), {c.theta1, c.gamma});
  units.insert(units.end(), {angle_unit, angle_unit});
  return {header, units};
}

// An output's cell at time t of a run of mean m: a count of quanta (⌊m (1 + τ) t / w⌋, a clock fast by τ
// accumulating the counts at m (1 + τ) in true time), wrapped to the counter's width, or the mean in the
// output's unit.
std::string output_cell(double m, const OutputWriting& writing, double tau, double t, const LogColumns& c) {
  const double w = writing.w;
  // a count of quanta is read as a rate against the clock
  double value = w > 0 ? std::floor(m * (1 + tau) * t / w) : m / writing.unit;
  if (w > 0 && c.counter_bits > 0)
    value -= std::ldexp(std::floor(std::ldexp(value, -c.counter_bits)), c.counter_bits);
  if (value == 0) value = 0;  // a count of none is "0", never the "-0" of a negative mean's floor at t = 0
  return fmt::format("{:.17g}", value);
}

}  // namespace

std::vector<RunLogFile> write_run_logs(const Config& config, const Eigen::VectorXd& e,
                                       const std::vector<double>& run_means, double step,
                                       const LogLayout& layout) {
  const std::string& column = config.instrument.quantum > 0 ? layout.columns.pulses : layout.columns.output;
  return write_instrument_logs(config, e, {{column, config.instrument, run_means}}, step, layout);
}

std::vector<RunLogFile> write_instrument_logs(const Config& config, const Eigen::VectorXd& e,
                                              const std::vector<LoggedOutput>& outputs, double step,
                                              const LogLayout& layout) {
  const auto& runs = config.plan.runs;
  check_log_inputs(config, e, outputs);
  const Experiment ex = config.experiment();
  const std::vector<double> main = ripple_of(config, e, ch::ripple1),
                            platform = ripple_of(config, e, ch::ripple3);
  const bool locked = config.centrifuge.geometry.platform_control == PlatformControl::phase_locked;
  std::vector<OutputWriting> writing;
  for (const LoggedOutput& o : outputs) writing.push_back(output_writing(o.instrument));
  check_log_file_names(runs);
  // A clock fast by τ stamps t (1 + τ), so the run means (the rate the lab reads, already / (1 + τ)) accumulate
  // their counts at m (1 + τ) in true time.
  const ChainReadings chain = chain_readings(config);
  const double tau = chain.tau;
  const LogColumns& c = layout.columns;
  const CsvFormat& f = layout.format;
  std::vector<RunLogFile> out;
  const auto [header, units] = log_header(layout, outputs, writing);
  std::vector<std::string> row;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const Run& run = runs[r];
    const double rate = nominal_rate(run, ex.geometry, ex.site) + e[ch::domega];
    check_log_step(step, rate, run.name);
    const bool turning = run.mode == PlatformMode::counter_rotating;
    const double gamma_rate = turning ? -(rate + e[ch::dOmega]) : 0.0;
    const double phi0 = initial_phase(run, ex.geometry, ex.site);
    std::string text;
    // A preamble as a DAQ writes one, up to the header.
    const int preamble = std::max(f.skip_lines, f.header_line - 1);
    for (int k = 1; k <= preamble; ++k) text += fmt::format("ccal simulate, run {}: line {} of the preamble\n", run.name, k);
    append_row(text, header, f, false);
    if (f.units_row) append_row(text, units, f, false);
    const auto n = std::int64_t(std::ceil(run.duration / step - 1e-9));
    const double duration = run.duration / (1 + tau);  // the machine's, which the clock reads as the plan's
    for (std::int64_t k = 0; k <= n; ++k) {
      const double t = duration * double(k) / double(n);
      const double theta_n = run.arm_azimuth + rate * t, gamma_n = phi0 + gamma_rate * t;
      const double d1 = angle_error(main, theta_n);
      const double gamma = turning ? gamma_n + angle_error(platform, gamma_n) - (locked ? d1 : 0.0) : phi0;
      const double stamped = t * (1 + tau);  // [s], as the clock reads it
      row.assign(1, c.iso_time ? iso8601_text(kTimestampOrigin + 1000 * std::llround(stamped * 1e6))  // to the µs
                               : fmt::format("{:.17g}", stamped / c.time_scale));
      for (std::size_t j = 0; j < outputs.size(); ++j) {
        row.push_back(output_cell(outputs[j].run_means[r], writing[j], tau, t, c));
      }
      const double theta1 = wrapped(theta_n + d1), gamma_true = wrapped(gamma);
      row.push_back(encoder_text(wrapped(theta1 + encoder_error(chain.encoder1, theta1)), layout));
      row.push_back(encoder_text(wrapped(gamma_true + encoder_error(chain.encoder3, gamma_true)), layout));
      append_row(text, row, f, true);
    }
    out.push_back({run_log_file_name(run.name), std::move(text)});
  }
  return out;
}

}  // namespace ccal
