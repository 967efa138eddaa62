#pragma once
// The design space of `ccal design` (the configuration's [design] table, docs/config.md; the method in
// docs/model.md §15): which runs a designed test plan may use and what it optimises. Every field is optional;
// an unset field takes the default that keeps the configured plan's choices a lab would not change without
// thinking (its number of runs, total time, g range, platform modes and mountings) and frees the rest
// (durations within a revolution, phases, arm azimuths). All values SI (g-levels in g).

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ccal/model/centrifuge.hpp"
#include "ccal/model/plan.hpp"

namespace ccal {

// What a design minimises (docs/model.md §15.2).
enum class DesignObjective {
  uncertainty,  // Σ w_k (U_k / R_k)² over the chosen coefficients: tolerances (LPU) + noise + rate noise
  d_optimal,    // −ln det(Hᵀ Σ⁻¹ H), Σ the instrument's noise alone (equal variances when it has none)
  a_optimal,    // Σ w_k [(Hᵀ Σ⁻¹ H)⁻¹]_kk / R_k² over the chosen coefficients, noise alone
};

// Every objective's name, in the enumeration's order: what the configuration, the options and the reports
// write.
inline constexpr std::string_view kDesignObjectiveNames[] = {"uncertainty", "d_optimal", "a_optimal"};
constexpr std::string_view design_objective_name(DesignObjective o) noexcept {
  return kDesignObjectiveNames[static_cast<int>(o)];
}

// Which phase of a run the design sets (the other follows from g-level and duration, model.md §6.1).
enum class DesignPhase { terminal, initial };

struct DesignSpace {
  std::optional<int> runs;           // number of runs (default: the plan's)
  // Distinct g-levels the designed plan keeps at least (default: the free terms + 1, so that the residuals can
  // show a term of the instrument's g-dependence the model lacks, a lack of fit; 1: no such constraint).
  std::optional<int> min_g_levels;
  std::optional<double> total_time;  // Σ T_j at most [s] (default: the plan's total)
  std::optional<double> max_g;       // the largest g-level the machine allows [g] (default: the plan's largest)
  std::vector<double> g_levels;      // allowed g-levels [g]; empty: the range below
  std::optional<double> g_min, g_max;  // range [g] (default: the plan's smallest and largest g-level)
  std::optional<double> g_step;        // grid step of the range [g] (default: (g_max − g_min)/25)
  std::vector<double> durations;       // nominal run durations [s] (default: the plan's mean duration)
  // The last revolution of a run is cut at this many equally spaced fractions of a platform turn (each
  // nominal duration becomes whole revolutions plus k/n of one, k = 0 … n−1); 0: durations exactly as given.
  std::optional<int> turn_fractions;  // default 8
  std::optional<DesignPhase> phase;   // default: as the plan's first run sets it
  std::vector<double> phases;         // allowed phases [rad]; empty: a grid of phase_step over a turn
  std::optional<double> phase_step;   // default 30°
  std::vector<double> arm_azimuths;   // allowed arm azimuths θ1(0) [rad]; empty: a grid of azimuth_step
  std::optional<double> azimuth_step;  // default 90°
  std::vector<Mounting> mountings;     // default: the plan's
  std::vector<PlatformMode> platforms;  // default: the plan's
  bool refine = true;                   // refine the continuous variables locally after the grid search
  // What the machine's operator can set: the designed plan is rounded to these (g-level to the nearest, the
  // duration down, phases and arm azimuth to the nearest) and scored as rounded. Defaults: 0.01 g, 1 ms, 0.1°.
  std::optional<double> g_resolution;         // [g]
  std::optional<double> duration_resolution;  // [s]
  std::optional<double> angle_resolution;     // [rad]

  DesignObjective objective = DesignObjective::uncertainty;
  std::vector<std::string> coefficients;   // the coefficients the objective counts (default: every free term)
  std::map<std::string, double> targets;   // coefficient → allowed U (SI): R_k of the objective
  std::map<std::string, double> weights;   // coefficient → w_k (default 1)
  std::optional<int> starts;               // starts of the search (default 6)
  std::optional<unsigned long long> seed;  // seed of the random starts (default 1)
};

}  // namespace ccal
