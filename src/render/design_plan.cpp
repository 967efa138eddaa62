// The designed plan as configuration text (render/design.hpp).
#include <fmt/format.h>

#include <numbers>
#include <sstream>

#include "ccal/core/units.hpp"
#include "ccal/render/design.hpp"

namespace ccal::render {

namespace {

// A value as the operator reads it: the fewest decimals (up to 9) in `unit` that read back as the same double,
// else all 17 digits in the SI unit (a plan not rounded to the machine's resolution still reads back exactly).
std::string setting(double si, const char* unit, double unit_si, const char* si_unit) {
  for (int decimals = 0; decimals <= 9; ++decimals) {
    const std::string text = fmt::format("{:.{}f} {}", si / unit_si, decimals, unit);
    if (parse_quantity(text).value_si == si) return text;
  }
  return fmt::format("{:.17g} {}", si, si_unit);
}

}  // namespace

std::string plan_toml(const Config& config) {
  constexpr double kDegree = std::numbers::pi / 180;
  std::string out =
      "# --- The test plan (designed by `ccal design`, docs/model.md §15) ------------------------------------\n"
      "# Rounded to what the machine sets ([design] g_resolution, duration_resolution, angle_resolution): each\n"
      "# value reads back exactly as the plan that was scored.\n"
      "[plan]\n";
  for (const Run& run : config.plan.runs) {
    out += fmt::format("\n[[plan.runs]]\nname = \"{}\"\n", run.name);
    out += fmt::format("g_level = \"{}\"\n", setting(run.g_level, "g", 1, "g"));
    out += fmt::format("duration = \"{}\"\n", setting(run.duration, "s", 1, "s"));
    out += fmt::format("platform = \"{}\"\n", platform_mode_name(run.mode));
    if (run.terminal_phase)
      out += fmt::format("terminal_phase = \"{}\"\n", setting(*run.terminal_phase, "deg", kDegree, "rad"));
    else
      out += fmt::format("initial_phase = \"{}\"\n", setting(run.initial_phase.value_or(0.0), "deg", kDegree, "rad"));
    out += fmt::format("arm_azimuth = \"{}\"\n", setting(run.arm_azimuth, "deg", kDegree, "rad"));
    out += fmt::format("mounting = \"{}\"\n", mounting_name(run.mounting));
  }
  return out;
}

namespace {

// The table a line opens, if it is a table header: "plan" for [plan], "plan.runs" for [[plan.runs]].
std::string header_of(const std::string& line) {
  std::size_t i = line.find_first_not_of(" \t");
  if (i == std::string::npos || line[i] != '[') return {};
  const bool array = line.compare(i, 2, "[[") == 0;
  const std::size_t open = i + (array ? 2 : 1);
  const std::size_t close = line.find(array ? "]]" : "]", open);
  if (close == std::string::npos) return {};
  std::string name = line.substr(open, close - open);
  name.erase(0, name.find_first_not_of(" \t"));
  name.erase(name.find_last_not_of(" \t") + 1);
  return name;
}

// A top-level line `setup = …` (a job's set-up file).
bool setup_key(const std::string& line) {
  const std::size_t first = line.find_first_not_of(" \t");
  if (first == std::string::npos || line.compare(first, 5, "setup") != 0) return false;
  const std::size_t next = line.find_first_not_of(" \t", first + 5);
  return next != std::string::npos && line[next] == '=';
}

bool is_plan(const std::string& table) { return table == "plan" || table.rfind("plan.", 0) == 0; }

}  // namespace

std::string config_with_plan(std::string_view original, const Config& config, std::string_view setup_path) {
  std::istringstream in{std::string(original)};
  std::string line, out;
  bool in_plan = false, written = false, top = true;
  std::string pending;  // comment lines just before a table header travel with that table
  while (std::getline(in, line)) {
    const std::string table = header_of(line);
    if (!table.empty()) top = false;
    if (top && !setup_path.empty() && setup_key(line)) {
      std::string quoted;
      for (char c : setup_path) quoted += c == '\\' || c == '"' ? std::string{'\\', c} : std::string(1, c);
      out += pending + fmt::format("setup = \"{}\"  # the set-up, from this file's folder\n", quoted);
      pending.clear();
      continue;
    }
    if (!table.empty()) {
      if (is_plan(table)) {
        in_plan = true;
        pending.clear();
        if (!written) {
          out += plan_toml(config);
          written = true;
        }
        continue;
      }
      in_plan = false;
      out += pending;
      pending.clear();
    }
    if (in_plan) continue;
    const std::size_t first = line.find_first_not_of(" \t");
    if (first != std::string::npos && line[first] == '#') {
      pending.append(line).push_back('\n');
      continue;
    }
    out.append(pending).append(line).push_back('\n');
    pending.clear();
  }
  if (!in_plan) out.append(pending);
  if (!written) out.append("\n").append(plan_toml(config));
  return out;
}

}  // namespace ccal::render
