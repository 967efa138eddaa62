#pragma once
// `ccal reduce` as a library call: recorded run logs (time, pulse count or output, optionally the encoder
// angles) to run means, the model's regressors for the runs as measured (rate, phases, platform mismatch and
// the drives' ripple from the encoders), and the identification of the [identification] terms
// (docs/model.md §13).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/intake/log_manifest.hpp"
#include "ccal/intake/run_log.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/verbs/identification.hpp"
#include "ccal/verbs/instrument_covariance.hpp"
#include "ccal/verbs/statement.hpp"

namespace ccal::verbs {

// The log of one run of the plan.
struct LogFile {
  std::string run;   // the run's name, or its 1-based index as text
  std::string path;  // CSV: time; pulses or output; optionally theta1, gamma
  // The manifest that names it, and where (its key's line and column): a problem of this log (an unknown run, a
  // run logged twice, one log for two runs) is then located there; empty: an option named it (`logs`).
  std::string manifest = {};
  int line = 0, column = 0;
};
// The logs a folder's manifest names, each located in it.
std::vector<LogFile> manifest_logs(const LogManifest& manifest);

// The unit of the logs' encoder columns.
enum class AngleUnit { rad, deg };
inline constexpr std::string_view kAngleUnitNames[] = {"rad", "deg"};  // in the enumeration's order

// Each logged run's mean is checked against what the configuration's instrument, with its nominal terms,
// reads at that run of the plan: beyond this many standard uncertainties of a run's mean (its noise, the
// drives' rate noise and the tolerances' effect on it) it is a warning, with strict_runs an error. A swapped
// or mislabelled log is thousands of u off; 10 leaves a machine within its tolerances unremarked.
inline constexpr double kRunCheckLimit = 10;

struct ReduceOptions {
  // At least as many as the identification has free terms. Not a row of the table: each front end reads
  // them (the command line: --log RUN=FILE, repeated; Python: a dict of run → file).
  std::vector<LogFile> logs;
  // How the logs' columns read (a log folder's manifest, intake/log_manifest.hpp); default: ccal's own layout.
  // Not a row either: the front ends read it with the logs (the command line: --logs DIR).
  LogLayout layout;
  AngleUnit angle_unit = AngleUnit::rad;  // of the encoder columns, unless the layout states their unit
  std::optional<double> pulse_weight;  // integrated output per pulse [output unit × s]; unset: the quantum
  std::optional<ModelMode> mode;       // model of the regressors; unset: the configuration's
  bool strict_runs = false;  // a run's mean beyond kRunCheckLimit u of the nominal reading: an error, not a warning
  bool statement = false;              // also the calibration statement with the configuration's budget
  // The statement's options (its rows are this table's, but its mode: the statement's budget is in `mode`).
  StatementOptions statement_options;
};

// The options' table (core/options.hpp): names, ranges and help of the fields a front end sets.
OptionTable<ReduceOptions> options_of(std::type_identity<ReduceOptions>);

struct ReduceResult {
  Config config;
  ModelMode mode = ModelMode::exact;
  double output_unit_si = 1;       // SI size of one output unit
  std::vector<std::string> files;  // per logged run, in plan order
  LogReduction logs;
  FileIdentification identification;
  // Runs whose encoders contradict the configured platform control, and weak terms: for the front end to
  // show (the verb prints nothing).
  std::vector<std::string> warnings;
  std::optional<CalibrationStatement> statement;  // with `statement`
  // A test of several instruments (Config::instruments): each instrument's reduction of the same logs through
  // its own output column (LogLayout::instruments), in the configuration's order; this result is then the
  // first's, with the list. With `statement`, the covariance of their coefficients (the machine's errors are one
  // for all: verbs/instrument_covariance.hpp), by the LPU and a Monte Carlo of statement_trials trials.
  std::vector<ReduceResult> instruments;
  std::optional<InstrumentCovariance> covariance;
};

// Throws OptionError naming the field (logs, pulse_weight, statement, coverage_probability) or CsvError
// naming the log's place.
// A configuration of several instruments is reduced instrument by instrument, each through the column the
// layout's [instruments] names for it (InputError naming the manifest when one has none).
ReduceResult reduce(const Config& config, const ReduceOptions& options);
// Refuses, for a configuration of several instruments, the outputs that hold one instrument's table (the
// observations file, the statement's CSV: InputError naming the option); nothing for one instrument.
void check_single_instrument_output(const Config& config, std::string_view field);

// The pulse weight as written on the command line: a bare number in the output unit × s, or a quantity whose
// unit has that dimension ("2.5e-5 deg" for an output in deg/s), as a value of ReduceOptions::pulse_weight.
// Throws OptionError naming pulse_weight for a wrong unit (saying which units are accepted) or a non-number.
double pulse_weight_from_text(const Config& config, std::string_view text);

// How the logs are read (RunLogOptions: SI scales of the output and the angles, the pulse weight) for these
// options. Throws OptionError naming pulse_weight when it is not a positive number.
RunLogOptions run_log_options(const Config& config, const ReduceOptions& options);

// Parameter ids of a drive's ripple channel up to the configuration's order: ripple1_c1, ripple1_s1, …
std::vector<std::string> ripple_ids(const Config& config, std::string_view channel);

}  // namespace ccal::verbs
