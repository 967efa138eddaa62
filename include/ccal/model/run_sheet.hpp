#pragma once
// A plan as its operator runs it: for each run, in the order it is made, what is set on the machine and what
// the machine should show (docs/cli.md, `ccal design`'s run sheet). Everything is derived from the plan and
// the machine; nothing here is chosen.

#include <string>
#include <string_view>
#include <vector>

#include "ccal/model/plan.hpp"

namespace ccal {

struct RunSheetLine {
  int order = 0;             // 1-based: the order in which the runs are made
  std::string run;           // the run's name, which its log carries
  double g_level = 0;        // A [g]
  double main_rate = 0;      // Ω = √(A g / R0) [rad/s]
  double platform_rate = 0;  // γ̇ [rad/s]: −Ω on a counter-rotating platform, 0 on a fixed one
  double duration = 0;       // T [s], from the start of the run's record to its end
  double turns = 0;          // ΩT / 2π: revolutions of the main axis during the run
  double arm_azimuth =
      0;  // θ1(0) [rad] in [0, 2π): the arm's azimuth from East, counter-clockwise, at the start
  double start_phase = 0;  // φ0 = γ(0) [rad] in [0, 2π): the IA from the outward radial at the start
  double stop_phase = 0;   // γ(T) = φ0 + γ̇T [rad] in [0, 2π): the same at the end
  bool terminal_phase =
      false;  // the plan sets the stop phase (the start phase follows from it), else the start
  Mounting mounting = Mounting::ia_horizontal;
  PlatformMode mode = PlatformMode::counter_rotating;
};

struct RunSheet {
  std::vector<RunSheetLine> lines;
  double total_duration = 0;  // Σ T [s]
};

// The plan's runs in plan order, each with its rates, turns and phases (docs/model.md §6.1).
RunSheet run_sheet(const TestPlan& plan, const Geometry& geometry, const Site& site);

// How a mounting places the instrument's axes in the mounting frame 5, in words: "IA = x5, PA = y5, OA = z5".
std::string_view mounting_axes(Mounting mounting) noexcept;

}  // namespace ccal
