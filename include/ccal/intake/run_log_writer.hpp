#pragma once
// Run logs as a centrifuge test would record them, written from the model (`ccal simulate --logs-out DIR`):
// what `ccal reduce` reads (intake/run_log.hpp), so that the path from a test's logs to its coefficients can be
// tried, and checked, without a centrifuge. Per run of the plan, sampled every `step` seconds over its
// duration:
//   time     t [s];
//   pulses   the cumulative count ⌊m t / w⌋ of the instrument's quanta w (its `quantum`) for the run mean m
//            (the simulated one, with the instrument's noise), or, for an instrument without a quantum,
//   output   m itself, in the output unit (the run's mean is all a reduction reads of it);
//   theta1   θ1 = θ1ⁿ + δ1(θ1ⁿ), θ1ⁿ = θ1(0) + (Ω + Δω) t, wrapped to [0, 2π);
//   gamma    γ = γⁿ + δ3(γⁿ) [− δ1(θ1ⁿ) phase-locked], γⁿ = φ0 − (Ω + Δω + ΔΩ) t on a counter-rotating
//            platform, φ0 on a fixed one;
// with δ(q) = Σ (ck sin kq − sk cos kq)/k the angle error of a drive's configured rate ripple c1, s1, …
// (docs/model.md §3.1, §13.1) and Δω, ΔΩ those of the machine's errors (the simulation's truth).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "ccal/io/config_file.hpp"
#include "ccal/intake/log_manifest.hpp"

namespace ccal {

struct RunLogFile {
  std::string name;  // file name: the run's name with characters other than letters, digits, '.', '-' as '_'
  std::string text;  // the CSV table
};

// One log per run of config's plan; machine_errors: the errors the simulated machine has (SI, by config's
// layout: SimulateResult::machine_errors); run_means: the runs' mean outputs [output SI], in plan order. step:
// at most a quarter revolution of the fastest run (the reduction unwraps less than 0.75π between samples);
// throws InputError otherwise or for a mean count that does not match the plan.
// layout: the file's format (delimiter, decimal separator, a preamble up to header_line or skip_lines, a units
// row), the columns' names, the time unit (or ISO 8601 timestamps from 2026-11-30T10:15:00Z, to the
// nearest microsecond) and the encoders' unit (intake/log_manifest.hpp; default: ccal's own, seconds and radians); in
// counts each reading is the whole count of the angle by the layout's count_rounding (the count below it, or
// the nearest), wrapped to one revolution.
std::vector<RunLogFile> write_run_logs(const Config& config, const Eigen::VectorXd& machine_errors,
                                       const std::vector<double>& run_means, double step,
                                       const LogLayout& layout = {});

// The output of one instrument in the logs of a test of several ([[instruments]]): its column's name, the
// instrument (its quantum: a count of pulses, else its output unit) and its runs' mean outputs [output SI], in
// plan order. Every instrument's column sits between the time and the encoders, in the order given; the time,
// the encoders and the clock are the machine's (config's), one for all.
struct LoggedOutput {
  std::string column;
  InstrumentModel instrument;
  std::vector<double> run_means;
};
std::vector<RunLogFile> write_instrument_logs(const Config& config, const Eigen::VectorXd& machine_errors,
                                              const std::vector<LoggedOutput>& outputs, double step,
                                              const LogLayout& layout = {});
// The file name of a run's log: its name with characters other than letters, digits, '.', '-' as '_', and ".csv".
std::string run_log_file_name(const std::string& run);

// The default sampling interval: 0.1 s, or an eighth of a revolution of the fastest run if that is shorter.
double default_log_step(const Config& config);

}  // namespace ccal
