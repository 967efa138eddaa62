#pragma once
// The options of a propagation of distributions by the Monte Carlo method (montecarlo.hpp), and their table:
// the one home of each option's name, default, range and help. `ccal montecarlo` (verbs/montecarlo.hpp) holds
// a PropagationOptions and lifts these rows into its own table; run_monte_carlo checks the same rows, so the
// engine refuses exactly what the command line and Python refuse.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <type_traits>

#include "ccal/core/options.hpp"
#include "ccal/core/progress.hpp"
#include "ccal/uncertainty/coverage.hpp"
#include "ccal/uncertainty/option_rows.hpp"

namespace ccal {

// The default M of a fixed run: at 10⁴ the interval ends of a normal output scatter by about 2.7·u/√M =
// 0.027 u, as much as the §8 tolerance δ of a two-digit u, so the bundled example's K3 failed its validation
// by sampling noise alone; at 10⁶ they scatter by 0.0027 u. The adaptive procedure's default stage: 10⁴.
inline constexpr std::uint64_t kDefaultMonteCarloTrials = 1000000;
inline constexpr std::uint64_t kDefaultMonteCarloStage = 10000;
inline constexpr std::uint64_t kDefaultMaxTrials = 1000000;

struct PropagationOptions {
  // M; adaptive: the stage size is max(trials, ⌈100/(1 − p)⌉, 10⁴). Unset: kDefaultMonteCarloTrials, or
  // stages of kDefaultMonteCarloStage.
  std::optional<std::uint64_t> trials;
  std::uint64_t seed = 1;
  int threads = 0;  // 0: the OpenMP default
  int digits = 0;   // n_dig > 0: the adaptive procedure of §7.9 with this many significant digits of u(y)
  // Adaptive: no stage is started that would go beyond this. Unset: kDefaultMaxTrials (optional: one given
  // with a fixed M is refused, at its default value too).
  std::optional<std::uint64_t> max_trials;
  // p; unset: kDefaultCoverageProbability (optional: the report refuses a p given beside its stated k)
  std::optional<double> coverage_probability;
  bool progress = false;  // a progress bar (%, trials/s, ETA) on stderr, only if stderr is a terminal
  ProgressCallback
      on_progress;  // called every 0.1 s at most; may throw Cancelled to stop (core/progress.hpp)
  // Keep every trial's outputs in MonteCarloDetail::samples (M × n_outputs, trial order): 8·M·n_outputs bytes
  // more, besides the engine's own copy, which is partly sorted for the intervals.
  bool keep_samples = false;
  // The outputs of trials 0 … k − 1 of an earlier run with the same seed, sources, correlations and trial
  // function (its MonteCarloDetail::samples, kept with keep_samples: k × n_outputs, trial order), taken as they
  // are instead of evaluated again. Trial i depends only on (seed, i), so the result is that of a run without
  // them, bit for bit, at the cost of M − k trials: a run that needs more trials extends the one before it.
  // Fixed M only (trials ≥ k); null: none.
  const Eigen::MatrixXd* earlier_samples = nullptr;
  int histogram_bins = 60;  // bins of each output's histogram over [lowest, highest] value, 1…10⁴
};

// The rows, in the order `ccal montecarlo --help` lists them: what a front end sets (a verb lifts them:
// core/options.hpp lifted_rows). The rest (progress, samples, histogram) are the library's own.
inline constexpr OptionSpec<PropagationOptions> kPropagationRows[] = {
    {"trials", &PropagationOptions::trials, "N",
     "Number of trials M (default 1000000); with digits, the stage size (default and least 10000)",
     rows::kTrials},
    rows::seed(&PropagationOptions::seed, "Seed of the random numbers (same seed, same results)"),
    rows::threads(&PropagationOptions::threads),
    {"digits", &PropagationOptions::digits, "n",
     "0: fixed M; n in 1..6: adaptive M (JCGM 101 §7.9) until n significant digits of u(y) are stable",
     OptionRange::between(1, 6).or_value(0, "fixed M")},
    {"max_trials", &PropagationOptions::max_trials, "N", "Adaptive procedure: no stage beyond this many trials",
     rows::kTrials.unset_means("1000000")},
    rows::coverage_probability(&PropagationOptions::coverage_probability,
                               "Coverage probability p of the intervals, in {range}"),
};

// The options' table (core/options.hpp).
OptionTable<PropagationOptions> options_of(std::type_identity<PropagationOptions>);

// What run_monte_carlo checks before any work: every row's range (OptionError naming the field), the threads
// the system can start (check_thread_count), for a fixed M that M values give the coverage interval's ends
// (check_coverage_interval), and the histogram's bins.
void check_propagation_options(const PropagationOptions& options);

}  // namespace ccal
