#pragma once
// `ccal montecarlo` as a library call: the propagation of the configured tolerances to the identified
// coefficients by the Monte Carlo method of JCGM 101, with the validation of the budget's LPU (§8 of JCGM
// 101, docs/model.md §10.2).

#include <cstdint>
#include <optional>

#include "ccal/core/model_mode.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "ccal/verbs/option_rows.hpp"

namespace ccal::verbs {

// The default M of a fixed run: at 10⁴ the interval ends of a normal output scatter by about 2.7·u/√M =
// 0.027 u, as much as the §8 tolerance δ of a two-digit u, so the bundled example's K3 failed its validation
// by sampling noise alone; at 10⁶ they scatter by 0.0027 u. The adaptive procedure's default stage: 10⁴.
inline constexpr std::int64_t kDefaultMonteCarloTrials = 1000000;
inline constexpr std::int64_t kDefaultMonteCarloStage = 10000;

struct MonteCarloOptions {
  std::optional<ModelMode> mode;  // kinematics; unset: the configuration's [identification] mode
  std::optional<std::int64_t> trials;  // M; with digits > 0 the stage size; unset: the defaults above
  std::uint64_t seed = 1;
  int threads = 0;  // 0: all cores
  int digits = 0;   // 0: fixed M; 1..6: the adaptive procedure (JCGM 101 §7.9) to these digits
  std::int64_t max_trials = 1000000;   // bound of the adaptive procedure
  double coverage_probability = 0.95;  // p of the intervals, in (0, 1) (--coverage-probability)
  bool progress = false;               // draw a progress bar on standard error when it is a terminal
  // Keep every trial's outputs (MonteCarloResult::samples, SI; 8·M bytes per coefficient more), for
  // --samples-out and Python's `samples`.
  bool keep_samples = false;
  ProgressCallback on_progress;  // trials done / of the stage, every 0.1 s at most; may throw Cancelled
};

// The options' table (core/options.hpp): names, ranges and help of the fields a front end sets.
OptionTable<MonteCarloOptions> options_of(std::type_identity<MonteCarloOptions>);

struct MonteCarloResult {
  Config config;
  ccal::BudgetResult budget;  // the LPU that the Monte Carlo validates, and the display units
  ccal::MonteCarloResult monte_carlo;
};

// Throws OptionError naming the field for a value out of range (its table), InputError for an empty
// [tolerances] or a plan that cannot identify the terms.
MonteCarloResult monte_carlo(const Config& config, const MonteCarloOptions& options = {});

}  // namespace ccal::verbs
