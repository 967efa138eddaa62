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

namespace ccal::verbs {

// The trial outputs are stored (8 bytes per trial and coefficient): 10⁹ trials of three coefficients are
// 24 GB, the most accepted.
inline constexpr std::int64_t kMaxMonteCarloTrials = 1000000000;

struct MonteCarloOptions {
  std::optional<ModelMode> mode;  // kinematics; unset: the configuration's [identification] mode
  std::int64_t trials = 10000;    // M (the first stage's, with digits > 0)
  std::uint64_t seed = 1;
  int threads = 0;  // 0: all cores
  int digits = 0;   // 0: fixed M; 1..6: the adaptive procedure (JCGM 101 §7.9) to these digits
  std::int64_t max_trials = 1000000;  // bound of the adaptive procedure
  double coverage = 0.95;             // coverage probability p of the intervals
  bool progress = false;              // draw a progress bar on standard error when it is a terminal
  ProgressCallback on_progress;       // trials done / of the stage, every 0.1 s at most; may throw Cancelled
};

struct MonteCarloResult {
  Config config;
  ccal::BudgetResult budget;  // the LPU that the Monte Carlo validates, and the display units
  ccal::MonteCarloResult monte_carlo;
};

// Throws InputError naming the option (--trials, --max-trials, --threads, --digits, --coverage) for a value
// out of range, for an empty [tolerances] or a plan that cannot identify the terms.
MonteCarloResult monte_carlo(const Config& config, const MonteCarloOptions& options = {});

}  // namespace ccal::verbs
