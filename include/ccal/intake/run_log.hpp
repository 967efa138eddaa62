#pragma once
// Recorded run logs (`ccal reduce`, docs/cli.md): per run a CSV table of time samples of the instrument's
// output — its cumulative pulse count, or the output itself — and optionally of the main-axis and platform
// encoder angles, reduced to the run's mean output and its measured motion (docs/model.md §13).
//
// Columns (these names by default, or those of RunLogOptions::columns; any order, other columns ignored):
//   time     [s], strictly increasing;
//   pulses   cumulative count of output quanta (a PIGA's pulses), or
//   output   the instrument's output, in its output unit (exactly one of the two);
//   theta1   main-axis encoder angle θ1 (optional), and
//   gamma    platform encoder angle γ (optional), in the log's angle unit, wrapped or not.
// The mean output over the log's span [t_first, t_last] is exact for pulse counts,
//   ⟨output⟩ = (P_last − P_first)·w / T,
// and the trapezoid rule for sampled outputs (spectrally accurate for a periodic output sampled at several
// points per revolution over whole revolutions, second order otherwise). Encoder angles are unwrapped (at
// most half a revolution between samples) and fitted by straight lines plus the harmonics of the drive's rate
// ripple (encoder_fit.hpp): the rate, the phases at the ends and the measured ripple.
//
// A log is reduced in one pass over its rows (from its file: memory independent of its length), and a
// CsvTable in memory through the very same accumulation, so both give the same bits.
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/io/csv_stream.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/model/centrifuge.hpp"
#include "ccal/model/plan.hpp"
#include "ccal/model/site.hpp"
#include "ccal/reduction/observe.hpp"

namespace ccal {

// The names of a log's columns and the unit of its time column: ccal's own layout by default, a data-acquisition
// system's as a log folder's manifest maps it (intake/log_manifest.hpp).
struct LogColumns {
  std::string time = "time";
  std::string pulses = "pulses";
  std::string output = "output";
  std::string theta1 = "theta1";
  std::string gamma = "gamma";
  double time_scale = 1;  // s per unit of the time column
  bool iso_time = false;  // the time column holds ISO 8601 timestamps (intake/iso_time.hpp), read from the first
  // The pulse counter's width: its count wraps at 2^counter_bits (0: a count that does not wrap). The reduction
  // takes each step between samples modulo 2^bits into [−2^(bits−1), 2^(bits−1)).
  int counter_bits = 0;
};

// A wild encoder reading: one that departs from the line through the two samples before it by more than this
// [rad] (or four counts of a coarse encoder) is refused with its file and line (docs/cli.md, `ccal reduce`).
inline constexpr double kEncoderJumpLimit = 0.01;

struct RunLogOptions {
  double pulse_weight = 0;  // integrated output per pulse [output SI · s]; needed for a `pulses` log
  double output_scale = 1;  // SI per unit of the `output` column
  double angle_scale = 1;   // rad per unit of the encoder columns
  double angle_quantum = 0;  // one count of the encoder columns [rad] when they hold counts, else 0
  int harmonic_order = 0;   // N: harmonics of the encoder fits (0: straight lines only)
  LogColumns columns;       // the columns' names and the time unit
  CsvFormat format;         // how the files are written (delimiter, decimal separator, header, units row)
  double angle_offset = 0;  // added to every encoder reading [rad]: half a count for counts rounded down (to
                            // the fitted phases, the same for a line: run_log_reducer.cpp)
  // The longest gap between samples accepted [s] (0: none declared). A gap is a step between samples of more
  // than 1.5 times the shortest before it; a declared gap is bridged by the encoders (docs/cli.md).
  double max_gap = 0;
  // Units the configuration or layout states, as written ("ms", "deg"; a units row is checked against them), or
  // "" where it leaves them to a units row.
  std::string time_unit_stated, angle_unit_stated;
  std::string output_unit;  // the instrument's output unit as configured (for a units row), empty: not checked
};

struct ReducedLog {
  std::string source;
  std::string sha256;  // of the log's bytes as read (the file's; the table's text for a CsvTable)
  std::size_t samples = 0;
  // Gaps: steps between samples of more than 1.5 times the shortest step before them; the time they miss is
  // their length less one shortest step each.
  std::size_t gaps = 0;
  double longest_gap = 0;  // [s], the step between the samples either side
  double missing = 0;      // [s]
  bool pulses = false;     // the output came as a pulse count
  double duration = 0;     // T = t_last − t_first [s]
  double mean_output = 0;  // ⟨output⟩ over the span [output SI]
  // Main-axis encoder (has_theta1): the line θ1(t) = θ1(t_first) + θ̇1 (t − t_first) and its RMS residual.
  bool has_theta1 = false;
  double theta1_rate = 0;   // θ̇1 = Ω + Δω [rad/s]
  double theta1_start = 0;  // [rad], in [0, 2π)
  double theta1_rms = 0;    // [rad]
  // The angle's harmonics Ĉ1, Ŝ1, …, ĈN, ŜN in θ1 [rad] (docs/model.md §13.1; empty: not fitted) and the
  // standard error of one of them [rad].
  std::vector<double> theta1_harmonics;
  double theta1_harmonic_sigma = 0;
  // Platform encoder (has_gamma): the same for γ; γ at both ends of the span.
  bool has_gamma = false;
  double gamma_rate = 0;                // γ̇ [rad/s]
  double gamma_start = 0;               // φ0 of the logged span [rad], in [0, 2π)
  double gamma_end = 0;                 // ψ, the terminal phase [rad], in [0, 2π)
  double gamma_rms = 0;                 // [rad]
  std::vector<double> gamma_harmonics;  // in γ, as theta1_harmonics
  double gamma_harmonic_sigma = 0;
};

// Reduces one log. planned_rate (Ω of the run's plan, rad/s) bounds the sampling interval of the encoders
// (unwrapping needs less than half a revolution between samples). Throws CsvError at the offending cell or
// header (missing or doubled columns, non-increasing time, fewer than two samples, encoder samples too far
// apart, a pulse log without a pulse weight).
ReducedLog reduce_run_log(const CsvTable& table, const RunLogOptions& options, double planned_rate);
// The same, streamed from the file in one pass (CsvError also for a CSV problem or an unreadable file).
ReducedLog reduce_run_log_file(const std::filesystem::path& path, const RunLogOptions& options,
                               double planned_rate);

// A drive's rate ripple (docs/model.md §3.1: c1, s1, …, cN, sN, relative) from its angle's harmonics
// (Ĉ1, Ŝ1, … [rad]): δ(q) = Σ (ck sin kq − sk cos kq)/k = Σ (Ĉk cos kq + Ŝk sin kq) gives ck = k Ŝk,
// sk = −k Ĉk (§13.1); and back.
std::vector<double> ripple_from_angle_harmonics(const std::vector<double>& angle);
std::vector<double> angle_harmonics_from_ripple(const std::vector<double>& ripple);
// The smallest angle ripple [rad] the encoder fits resolve, whatever their noise: below a 2^32-count
// encoder's step (1.5e-9 rad), far above the round-off of angles written with 17 digits (model.md §13.1).
inline constexpr double kRippleResolutionFloor = 1e-10;
// A harmonic resolved by a fit has an amplitude above this many standard errors of one coefficient.
inline constexpr double kRippleSignificance = 10;
// The angle harmonics with each harmonic k whose amplitude hypot(Ĉk, Ŝk) is not resolved (at most
// max(kRippleSignificance·sigma, kRippleResolutionFloor)) set to exactly 0: the drive shows no such ripple,
// and the model of the run keeps the ripple-free motion (and its quadrature) it had before the encoders
// measured it.
std::vector<double> resolved_harmonics(const std::vector<double>& angle, double sigma);

// The main axis's angle error δ1 (its angle harmonics in θ1) as harmonics in γ on a counter-rotating
// platform, θ1 = ψ0 − γ: what a phase-locked platform's angle carries is minus this (§13.2).
std::vector<double> main_angle_error_in_gamma(const std::vector<double>& theta1_angle, double psi0);

// Which control the platform's angle looks like (docs/model.md §13.2), from a log with both encoders'
// harmonics on a counter-rotating platform.
enum class ControlLook { not_tested, undetermined, speed, phase_locked };
std::string_view control_look_name(ControlLook look);
struct ControlEvidence {
  ControlLook look = ControlLook::not_tested;
  double following = 0;      // λ = g·p/|p|²: 1 phase-locked, 0 speed
  double main_in_gamma = 0;  // |p|, the main axis's angle ripple as a phase-locked γ would carry it [rad]
  double threshold = 0;      // |p| below this leaves the mode undetermined [rad]
};
ControlEvidence platform_control_evidence(const ReducedLog& log);

// The planned run as the log measured it: the log's duration; with the main-axis encoder the g-level of the
// measured rate (A = θ̇1² R0 / g) and the arm azimuth θ1(t_first); with the platform encoder the initial phase
// γ(t_first) (the terminal phase is then not used).
Run measured_run(const Run& planned, const ReducedLog& log, const Geometry& geometry, const Site& site);

// The platform rate mismatch the log measured, ΔΩ = −γ̇ − θ̇1 on a counter-rotating platform (0 unless both
// encoders were logged and the platform counter-rotates).
double measured_platform_mismatch(const Run& planned, const ReducedLog& log);

// One logged run of a plan, as reduced and modelled.
struct LoggedRun {
  std::size_t index = 0;  // in the plan
  ReducedLog log;
  Run measured;             // measured_run of the planned run
  double planned_rate = 0;  // Ω of the plan [rad/s]
  double rate = 0;          // Ω of the run as measured [rad/s]
  double mismatch = 0;  // ΔΩ of the model: measured with both encoders, else the configured value [rad/s]
  // The drives' rate ripple of the model (c1, s1, …, cN, sN, relative), measured by the encoder (empty: the
  // configured values, the encoder not logged or its harmonics not fitted).
  std::vector<double> main_ripple, platform_ripple;
  ControlEvidence control;  // the platform's control as the encoders show it
};
struct LogReduction {
  std::vector<LoggedRun> runs;        // in plan order
  Observations<double> observations;  // per logged run: the model's regressors, the log's mean output
};
// Throws OptionError naming `field` (the option that gives the logs), "n logged run(s) cannot determine …",
// when fewer runs are logged than the spec has free terms.
void check_log_count(const IdentificationSpec& spec, std::size_t logs, std::string_view field);

// The observations of logged runs (plan index → log table; each run once): every run is modelled as measured
// (measured_run; with the main-axis encoder Δω = 0 in the model, with both encoders the measured ΔΩ), the
// other error values as in `simulate` ([identification] compensate), with each logged encoder's measured
// ripple replacing the configured ripple of its drive (the fits use the configuration's harmonic order), and
// its output is the log's mean. Throws
// InputError for a run index outside the plan or logged twice, or fewer logs than free terms; CsvError for a
// bad log.
LogReduction reduce_logs(const Config& config, const std::vector<std::pair<std::size_t, CsvTable>>& logs,
                         const RunLogOptions& options, ModelMode mode);
// The same for log files, each streamed in one pass (what `ccal reduce` does).
LogReduction reduce_log_files(const Config& config,
                              const std::vector<std::pair<std::size_t, std::filesystem::path>>& logs,
                              const RunLogOptions& options, ModelMode mode);

}  // namespace ccal
