#pragma once
// Propagation of distributions by a Monte Carlo method, JCGM 101:2008 (GUM Supplement 1), for the error
// budget: every tolerance is a random source, a trial evaluates the model (e.g. simulate the test plan and
// identify the coefficients) at one draw of all sources, and the M trial outputs give the estimate, the
// standard uncertainty, coverage intervals and the output covariance, optionally with the adaptive choice of
// M (§7.9) and the validation of the law of propagation of uncertainty (LPU, §8).
//
// Sampling (JCGM 101 §6.4, §7.3). Every source is drawn by the inverse of its distribution function F at a
// uniform u in (0, 1), x = bound · F⁻¹(u), with the tolerance's bound:
//     normal      x = bound · Φ⁻¹(u)                                                  σ = bound
//     uniform     x = bound · (2u − 1)                                                σ = bound/√3
//     triangular  x = bound · (√(2u) − 1) for u < ½, else bound · (1 − √(2(1 − u)))   σ = bound/√6
//     arcsine     x = bound · sin(π(u − ½)) = −bound · cos(πu)                        σ = bound/√2
// (the arcsine law is that of a sinusoid of amplitude bound at a uniformly distributed phase, written here
// through its monotone inverse distribution function).
// Correlation groups: all sources with the same non-empty Tolerance::group share ONE uniform u per trial, and
// each member is its own bound · F⁻¹(u) for its own distribution. Every F⁻¹ is increasing, so the members are
// fully rank-correlated (Spearman ρ = 1) with the same sign: one member at its upper tail puts every other
// member at its upper tail. Members of one distribution type are exactly proportional (Pearson r = 1);
// members of different types have a Pearson correlation slightly below 1 (e.g. 0.98 between a normal and a
// uniform member), which the LPU's r = 1 slightly overstates.
// Partly correlated sources ([[correlations]]): a Gaussian copula over the same slots (gaussian_copula.hpp).
// Trial i draws one standard normal per slot, Φ⁻¹ of its uniform (as a normal source's), the slots' scores
// y = L z, and each source bound · G_D(y_slot): its own distribution, with each configured Pearson r between
// the pairs.
//
// Random numbers and determinism. Trial i (0-based, counted over all stages) has its own generator:
// xoshiro256** (D. Blackman, S. Vigna, "Scrambled linear pseudorandom number generators", ACM TOMS 47(4),
// 2021) whose 256-bit state is words 4i+1 … 4i+4 of the SplitMix64 sequence (G. L. Steele, D. Lea, C. H.
// Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014) started from the mixed seed. A
// trial's draws therefore depend only on (seed, i); trial outputs are stored by i, and every statistic is
// computed in a fixed order from the stored values, so a seed gives bit-identical results for any number of
// threads, and an adaptive run of h stages equals a fixed run of h·M trials. Uniforms are u = (k + ½)·2⁻⁵²
// with k the top 52 bits of a word: never 0 or 1, and 1 − u is on the same grid, so every F⁻¹ above is
// exactly odd about u = ½ (the normal's tails are cut at Φ⁻¹(2⁻⁵³) ≈ ±8.2σ).
//
// Statistics of each output from its M values (§7.5–7.7), with y_(1) ≤ … ≤ y_(M) the sorted values:
//     y = (1/M) Σ y_r,  u²(y) = 1/(M − 1) Σ (y_r − y)²  (§7.6); the covariance likewise (JCGM 102:2011);
//     q = pM if pM is an integer, else ⌊pM + ½⌋ (at most M − 1); the 100p % intervals are [y_(r), y_(r+q)]:
//       probabilistically symmetric: r = (M − q)/2 if that is an integer, else ⌊(M − q + 1)/2⌋ (§7.7.2);
//       shortest: the r in 1 … M − q with the least y_(r+q) − y_(r) (the first one on ties).
// Sums are compensated (Neumaier), so they stay accurate at M = 10⁸.
//
// Adaptive procedure (§7.9.4), options.digits = n_dig > 0: stages of M = max(trials, J, 10⁴)
// trials, J = ⌈100/(1 − p)⌉. After each stage h ≥ 2, for every output, the standard deviations s of the
// average over stages of the stage values y⁽ʳ⁾, u(y⁽ʳ⁾), y_low⁽ʳ⁾, y_high⁽ʳ⁾ (symmetric interval) are
// compared with the numerical tolerance δ of u(y) from all h·M values (§7.9.2: u(y) = c·10ˡ with c an
// integer of n_dig digits, δ = ½·10ˡ); the procedure stops when 2s ≤ δ for all four and every output, or
// (converged = false) when another stage would exceed max_trials. The final results use all h·M values.
//
// Validation of the LPU (§8): given u_c per output, U_p = k·u_c with k = Φ⁻¹((1 + p)/2) (1.960 for 95 %),
// y the LPU estimate: the model at the sources' expectations (all draws zero, every distribution above is
// centred on zero), evaluated once by run_monte_carlo. d_low = |y − U_p − y_low|, d_high = |y + U_p − y_high|
// against the symmetric MC interval; validated iff both ≤ δ, the numerical tolerance (§7.9.2) of the LPU's
// u_c with n_dig significant digits (options.digits, or 2 when the run is not adaptive).
//
// Histograms: per output, histogram_bins equal bins from its smallest to its largest value (the counts sum to
// M). Sampling error of an interval end y_(r): distribution-free, from the order statistics around it
// (sample_statistics.hpp), reported with the validation so that a failed one says whether M explains it.
//
// Memory: the trial outputs are kept for the quantiles, 8·M·n_outputs bytes (M counted over all stages; the
// intervals read only the 2(M − q + 1) ≈ 2(1 − p)M extreme order statistics of each output, but keeping every
// value lets adaptive stages merge exactly and every sum run in a fixed order; the buffers grow geometrically
// from stage to stage, so up to about twice that), plus O(n_outputs²) for the covariance, O(n_sources +
// n_outputs) per thread, and in the adaptive procedure a partly sorted copy of one stage's values per thread
// (8·stage size bytes each). Only the tails of the values that the intervals read are sorted (the (1 − p)M
// lowest and highest), in place, after the covariance. keep_samples copies the values in trial order before
// that sort: 8·M·n_outputs bytes more (24 MB for 10⁶ trials of 3 outputs); a file of them is written from
// that copy in blocks (render/montecarlo_samples.hpp), so the file's text is never all in memory.
//
// Threads: an OpenMP parallel loop over the trials of a stage, each thread with its own draw and output
// buffers and its own copy of the TrialFunction, made before the loop (nothing is allocated by the engine
// inside it). A trial may so keep scratch buffers in its state; what its copies share they must only read.
// An exception thrown by a trial stops the run and is rethrown.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/core/progress.hpp"
#include "ccal/reduction/observe.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/propagation_options.hpp"
#include "ccal/uncertainty/rate_noise.hpp"

namespace ccal {

// Throws OptionError of `what` (e.g. "threads") unless the system can start that many threads now (they are
// started and ended to find out: the OpenMP runtime would end the process, exit code 1, on a thread it cannot
// create). The range, 0 or 1 … kMaxThreads, is the threads row's (option_rows.hpp), checked with the table.
void check_thread_count(int threads, const char* what);

// Throws InputError naming the source unless every bound is finite and ≥ 0.
void check_source_bounds(const std::vector<Tolerance>& sources);

// The least M for which the coverage interval of probability p exists: q = round(pM) of §7.7.2 must leave at
// least one of the M sorted values out (q ≤ M − 1), about M = 1/(2(1 − p)). InputError unless 0 < p < 1.
std::uint64_t least_trials_for_coverage(double p);

// Throws OptionError of coverage_probability, naming the option of the trials (trials_field) too and what each
// would need, when `trials` values cannot give the coverage interval of probability p (trials <
// least_trials_for_coverage(p)).
void check_coverage_interval(std::uint64_t trials, double p, std::string_view trials_field = "trials");

// The distribution of one output's M values in equal bins.
struct SampleHistogram {
  double lowest = 0;                  // the smallest value: the first bin's lower edge
  double highest = 0;                 // the largest value: the last bin's upper edge (closed)
  std::vector<std::uint64_t> counts;  // they sum to M
  double bin_width() const { return counts.empty() ? 0.0 : (highest - lowest) / double(counts.size()); }
};

// One trial: given the drawn source values (SI, one per tolerance, in tolerance order), write the outputs
// (every element; non-finite outputs stop the run). The engine calls one copy per thread: a mutable lambda
// may hold scratch buffers; state shared between copies (e.g. through a shared_ptr) must be read-only.
using TrialFunction = std::function<void(std::span<const double> draws, std::span<double> outputs)>;

struct OutputSummary {
  std::string name;
  double mean = 0;           // y, average of the M values
  double std_dev = 0;        // u(y)
  double low_symmetric = 0;  // probabilistically symmetric 100p % interval (§7.7.2)
  double high_symmetric = 0;
  double low_shortest = 0;  // shortest 100p % interval (§7.7.2)
  double high_shortest = 0;
  double estimate = 0;  // the model at the sources' expectations (all draws zero): the LPU estimate

  // Adaptive procedure (§7.9.4; all zero for a fixed M): numerical tolerance of u(y) with n_dig digits and
  // the standard deviations of the average over stages of y, u(y), y_low, y_high (converged when 2s ≤ delta).
  double delta = 0;
  double s_mean = 0;
  double s_std_dev = 0;
  double s_low = 0;
  double s_high = 0;

  // Validation of the LPU (§8), when u_c was given (has_lpu); d_low, d_high and validation_delta otherwise 0.
  bool has_lpu = false;
  double lpu_std = 0;           // u_c
  double lpu_expanded = 0;      // U_p = k·u_c
  double validation_delta = 0;  // δ of u_c with n_dig digits
  double d_low = 0;             // |estimate − U_p − low_symmetric|
  double d_high = 0;            // |estimate + U_p − high_symmetric|
  bool validated = false;       // d_low ≤ δ and d_high ≤ δ

  // Sampling error of the symmetric interval's ends, distribution-free (the larger of the two): what a
  // failed validation must exceed before it says more about the LPU than about M (validation_diagnosis).
  double interval_end_std_error = 0;
  SampleHistogram histogram;
};

// Why a validation failed (JCGM 101 §8 at a fixed M): whether the excess of d = max(d_low, d_high) over δ
// is within 3 standard errors of the interval ends (then more trials may well validate it), and the M at
// which that standard error would be a third of δ (the sampling error no longer decides the verdict).
struct ValidationDiagnosis {
  bool validated = false;
  double excess = 0;                // max(d_low, d_high) − δ, ≤ 0 when validated
  double excess_in_std_errors = 0;  // excess / interval_end_std_error
  bool explained_by_sampling = false;
  std::uint64_t trials_needed = 0;  // M·(3·std_error/δ)², rounded up to 2 significant digits
};
ValidationDiagnosis validation_diagnosis(const OutputSummary& summary, std::uint64_t trials);

struct MonteCarloDetail {
  std::uint64_t trials = 0;        // M, over all stages
  std::uint64_t stage_trials = 0;  // trials per stage (= trials for a fixed M)
  int stages = 0;
  bool adaptive = false;
  // Adaptive: the §7.9.4 criterion was met within max_trials. Fixed M: true (M was prescribed; nothing was
  // checked, see notes).
  bool converged = false;
  std::uint64_t seed = 0;
  int threads = 1;                    // threads used
  double coverage_probability = kDefaultCoverageProbability;  // p
  double coverage_factor = 0;         // k = Φ⁻¹((1 + p)/2) for the LPU interval
  int digits = 0;                     // n_dig used for δ (adaptive and validation)
  std::uint64_t interval_points = 0;  // q: the intervals span y_(r) … y_(r+q)
  std::uint64_t sample_bytes = 0;     // memory of the stored outputs, 8·M·n_outputs
  double seconds = 0;                 // wall time of the whole run
  std::vector<OutputSummary> outputs;
  Eigen::MatrixXd covariance;   // of the output vector, 1/(M − 1)
  Eigen::MatrixXd correlation;  // covariance scaled to unit diagonal (0 where an output does not vary)
  Eigen::MatrixXd samples;  // options.keep_samples: row i = trial i's outputs (M × n_outputs), else empty
  std::string notes;        // how the results were obtained, one statement a line, for a report
};

// Runs the Monte Carlo propagation. sources: the random inputs (Tolerance::parameter is not used here, only
// bound, distribution and group); output_names: n_outputs names, or empty for "y1", "y2", …; lpu_std: u_c per
// output for the §8 validation, or null. Throws InputError for invalid options or sources, or when a trial
// gives a non-finite output; rethrows an exception thrown by the trial function.
// correlations: pairs of source ids with their Pearson r ([[correlations]]), drawn through a Gaussian copula
// that keeps every source's distribution (gaussian_copula.hpp); InputError where it cannot.
MonteCarloDetail run_monte_carlo(const std::vector<Tolerance>& sources,
                                 const std::vector<Correlation>& correlations, int n_outputs,
                                 std::vector<std::string> output_names, const TrialFunction& trial,
                                 const PropagationOptions& options, const Eigen::VectorXd* lpu_std = nullptr);
inline MonteCarloDetail run_monte_carlo(const std::vector<Tolerance>& sources, int n_outputs,
                                        std::vector<std::string> output_names, const TrialFunction& trial,
                                        const PropagationOptions& options,
                                        const Eigen::VectorXd* lpu_std = nullptr) {
  return run_monte_carlo(sources, {}, n_outputs, std::move(output_names), trial, options, lpu_std);
}

// The draws of one trial (SI, one per source, in the sources' order) exactly as run_monte_carlo with this seed
// draws its trial `trial` (0-based): one machine drawn from the stated knowledge, every source from its
// distribution, groups as one draw and correlations through the copula (`ccal simulate --draw-truth`, the
// coverage study). Throws as run_monte_carlo for sources or correlations it refuses.
std::vector<double> draw_sources(const std::vector<Tolerance>& sources,
                                 const std::vector<Correlation>& correlations, std::uint64_t seed,
                                 std::uint64_t trial = 0);

// The pieces of the statistics (§7.7.2, §7.9.2), for reports and checks:
// q for M values and coverage probability p (at most M − 1);
std::uint64_t coverage_points(std::uint64_t M, double p);
// the probabilistically symmetric and the shortest 100p % intervals of values sorted in ascending order
// (at least 2 of them);
std::pair<double, double> symmetric_coverage_interval(std::span<const double> sorted, double p);
std::pair<double, double> shortest_coverage_interval(std::span<const double> sorted, double p);
// the numerical tolerance δ = ½·10ˡ of a value u = c·10ˡ with c an integer of n_dig digits (0 for u = 0).
double numerical_tolerance(double u, int n_dig);

// The law of propagation of uncertainty (JCGM 100 §5) for the same model: sensitivities by central
// differences, c_ij = (f_i(+h e_j) − f_i(−h e_j))/2h with h = step_fraction·u(x_j) about the expectations
// (zero draws). Sources of one group are fully correlated (r = 1): their contributions c_ij u_j add linearly;
// with correlations (pairs of source ids, input_correlation.hpp) the covariance is E R Eᵀ, E_ij = c_ij u_j.
struct LinearPropagation {
  Eigen::VectorXd estimate;         // f(0)
  Eigen::MatrixXd sensitivities;    // n_outputs × n_sources, output per unit of source (SI)
  Eigen::VectorXd std_uncertainty;  // u_c per output
  Eigen::MatrixXd covariance;       // of the outputs
};
LinearPropagation propagate_linear(const std::vector<Tolerance>& sources,
                                   const std::vector<Correlation>& correlations, int n_outputs,
                                   const TrialFunction& trial, double step_fraction = 1e-2);
inline LinearPropagation propagate_linear(const std::vector<Tolerance>& sources, int n_outputs,
                                          const TrialFunction& trial, double step_fraction = 1e-2) {
  return propagate_linear(sources, {}, n_outputs, trial, step_fraction);
}

// The calibration as a Monte Carlo model. A trial adds the drawn errors to the actual errors (the [errors]
// section: Config::centrifuge.errors) of their parameters (Tolerance::parameter), simulates the plan,
// identifies the free terms and returns their deviations (SI, in spec.free_terms order) from the terms
// identified with no error at all. The analyst knows the actual errors only: the model side uses them when
// spec.compensate, zero otherwise; the drawn errors are never known. So the means show the bias of the actual
// errors, the spreads those of the tolerances.
struct CalibrationTrialCache;
class CalibrationModel {
 public:
  // An empty model: calibration_trial refuses it. Only calibration_model builds a usable one.
  CalibrationModel() = default;

  const Experiment& experiment() const;
  const IdentificationSpec& spec() const;
  const Eigen::VectorXd& actual_errors() const;  // indexed by experiment().layout
  const std::vector<int>& parameters() const;    // the layout index of each source
  ModelMode mode() const;
  const Eigen::VectorXd& reference() const;  // the free terms identified with zero errors (SI)
  // Quadrature for the trials. A trial needs the run means to ~1e-12 of the output's swing (the coefficient
  // spread is ~1e-3 of it), not to round-off: M covers the harmonics that carry first-order error terms,
  // 2(degree + N) + 2 (the ε² harmonics beyond it alias at ~1e-10 of ε-sized terms), and two slow nodes
  // for |ΔΩ|T ≤ 1e-3 (more beyond): the drift-dependent part of a run is either the heading-dependent,
  // error-sized part or an oscillatory harmonic reduced by 1/(mΩT) after integration, so linear interpolation
  // in time errs by < 1e-12 of the swing for 3σ draws of the bundled tolerances (tests/reduction/run_average_test.cpp).
  const ReductionOptions& reduction() const;
  // What every trial shares, computed once from the fields above (the analyst's H⁺ and known part, the
  // truth's run-mean kernel). Its type is internal to the library (src/uncertainty/calibration_cache.hpp);
  // the fields are read-only so that it always matches them.
  const CalibrationTrialCache& trial_cache() const;

  std::vector<std::string> output_names() const { return spec().free_terms; }
  int n_outputs() const { return int(spec().free_terms.size()); }
  bool empty() const { return !state_; }

 private:
  struct State;  // defined with calibration_model (src/uncertainty/calibration_model.cpp)
  friend CalibrationModel calibration_model(const Experiment&, const IdentificationSpec&,
                                            const std::vector<Tolerance>&, const Eigen::VectorXd&, ModelMode);
  const State& state() const;
  std::shared_ptr<const State> state_;  // shared by copies and by the trial functions: never changed
};
// Checks that every source names a parameter of the layout, a run's rate noise or an input of the measuring
// chain (InputError otherwise) and identifies the
// reference.
CalibrationModel calibration_model(const Experiment& experiment, const IdentificationSpec& spec,
                                   const std::vector<Tolerance>& sources,
                                   const Eigen::VectorXd& actual_errors, ModelMode mode = ModelMode::exact);
// The Monte Carlo's sources of a configuration: its tolerances, then the drives' rate noise as per-run
// sources (rate_noise.hpp).
inline std::vector<Tolerance> monte_carlo_sources(const Config& cfg) {
  std::vector<Tolerance> sources = cfg.tolerances;
  for (Tolerance& t : rate_noise_sources(cfg)) sources.push_back(std::move(t));
  return sources;
}
inline CalibrationModel calibration_model(const Config& cfg, ModelMode mode = ModelMode::exact) {
  return calibration_model(cfg.experiment(), cfg.identification, monte_carlo_sources(cfg),
                           cfg.centrifuge.errors, mode);
}
// The trial function of a model: it shares the model's read-only state and owns its scratch buffers, so it
// must be copied once per thread (as run_monte_carlo does); std::invalid_argument for an empty model.
TrialFunction calibration_trial(const CalibrationModel& model);

}  // namespace ccal
