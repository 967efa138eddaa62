#pragma once
// The candidate runs of `ccal design` and their cached rows (docs/model.md §15.1): the configuration's
// [design] table made concrete (defaults from the configured plan), the grid of candidate runs, and for each
// run its regressor row, its sensitivity row and its Type A variances, computed by the code the budget uses
// (observe's model means, output_jacobian of uncertainty/budget.hpp, rate_noise_gain), so that a plan scores
// exactly as the budget would score it.

#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/design_search.hpp"

namespace ccal {

// The design space with every default resolved (SI; g-levels in g).
struct ResolvedDesignSpace {
  int runs = 0;
  int min_g_levels = 1;   // distinct g-levels a plan keeps at least (default: free terms + 1)
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
// contradictory space (a g-level above max_g, fewer runs than free terms, runs that cannot fit the total time,
// fewer runs or allowed g-levels than min_g_levels).
ResolvedDesignSpace resolve_design_space(const Config& config);

// Every combination of the grids: g-level × duration (whole revolutions of each nominal duration less k/n of a
// turn, so never longer than it) × phase × arm azimuth × mounting × platform mode.
std::vector<DesignRun> candidate_runs(const ResolvedDesignSpace& space, const Config& config);

// A plan's run as a design run (its own phase kind kept) and back.
DesignRun design_run(const Run& run);
Run plan_run(const DesignRun& run, std::string name);

// What the machine's operator can set ([design] g_resolution, duration_resolution, angle_resolution; defaults
// 0.01 g, 1 ms, 0.1°).
struct SettingResolution {
  double g = 0.01;                   // [g]
  // [s]. A run's duration places where the platform stops in its last turn, which the designed plans use to
  // cancel leaks: 0.1 s (1 rad at 10 rad/s) took the bundled example's designed U(K3) (three g-levels) from
  // 0.00045 to 0.0056, 1 ms costs it 0.4 % (a data acquisition window is set to its sample clock, far finer).
  double duration = 0.001;
  double angle = 0.1 * std::numbers::pi / 180;  // [rad]
};
SettingResolution setting_resolution(const DesignSpace& design);

// A run as the operator sets it: the g-level to the nearest step (the step below when that is above max_g), the
// duration down to its step (never longer, so a plan keeps within its total time; at least one step), the phase
// and the arm azimuth to the nearest step in [0°, 360°). Each value is the one its shortest decimal in g, s or
// deg reads back as, so the plan written out (render/design.hpp, plan_toml) is the plan scored.
Run rounded_run(const Run& run, const SettingResolution& resolution, double max_g);

// The cached rows of the runs under the configuration (its tolerances, groups, drives' noise, instrument noise,
// identification and mode), in parallel (OpenMP, `threads` ≤ 0: the default). Deterministic. `on_row` (if set)
// is called once per run done, from any thread, one at a time or concurrently: it must be thread-safe and
// must not throw.
CandidateRows candidate_rows(const Config& config, const std::vector<DesignRun>& runs, int threads = 0,
                             const std::function<void()>& on_row = {});

}  // namespace ccal
