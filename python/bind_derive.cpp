// Configurations derived from a configuration without editing TOML text: a tolerance, a known error or the
// test plan changed. Each value is read as the configuration file reads it (io/config_file.hpp: a string
// "<number> <unit>" converted to SI with its dimension checked, or a number with unit=), so that a derived
// configuration equals the one read from the correspondingly edited file, and is checked as that file would
// be (tests/python/test_pythonic.py compares their budgets).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"
#include "ccal/io/config_file.hpp"

namespace ccal::python {

namespace {

using Value = std::variant<double, std::string>;

// "<number> <unit>" → SI with the expected dimension; a number needs `unit` unless dimensionless.
double quantity(const Value& value, const std::optional<std::string>& unit, Dimension dim,
                const std::string& what, bool takes_unit = true) {
  std::string text;
  if (const auto* s = std::get_if<std::string>(&value)) {
    if (unit) throw InputError(what + ": give the unit in the string or in unit=, not in both");
    text = *s;
  } else if (unit) {
    text = fmt::format("{:.17g} {}", std::get<double>(value), *unit);
  } else if (dim == kind::dimensionless) {
    text = fmt::format("{:.17g}", std::get<double>(value));
  } else {
    // The example is the number given only where it could be taken (not -1, nan or inf for a bound).
    const double given = std::get<double>(value);
    const double shown = std::isfinite(given) && given > 0 ? given : 1.0;
    throw InputError(
        fmt::format("{}: the bare number {:g} has no unit; accepted: a string with the unit, such as \"{:g} {}\"{}",
                    what, given, shown, dim == kind::angle ? std::string("deg") : si_unit(dim),
                    takes_unit ? ", or unit=\"...\"" : ""));
  }
  try {
    return parse_as(text, dim, "", dim == kind::dimensionless);
  } catch (const UnitError& e) {
    throw InputError(what + ": " + e.what());
  }
}

Dimension parameter_dimension(const ErrorLayout& layout, int index) {
  const std::string_view symbol = unit_symbol(layout.parameter_unit(index));
  return symbol == "1" ? kind::dimensionless : parse_unit(symbol).dim;
}

// Index of an error parameter, with the configuration reader's checks (a ripple has no constant term).
int parameter(const Config& cfg, const std::string& id, const std::string& what) {
  const ErrorLayout& layout = cfg.centrifuge.layout;
  const auto index = layout.find_parameter(id);
  if (!index) {
    const std::optional<std::string> nearest = nearest_name(id, layout.parameter_ids());
    const std::string hint = nearest ? fmt::format("; did you mean '{}'?", *nearest) : "";
    throw InputError(
        fmt::format("{}: '{}' is not an error parameter of this centrifuge (harmonic order {}){}; "
                    "accepted: Config.error_ids",
                    what, id, layout.harmonic_order(), hint));
  }
  const Channel& c = channels()[layout.parameter_channel(*index)];
  if ((c.kind == ErrorKind::main_ripple || c.kind == ErrorKind::platform_ripple) &&
      layout.parameter_harmonic(*index) == 0)
    throw InputError(
        fmt::format("{}: a rate ripple has no constant term; accepted: {}_c<k>, {}_s<k>", what, c.id, c.id));
  return *index;
}

Distribution distribution_named(const std::string& name) {
  for (const Distribution d :
       {Distribution::normal, Distribution::uniform, Distribution::triangular, Distribution::arcsine})
    if (distribution_name(d) == name) return d;
  throw InputError("distribution: '" + name + "'; accepted: 'normal', 'uniform', 'triangular', 'arcsine'");
}

// The unit the bound was written in (kept for display, as the file reader keeps it): unit=, or the text after
// the number; "" when it is not one of the expected dimension.
std::string written_unit(const Value& bound, const std::optional<std::string>& unit, Dimension dim) {
  std::string text = unit.value_or("");
  if (const auto* s = std::get_if<std::string>(&bound)) {
    char* end = nullptr;
    std::strtod(s->c_str(), &end);
    text = end ? end : "";
  }
  text.erase(0, text.find_first_not_of(" \t"));
  text.erase(text.find_last_not_of(" \t") + 1);
  try {
    if (!text.empty() && parse_unit(text).dim == dim) return text;
  } catch (const UnitError&) {
  }
  return "";
}

// A configuration changed in code describes no file: it carries no fingerprint (Config::text_sha256).
Config derived_from(const Config& cfg) {
  Config out = cfg;
  clear_fingerprints(out);
  return out;
}

Config with_tolerance(const Config& cfg, const std::string& id, const Value& bound,
                      const std::optional<std::string>& unit, const std::optional<std::string>& distribution,
                      const std::optional<std::string>& group, const std::optional<double>& cost) {
  Config out = derived_from(cfg);
  const int index = parameter(cfg, id, "with_tolerance");
  auto it = std::find_if(out.tolerances.begin(), out.tolerances.end(),
                         [&](const Tolerance& t) { return t.parameter == index; });
  if (it == out.tolerances.end()) {  // a new source: normal, no group, cost 1, as a new line of the file
    Tolerance t;
    t.parameter = index;
    t.id = cfg.centrifuge.layout.parameter_id(index);
    it = out.tolerances.insert(std::upper_bound(out.tolerances.begin(), out.tolerances.end(), index,
                                                [](int i, const Tolerance& x) { return i < x.parameter; }),
                               std::move(t));
  }
  it->bound =
      quantity(bound, unit, parameter_dimension(cfg.centrifuge.layout, index), "with_tolerance: " + id);
  if (!(it->bound > 0)) throw InputError(fmt::format("with_tolerance: {}: the bound must be positive", id));
  it->unit = written_unit(bound, unit, parameter_dimension(cfg.centrifuge.layout, index));
  if (distribution) it->distribution = distribution_named(*distribution);
  if (group) it->group = *group;
  if (cost) {
    if (!(*cost > 0)) throw InputError(fmt::format("with_tolerance: {}: cost must be > 0", id));
    it->cost = *cost;
  }
  return out;
}

Config without_tolerance(const Config& cfg, const std::string& id) {
  Config out = derived_from(cfg);
  const int index = parameter(cfg, id, "without_tolerance");
  std::erase_if(out.tolerances, [&](const Tolerance& t) { return t.parameter == index; });
  return out;
}

Config with_error(const Config& cfg, const std::string& id, const Value& value,
                  const std::optional<std::string>& unit) {
  Config out = derived_from(cfg);
  const int index = parameter(cfg, id, "with_error");
  out.centrifuge.errors[index] =
      quantity(value, unit, parameter_dimension(cfg.centrifuge.layout, index), "with_error: " + id);
  return out;
}

struct PlanChange {
  std::optional<std::vector<Value>> g;
  std::optional<std::vector<std::string>> names;
  std::optional<Value> duration, initial_phase, terminal_phase, arm_azimuth;
  std::optional<std::string> platform, mounting;
};

// New runs from the g-levels (each a copy of the first run with its level, named "<level>g"), then the
// fields given applied to every run, as [plan] defaults with [[plan.runs]] tables that name only g_level.
// The runs at the given g-levels (each a copy of the plan's first run, named as given or "<g>g").
std::vector<Run> runs_at_levels(const Config& cfg, const PlanChange& c) {
  if (c.g->empty())
    throw InputError("with_plan: g: no runs; accepted: at least one g-level, e.g. [5, 10, 20] or [\"5 g\"]");
  if (c.names && c.names->size() != c.g->size())
    throw InputError(fmt::format("with_plan: names: {} names for {} g-levels", c.names->size(), c.g->size()));
  std::vector<Run> fresh;
  for (std::size_t k = 0; k < c.g->size(); ++k) {
    Run run = cfg.plan.runs.front();
    const Value& level = (*c.g)[k];
    run.g_level = std::holds_alternative<double>(level)
                      ? quantity(level, std::string("g"), kind::acceleration_g, "with_plan: g")
                      : quantity(level, std::nullopt, kind::acceleration_g, "with_plan: g", false);
    if (!(run.g_level > 0) || run.g_level > 1000)
      throw InputError(
          fmt::format("with_plan: g: {:g} g; accepted: a centripetal level in (0, 1000] g", run.g_level));
    run.name = c.names ? (*c.names)[k] : fmt::format("{:g}g", run.g_level);
    fresh.push_back(std::move(run));
  }
  return fresh;
}

// The change to every run: its duration, one of its phases, its arm azimuth, platform and mounting, where
// given.
void change_run(Run& run, const PlanChange& c) {
  if (c.duration) {
    run.duration = quantity(*c.duration, std::nullopt, kind::time, "with_plan: duration", false);
    if (!(run.duration > 0) || run.duration > 1e6)
      throw InputError(fmt::format("with_plan: duration: {:g} s is out of range; accepted: a run duration in "
                                   "(0, 1e6] s",
                                   run.duration));
  }
  if (c.initial_phase) {
    run.initial_phase = quantity(*c.initial_phase, std::nullopt, kind::angle, "with_plan: initial_phase", false);
    run.terminal_phase.reset();
  }
  if (c.terminal_phase) {
    run.terminal_phase = quantity(*c.terminal_phase, std::nullopt, kind::angle, "with_plan: terminal_phase", false);
    run.initial_phase.reset();
  }
  if (c.arm_azimuth)
    run.arm_azimuth = quantity(*c.arm_azimuth, std::nullopt, kind::angle, "with_plan: arm_azimuth", false);
  if (c.platform) {
    if (*c.platform == "counter_rotating")
      run.mode = PlatformMode::counter_rotating;
    else if (*c.platform == "fixed")
      run.mode = PlatformMode::fixed;
    else
      throw InputError("with_plan: platform: '" + *c.platform + "'; accepted: 'counter_rotating', 'fixed'");
  }
  if (c.mounting) {
    bool found = false;
    for (const Mounting m :
         {Mounting::ia_horizontal, Mounting::ia_reversed, Mounting::pa_vertical, Mounting::ia_vertical})
      if (mounting_name(m) == *c.mounting) {
        run.mounting = m;
        found = true;
      }
    if (!found)
      throw InputError("with_plan: mounting: '" + *c.mounting +
                       "'; accepted: 'ia_horizontal', 'ia_reversed', 'pa_vertical', 'ia_vertical'");
  }
}

Config with_plan(const Config& cfg, const PlanChange& c) {
  Config out = derived_from(cfg);
  auto& runs = out.plan.runs;
  if (c.g) {
    runs = runs_at_levels(cfg, c);
  } else if (c.names) {
    if (c.names->size() != runs.size())
      throw InputError(fmt::format("with_plan: names: {} names for {} runs", c.names->size(), runs.size()));
    for (std::size_t k = 0; k < runs.size(); ++k) runs[k].name = (*c.names)[k];
  }
  std::set<std::string> seen;
  for (const Run& run : runs)
    if (run.name.empty() || !seen.insert(run.name).second)
      throw InputError(c.g ? "with_plan: g: the g-level of run '" + run.name +
                                 "' is given twice, and runs are named by it (names unique in the plan); accepted: "
                                 "each g-level once"
                           : "with_plan: names: '" + run.name + "' is empty or given twice; accepted: a name of "
                             "its own for each run");
  if (c.initial_phase && c.terminal_phase)
    throw InputError("with_plan: both initial_phase and terminal_phase are given; accepted: one of them");
  for (Run& run : runs) change_run(run, c);
  return out;
}

}  // namespace

void bind_derive(py::module_& m) {
  auto config = py::reinterpret_borrow<py::class_<Config>>(m.attr("Config"));
  config.def(
      "with_tolerance", &with_tolerance, py::arg("id"), py::arg("bound"), py::arg("unit") = py::none(),
      py::arg("distribution") = py::none(), py::arg("group") = py::none(), py::arg("cost") = py::none(),
      "A copy with the tolerance of error parameter `id` set: bound as in [tolerances] (\"2 arcsec\", or a "
      "number with unit=\"arcsec\"); distribution ('normal', 'uniform', 'triangular', 'arcsine'), "
      "group and cost change only if given (a source without a tolerance gets a normal one, no group, "
      "cost 1).");
  config.def("without_tolerance", &without_tolerance, py::arg("id"),
             "A copy without the tolerance of error parameter `id` (as if its line of [tolerances] were "
             "removed).");
  config.def(
      "with_error", &with_error, py::arg("id"), py::arg("value"), py::arg("unit") = py::none(),
      "A copy with the known (actual) value of error parameter `id` set, as in [errors] (\"2 arcsec\", "
      "or a number with unit=...; 0 removes it).");
  config.def(
      "with_plan",
      [](const Config& cfg, std::optional<std::vector<Value>> g, std::optional<Value> duration,
         std::optional<std::string> platform, std::optional<Value> terminal_phase,
         std::optional<Value> initial_phase, std::optional<Value> arm_azimuth,
         std::optional<std::string> mounting, std::optional<std::vector<std::string>> names) {
        return with_plan(cfg, PlanChange{std::move(g), std::move(names), std::move(duration),
                                         std::move(initial_phase), std::move(terminal_phase),
                                         std::move(arm_azimuth), std::move(platform), std::move(mounting)});
      },
      py::arg("g") = py::none(), py::arg("duration") = py::none(), py::arg("platform") = py::none(),
      py::arg("terminal_phase") = py::none(), py::arg("initial_phase") = py::none(),
      py::arg("arm_azimuth") = py::none(), py::arg("mounting") = py::none(), py::arg("names") = py::none(),
      "A copy with the test plan changed. g: the runs' g-levels (numbers in g, or strings \"12.5 g\"), each "
      "run a copy of the first with that level, named '<level>g' unless names= is given; duration, "
      "terminal_phase or initial_phase, arm_azimuth (strings with units: \"600 s\", \"180 deg\"), platform "
      "('counter_rotating', 'fixed') and mounting: set on every run, as [plan] defaults.");
}

}  // namespace ccal::python
