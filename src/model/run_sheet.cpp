#include "ccal/model/run_sheet.hpp"

#include <numbers>

namespace ccal {

RunSheet run_sheet(const TestPlan& plan, const Geometry& geometry, const Site& site) {
  RunSheet sheet;
  for (const Run& run : plan.runs) {
    RunSheetLine line;
    line.order = int(sheet.lines.size()) + 1;
    line.run = run.name;
    line.g_level = run.g_level;
    line.main_rate = nominal_rate(run, geometry, site);
    line.platform_rate = nominal_platform_rate(run, geometry, site);
    line.duration = run.duration;
    line.turns = line.main_rate * run.duration / (2 * std::numbers::pi);
    line.arm_azimuth = angle_in_turn(run.arm_azimuth);
    line.start_phase = angle_in_turn(initial_phase(run, geometry, site));
    // γ(T) = φ0 + γ̇T (model.md §6.1); a terminal phase the plan sets is shown as set, not as recomputed.
    line.stop_phase = run.terminal_phase
                          ? angle_in_turn(*run.terminal_phase)
                          : angle_in_turn(line.start_phase + line.platform_rate * run.duration);
    line.terminal_phase = run.terminal_phase.has_value();
    line.mounting = run.mounting;
    line.mode = run.mode;
    sheet.total_duration += run.duration;
    sheet.lines.push_back(line);
  }
  return sheet;
}

std::string_view mounting_axes(Mounting mounting) noexcept {
  switch (mounting) {
    case Mounting::ia_horizontal:
      return "IA = x5, PA = y5, OA = z5";
    case Mounting::ia_reversed:
      return "IA = -x5, PA = -y5, OA = z5";
    case Mounting::pa_vertical:
      return "IA = x5, PA = z5, OA = -y5";
    case Mounting::ia_vertical:
      return "IA = z5, PA = x5, OA = y5";
  }
  return "";
}

}  // namespace ccal
