#pragma once
// Recorded run logs (`ccal reduce`, docs/cli.md): per run a CSV table of time samples of the instrument's
// output — its cumulative pulse count, or the output itself — and optionally of the main-axis and platform
// encoder angles, reduced to the run's mean output and its measured motion (docs/model.md §13).
//
// Columns (names fixed, any order, other columns ignored):
//   time     [s], strictly increasing;
//   pulses   cumulative count of output quanta (a PIGA's pulses), or
//   output   the instrument's output, in its output unit (exactly one of the two);
//   theta1   main-axis encoder angle θ1 (optional), and
//   gamma    platform encoder angle γ (optional), in the log's angle unit, wrapped or not.
// The mean output over the log's span [t_first, t_last] is exact for pulse counts,
//   ⟨output⟩ = (P_last − P_first)·w / T,
// and the trapezoid rule for sampled outputs (spectrally accurate for a periodic output sampled at several
// points per revolution over whole revolutions, second order otherwise). Encoder angles are unwrapped (at
// most half a revolution between samples) and fitted by straight lines: the rate and the phases at the ends.
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ccal/centrifuge.hpp"
#include "ccal/config.hpp"
#include "ccal/model_mode.hpp"
#include "ccal/observation_csv.hpp"
#include "ccal/simulate.hpp"
#include "ccal/site.hpp"
#include "ccal/test_plan.hpp"

namespace ccal {

struct RunLogOptions {
  double pulse_weight = 0;  // integrated output per pulse [output SI · s]; needed for a `pulses` log
  double output_scale = 1;  // SI per unit of the `output` column
  double angle_scale = 1;   // rad per unit of the encoder columns
};

struct ReducedLog {
  std::string source;
  std::size_t samples = 0;
  bool pulses = false;     // the output came as a pulse count
  double duration = 0;     // T = t_last − t_first [s]
  double mean_output = 0;  // ⟨output⟩ over the span [output SI]
  // Main-axis encoder (has_theta1): the line θ1(t) = θ1(t_first) + θ̇1 (t − t_first) and its RMS residual.
  bool has_theta1 = false;
  double theta1_rate = 0;   // θ̇1 = Ω + Δω [rad/s]
  double theta1_start = 0;  // [rad], in [0, 2π)
  double theta1_rms = 0;    // [rad]
  // Platform encoder (has_gamma): the same for γ; γ at both ends of the span.
  bool has_gamma = false;
  double gamma_rate = 0;   // γ̇ [rad/s]
  double gamma_start = 0;  // φ0 of the logged span [rad], in [0, 2π)
  double gamma_end = 0;    // ψ, the terminal phase [rad], in [0, 2π)
  double gamma_rms = 0;    // [rad]
};

// Reduces one log. planned_rate (Ω of the run's plan, rad/s) bounds the sampling interval of the encoders
// (unwrapping needs less than half a revolution between samples). Throws CsvError at the offending cell or
// header (missing or doubled columns, non-increasing time, fewer than two samples, encoder samples too far
// apart, a pulse log without a pulse weight).
ReducedLog reduce_run_log(const CsvTable& table, const RunLogOptions& options, double planned_rate);

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
};
struct LogReduction {
  std::vector<LoggedRun> runs;        // in plan order
  Observations<double> observations;  // per logged run: the model's regressors, the log's mean output
};
// Throws InputError "<where>: n logged run(s) cannot determine …" when fewer runs are logged than the spec
// has free terms.
void check_log_count(const IdentificationSpec& spec, std::size_t logs, std::string_view where);

// The observations of logged runs (plan index → log table; each run once): every run is modelled as measured
// (measured_run; with the main-axis encoder Δω = 0 in the model, with both encoders the measured ΔΩ), the
// other error values as in `simulate` ([identification] compensate), and its output is the log's mean. Throws
// InputError for a run index outside the plan or logged twice, or fewer logs than free terms; CsvError for a
// bad log.
LogReduction reduce_logs(const Config& config, const std::vector<std::pair<std::size_t, CsvTable>>& logs,
                         const RunLogOptions& options, ModelMode mode);

}  // namespace ccal
