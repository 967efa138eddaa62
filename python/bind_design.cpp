// ccal.design: `ccal design` from Python (docs/python.md).
#include "ccal/render/design.hpp"  // before bindings.hpp: bind_verb_result renders the design result
// (keep this order)
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "option_keywords.hpp"
#include "ccal/intake/measured_inputs.hpp"
#include "ccal/verbs/design.hpp"
#include "ccal/verbs/statement.hpp"

namespace ccal::python {
namespace {

// A run by value: name, g_level, duration, platform, initial_phase, terminal_phase, arm_azimuth, mounting.
using RunValues = std::tuple<std::string, double, double, std::string, std::optional<double>, std::optional<double>,
                             double, std::string>;

Run run_of_values(const RunValues& v) {
  Run run;
  run.name = std::get<0>(v);
  run.g_level = std::get<1>(v);
  run.duration = std::get<2>(v);
  const std::string& platform = std::get<3>(v);
  run.mode = platform == platform_mode_name(PlatformMode::fixed) ? PlatformMode::fixed : PlatformMode::counter_rotating;
  run.initial_phase = std::get<4>(v);
  run.terminal_phase = std::get<5>(v);
  run.arm_azimuth = std::get<6>(v);
  for (const Mounting m : {Mounting::ia_horizontal, Mounting::ia_reversed, Mounting::pa_vertical, Mounting::ia_vertical})
    if (mounting_name(m) == std::get<7>(v)) run.mounting = m;
  return run;
}

// The configurations a design makes from the one it is given (verbs/design.cpp), for a Design pickled by value
// (python/ccal/_pickling.py, which checks each against the original's attributes when pickling): the expected
// measured inputs charged when `measured_inputs` (what the design's budgets see); then, when `runs` are given,
// the plan replaced by them and the fingerprints cleared (another plan: no longer the file's), and with
// `to_instruments` each instrument given that plan too.
Config design_config(const Config& cfg, const std::optional<std::vector<RunValues>>& runs, bool measured_inputs,
                     bool to_instruments) {
  Config c = measured_inputs ? verbs::with_measured_inputs(cfg, expected_measured_inputs(cfg)) : cfg;
  if (!runs) return c;
  clear_fingerprints(c);
  c.plan.runs.clear();
  for (const RunValues& v : *runs) c.plan.runs.push_back(run_of_values(v));
  if (to_instruments)
    for (Config& one : c.instruments) {
      one.plan = c.plan;
      clear_fingerprints(one);
    }
  return c;
}

// A plan as its operator runs it.
void bind_run_sheet(py::module_& m) {
  py::class_<RunSheetLine>(m, "RunSheetLine", "One run of a run sheet: what the operator sets and sees.")
      .def_readonly("order", &RunSheetLine::order, "1-based order in which the runs are made [—]")
      .def_readonly("run", &RunSheetLine::run, "the run's name, which its log carries [—]")
      .def_readonly("g_level", &RunSheetLine::g_level, "A [g]")
      .def_readonly("main_rate", &RunSheetLine::main_rate, "the main axis's rate Ω [rad/s]")
      .def_readonly("platform_rate", &RunSheetLine::platform_rate,
                    "the platform's rate: −Ω counter-rotating, 0 fixed [rad/s]")
      .def_readonly("duration", &RunSheetLine::duration, "T [s]")
      .def_readonly("turns", &RunSheetLine::turns, "revolutions of the main axis in T [—]")
      .def_readonly("arm_azimuth", &RunSheetLine::arm_azimuth,
                    "θ1(0): the arm's azimuth from East, counter-clockwise, in [0, 2π) [rad]")
      .def_readonly("start_phase", &RunSheetLine::start_phase, "φ0 = γ(0) in [0, 2π) [rad]")
      .def_readonly("stop_phase", &RunSheetLine::stop_phase, "γ(T) in [0, 2π) [rad]")
      .def_readonly("terminal_phase", &RunSheetLine::terminal_phase,
                    "the plan sets the stop phase (else the start phase) [—]")
      .def_property_readonly(
          "mounting", [](const RunSheetLine& l) { return std::string(mounting_name(l.mounting)); },
          "the mounting's name, e.g. 'ia_horizontal' [—]")
      .def_property_readonly(
          "platform", [](const RunSheetLine& l) { return std::string(platform_mode_name(l.mode)); },
          "'counter_rotating' or 'fixed' [—]");
  py::class_<RunSheet>(m, "RunSheet", "A plan as its operator runs it, run by run in order.")
      .def_readonly("lines", &RunSheet::lines, "the runs in order, list of RunSheetLine [—]")
      .def_readonly("total_duration", &RunSheet::total_duration, "Σ T [s]");
}

// What a Design unpickled by value needs (python/ccal/_pickling.py): its config_text, and its configurations
// made again from the one given.
void bind_design_by_value(py::module_& m) {
  m.def(
      "_config_with_plan",
      [](const std::string& original, const Config& designed) { return render::config_with_plan(original, designed); },
      py::arg("original"), py::arg("designed"),
      "Design.config_text of a Design unpickled by value: `original` with its [plan] replaced by designed's.");
  auto config = py::reinterpret_borrow<py::class_<Config>>(m.attr("Config"));
  config.def("_design_config", &design_config, py::arg("runs"), py::arg("measured_inputs"),
             py::arg("to_instruments"),
             "A configuration the design makes from this one (for a Design pickled by value).");
}

}  // namespace

void bind_design(py::module_& m) {
  py::class_<verbs::DesignTarget>(m, "DesignTarget", "A coefficient of the design's objective.")
      .def_readonly("coefficient", &verbs::DesignTarget::coefficient, "the coefficient's id, e.g. 'K3' [—]")
      .def_readonly("weight", &verbs::DesignTarget::weight, "w_k in the objective (0: not counted) [—]")
      .def_readonly("reference", &verbs::DesignTarget::reference,
                    "R_k: the user's target, or the configured plan's U_k [coefficient SI: output SI per gⁿ]")
      .def_readonly("is_target", &verbs::DesignTarget::is_target,
                    "R_k is a user's target (else the configured plan's U_k) [—]");

  bind_run_sheet(m);

  py::class_<verbs::DesignResult>(
      m, "Design",
      "`ccal design`: the configured and the designed plan with their full budgets; "
      "str() is the CLI's text, to_json() its JSON.",
      py::dynamic_attr())  // the call that made it, for pickling (python/ccal/_pickling.py)
      .def("to_json", [](const verbs::DesignResult& r) { return render::json(r); })
      .def("__str__", [](const verbs::DesignResult& r) { return render::text(r); })
      .def_readonly("config", &verbs::DesignResult::config, "the configuration as given [Config]")
      .def_readonly("designed", &verbs::DesignResult::designed,
                    "the configuration with the designed plan [Config]")
      .def_property_readonly(
          "before",
          [](const verbs::DesignResult& r) -> std::optional<verbs::BudgetResult> {
            if (!r.instruments.empty()) return std::nullopt;
            return r.before;
          },
          "the full budget of the configured plan; None for a test of several instruments, each instrument's "
          "Design has its own [Budget]")
      .def_property_readonly(
          "after",
          [](const verbs::DesignResult& r) -> std::optional<verbs::BudgetResult> {
            if (!r.instruments.empty()) return std::nullopt;
            return r.after;
          },
          "the full budget of the designed plan; None for a test of several instruments, each instrument's "
          "Design has its own [Budget]")
      .def_property_readonly(
          "units", [](const verbs::DesignResult& r) { return r.after.budget.units; },
          "the display unit of each coefficient of the budgets (one instrument; [] for several) [—]")
      .def_property_readonly(
          "display_scale", [](const verbs::DesignResult& r) { return r.after.budget.display_scale; },
          "SI → display unit factor per coefficient of the budgets [display unit per SI]")
      .def_readonly("targets", &verbs::DesignResult::targets,
                    "the objective's coefficients, list of DesignTarget [—]")
      .def_readonly("candidates", &verbs::DesignResult::candidates, "the number of candidate runs cached [—]")
      .def_readonly("candidates_from_cache", &verbs::DesignResult::candidates_from_cache,
                    "whether the candidate runs' rows were read from the cache file [—]")
      .def_readonly("configured_objective", &verbs::DesignResult::configured_objective,
                    "the objective of the configured plan, by the cached rows [—]")
      .def_readonly("designed_objective", &verbs::DesignResult::designed_objective,
                    "the objective of the designed plan [—]")
      .def_readonly(
          "tolerance_before", &verbs::DesignResult::tolerance_before,
          "U_k from the tolerances, configured plan, per coefficient [coefficient SI: output SI per gⁿ]")
      .def_readonly(
          "tolerance_after", &verbs::DesignResult::tolerance_after,
          "U_k from the tolerances, designed plan, per coefficient [coefficient SI: output SI per gⁿ]")
      .def_readonly(
          "sheet", &verbs::DesignResult::sheet,
          "the designed plan as its operator runs it; `after` is its budget if run as written [RunSheet]")
      .def_readonly("mechanism", &verbs::DesignResult::mechanism,
                    "in words: what the designed plan does differently, how much from a stronger signal and "
                    "how much from errors cancelling [—]")
      .def_readonly("instruments", &verbs::DesignResult::instruments,
                    "a test of several instruments: each one's Design of the one plan (its targets, before, after, "
                    "objectives, mechanism), in the file's order; the whole result's designed and sheet are the "
                    "plan, its objectives the joint ones; [] for one instrument [list of Design]");
  // config_text(original) is python/ccal/_results.py's, which a Design unpickled by value has too.
  bind_design_by_value(m);

  m.def(
      "design",
      [](const Config& cfg, const TargetMap& targets, const py::kwargs& keywords) {
        auto o = options_from_keywords<verbs::DesignOptions>(keywords, "design", {}, {"targets"});
        o.targets = target_texts(targets);
        py::gil_scoped_release release;
        return verbs::design(cfg, o);
      },
      py::arg("config"), py::arg("targets") = TargetMap{},
      "The test plan within the configuration's [design] space under which the tolerances cost least "
      "(`ccal design`), re-scored by the full budget; targets: coefficient id → allowed expanded "
      "uncertainty (a number in the display unit or a string with a unit), for the objective 'uncertainty'.");
  record_keywords<verbs::DesignOptions>(m, "design", {"targets"});
}

}  // namespace ccal::python
