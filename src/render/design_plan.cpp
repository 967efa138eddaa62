// The designed plan as configuration text (render/design.hpp).
#include <fmt/format.h>

#include <sstream>

#include "ccal/render/design.hpp"

namespace ccal::render {

std::string plan_toml(const Config& config) {
  std::string out =
      "# --- The test plan (designed by `ccal design`, docs/model.md §15) ------------------------------------\n"
      "# Values in g, s and rad with 17 significant digits: they read back exactly as designed.\n"
      "[plan]\n";
  for (const Run& run : config.plan.runs) {
    out += fmt::format("\n[[plan.runs]]\nname = \"{}\"\n", run.name);
    out += fmt::format("g_level = \"{:.17g} g\"\n", run.g_level);
    out += fmt::format("duration = \"{:.17g} s\"\n", run.duration);
    out += fmt::format("platform = \"{}\"\n", platform_mode_name(run.mode));
    if (run.terminal_phase)
      out += fmt::format("terminal_phase = \"{:.17g} rad\"\n", *run.terminal_phase);
    else
      out += fmt::format("initial_phase = \"{:.17g} rad\"\n", run.initial_phase.value_or(0.0));
    out += fmt::format("arm_azimuth = \"{:.17g} rad\"\n", run.arm_azimuth);
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

bool is_plan(const std::string& table) { return table == "plan" || table.rfind("plan.", 0) == 0; }

}  // namespace

std::string config_with_plan(std::string_view original, const Config& config) {
  std::istringstream in{std::string(original)};
  std::string line, out;
  bool in_plan = false, written = false;
  std::string pending;  // comment lines just before a table header travel with that table
  while (std::getline(in, line)) {
    const std::string table = header_of(line);
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
