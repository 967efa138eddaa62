#pragma once
// `ccal reduce` as a library call: recorded run logs (time, pulse count or output, optionally the encoder
// angles) to run means, the model's regressors for the runs as measured (rate, phases, platform mismatch and
// the drives' ripple from the encoders), and the identification of the [identification] terms
// (docs/model.md §13).

#include <optional>
#include <string>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/io/run_log.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/verbs/identification.hpp"
#include "ccal/verbs/statement.hpp"

namespace ccal::verbs {

// The log of one run of the plan.
struct LogFile {
  std::string run;   // the run's name, or its 1-based index as text
  std::string path;  // CSV: time; pulses or output; optionally theta1, gamma
};

struct ReduceOptions {
  std::vector<LogFile> logs;           // at least as many as the identification has free terms
  bool angles_in_degrees = false;      // the encoder columns' unit (else rad)
  std::optional<double> pulse_weight;  // integrated output per pulse [output unit × s]; unset: the quantum
  std::optional<ModelMode> mode;       // model of the regressors; unset: the configuration's
  bool budget = false;                 // also the calibration statement with the configuration's budget
  double coverage_probability = 0.95;  // p of the statement's intervals
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
  std::optional<CalibrationStatement> statement;  // with `budget`
};

// Throws InputError naming the option (--log, --pulse-weight, --budget, --coverage-probability) or CsvError
// naming the log's place.
ReduceResult reduce(const Config& config, const ReduceOptions& options);

// Parameter ids of a drive's ripple channel up to the configuration's order: ripple1_c1, ripple1_s1, …
std::vector<std::string> ripple_ids(const Config& config, std::string_view channel);

}  // namespace ccal::verbs
