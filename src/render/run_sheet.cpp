// A run sheet as text (render/run_sheet.hpp).
#include "ccal/render/run_sheet.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "ccal/core/constants.hpp"
#include "ccal/render/table.hpp"

namespace ccal::render {

namespace {

std::string fixed(double value, int decimals) { return fmt::format("{:.{}f}", value, decimals); }

}  // namespace

int decimals_of(double step) {
  for (int d = 0; d < 9; ++d) {
    const double scaled = step * std::pow(10.0, d);
    if (std::round(scaled) >= 1 && std::abs(scaled - std::round(scaled)) < 1e-9 * scaled) return d;
  }
  return 9;
}

std::string text(const RunSheet& sheet, const SettingResolution& resolution) {
  const int g_decimals = decimals_of(resolution.g);
  const int t_decimals = decimals_of(resolution.duration);
  const int a_decimals = decimals_of(resolution.angle * constants::degrees_per_rad);
  // The speed moves by Ω·Δg/(2A) for a g step Δg: one more decimal than that step in rpm shows it.
  Table t({"#", "run", "g-level [g]", "speed [rpm]", "platform", "duration [s]", "turns", "arm az. [deg]",
           "phase start [deg]", "phase stop [deg]", "mounting"});
  std::vector<std::string> mountings;
  bool any_terminal = false, any_initial = false;
  for (const RunSheetLine& l : sheet.lines) {
    const double rpm = l.main_rate / constants::rpm;
    const double rpm_step = rpm * resolution.g / (2 * l.g_level);
    const int rpm_decimals = std::clamp(int(std::ceil(-std::log10(rpm_step))) + 1, 1, 6);
    // A counter-rotating platform turns at −Ω, the speed shown: its control needs no figure of its own.
    const std::string platform = l.mode == PlatformMode::fixed ? "fixed" : "counter";
    // The phase the plan sets is marked "*"; the other follows from it, the speed and the duration.
    t.add_row({std::to_string(l.order), l.run, fixed(l.g_level, g_decimals), fixed(rpm, rpm_decimals),
               platform, fixed(l.duration, t_decimals), fixed(l.turns, 3),
               fixed(l.arm_azimuth * constants::degrees_per_rad, a_decimals),
               fixed(l.start_phase * constants::degrees_per_rad, a_decimals) + (l.terminal_phase ? " " : "*"),
               fixed(l.stop_phase * constants::degrees_per_rad, a_decimals) + (l.terminal_phase ? "*" : " "),
               std::string(mounting_name(l.mounting))});
    (l.terminal_phase ? any_terminal : any_initial) = true;
    const std::string m = fmt::format("{} ({})", mounting_name(l.mounting), mounting_axes(l.mounting));
    if (std::find(mountings.begin(), mountings.end(), m) == mountings.end()) mountings.push_back(m);
  }
  std::string out = t.render();
  out += fmt::format("  total {} s\n", fixed(sheet.total_duration, t_decimals));
  out += wrap_words(
      fmt::format(
          "  Each run, at its speed (the main axis's; a counter-rotating platform turns back at the same "
          "rate), starts its record as the arm passes its azimuth (from East, counter-clockwise) with the "
          "platform at its start phase (the input axis from the outward radial), and ends it after its "
          "duration, the platform then at its stop phase. {}Mounting: {}.",
          any_terminal && any_initial ? "* the phase the plan sets; the other follows from it. "
          : any_terminal              ? "The plan sets the stop phase (*); the start phase follows from it. "
                                      : "The plan sets the start phase (*). ",
          fmt::join(mountings, "; ")),
      110, "  ");
  return out;
}

}  // namespace ccal::render
