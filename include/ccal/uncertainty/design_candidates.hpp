#pragma once
// The candidate runs of `ccal design` and their cached rows (docs/model.md §15.1): the configuration's
// [design] table made concrete (defaults from the configured plan), the grid of candidate runs, and for each
// run its regressor row, its sensitivity row and its Type A variances, computed by the code the budget uses
// (observe's model means, output_jacobian of uncertainty/budget.hpp, rate_noise_gain), so that a plan scores
// exactly as the budget would score it.

#include <string>
#include <vector>

#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/design_search.hpp"

namespace ccal {

// The design space with every default resolved (SI; g-levels in g).
struct ResolvedDesignSpace {
  int runs = 0;
  double total_time = 0;  // Σ T ≤ [s]
  double max_g = 0;       // [g]
  std::vector<double> g_levels;
  std::vector<double> durations;  // nominal [s]
  int turn_fractions = 0;
  DesignPhase phase = DesignPhase::terminal;
  std::vector<double> phases, arm_azimuths;  // [rad]
  std::vector<Mounting> mountings;
  std::vector<PlatformMode> platforms;
  Refinement refinement;
  std::vector<std::string> free;   // the variables the search may change (for the report)
  std::vector<std::string> fixed;  // and those it keeps
};

// Resolves config.design against config.plan. Throws InputError naming the [design] key for an empty or
// contradictory space (a g-level above max_g, fewer runs than free terms, runs that cannot fit the total time).
ResolvedDesignSpace resolve_design_space(const Config& config);

// Every combination of the grids: g-level × duration (whole revolutions of each nominal duration less k/n of a
// turn, so never longer than it) × phase × arm azimuth × mounting × platform mode.
std::vector<DesignRun> candidate_runs(const ResolvedDesignSpace& space, const Config& config);

// A plan's run as a design run (its own phase kind kept) and back.
DesignRun design_run(const Run& run);
Run plan_run(const DesignRun& run, std::string name);

// The cached rows of the runs under the configuration (its tolerances, groups, drives' noise, instrument noise,
// identification and mode), in parallel (OpenMP, `threads` ≤ 0: the default). Deterministic.
CandidateRows candidate_rows(const Config& config, const std::vector<DesignRun>& runs, int threads = 0);

}  // namespace ccal
