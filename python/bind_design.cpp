// ccal.design: `ccal design` from Python (docs/python.md).
#include "ccal/render/design.hpp"  // before bindings.hpp: bind_verb_result renders the design result
// (keep this order)
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <map>
#include <optional>
#include <string>
#include <variant>

#include "bindings.hpp"
#include "option_keywords.hpp"
#include "ccal/verbs/design.hpp"

namespace ccal::python {

void bind_design(py::module_& m) {
  py::class_<verbs::DesignTarget>(m, "DesignTarget", "A coefficient of the design's objective.")
      .def_readonly("coefficient", &verbs::DesignTarget::coefficient, "the coefficient's id, e.g. 'K3' [—]")
      .def_readonly("weight", &verbs::DesignTarget::weight, "w_k in the objective (0: not counted) [—]")
      .def_readonly("reference", &verbs::DesignTarget::reference,
                    "R_k: the user's target, or the configured plan's U_k [coefficient SI: output SI per gⁿ]")
      .def_readonly("is_target", &verbs::DesignTarget::is_target,
                    "R_k is a user's target (else the configured plan's U_k) [—]");

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
      .def_readonly("before", &verbs::DesignResult::before, "the full budget of the configured plan [Budget]")
      .def_readonly("after", &verbs::DesignResult::after, "the full budget of the designed plan [Budget]")
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
                    "plan, its objectives the joint ones; [] for one instrument [list of Design]")
      .def(
          "config_text",
          [](const verbs::DesignResult& r, const std::string& original) {
            return render::config_with_plan(original, r.designed);
          },
          py::arg("original"),
          "The configuration text `original` with its [plan] replaced by the designed one (as --plan-out).");

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
