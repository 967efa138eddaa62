// `ccal force` from Python: the sensed input at one instant with the first-order contributions, the
// SensedInput result and sensed_input().
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <variant>

#include "bindings.hpp"
#include "option_keywords.hpp"
#include "ccal/core/units.hpp"
#include "ccal/model/sensed_input.hpp"
#include "ccal/verbs/force.hpp"

namespace ccal::python {

// The sensed input at one instant, with the first-order contributions.
void bind_force(py::module_& m) {
  py::class_<ForceContribution>(m, "ForceContribution")
      .def_readonly("id", &ForceContribution::id, "the error parameter's id [—]")
      .def_readonly("value", &ForceContribution::value_si,
                    "the parameter's configured value [SI unit of the parameter]")
      .def_readonly("unit", &ForceContribution::unit, "the parameter's SI unit [—]")
      .def_readonly("f_ia", &ForceContribution::f_ia, "first-order change of the IA specific force [g]")
      .def_readonly("w_ia", &ForceContribution::w_ia, "first-order change of the IA inertial rate [rad/s]");

  py::class_<SensedInputBreakdown>(m, "SensedInputDetail",
                                   "What the instrument senses at one instant of a run.")
      .def_readonly("specific_force", &SensedInputBreakdown::specific_force,
                    "specific force along IA, PA, OA [g]")
      .def_readonly("angular_rate", &SensedInputBreakdown::angular_rate,
                    "inertial angular rate about IA, PA, OA [rad/s]")
      .def_readonly("rate", &SensedInputBreakdown::rate, "the nominal main-axis rate Ω [rad/s]")
      .def_readonly("initial_phase", &SensedInputBreakdown::initial_phase, "φ0 [rad]")
      .def_readonly("time", &SensedInputBreakdown::time, "t in the run [s]")
      .def_readonly("nominal_f_ia", &SensedInputBreakdown::nominal_f_ia,
                    "the error-free IA specific force [g]")
      .def_readonly("nominal_w_ia", &SensedInputBreakdown::nominal_w_ia,
                    "the error-free IA inertial rate [rad/s]")
      .def_readonly("contributions", &SensedInputBreakdown::contributions,
                    "first-order contribution of each non-zero error, list of ForceContribution [—]")
      .def_readonly("first_order_f_ia", &SensedInputBreakdown::first_order_f_ia,
                    "nominal + Σ first-order contributions to the IA specific force [g]")
      .def_readonly("first_order_w_ia", &SensedInputBreakdown::first_order_w_ia,
                    "nominal + Σ first-order contributions to the IA rate [rad/s]")
      .def_property_readonly("remainder_f_ia", &SensedInputBreakdown::remainder_f_ia,
                             "exact − first order, IA specific force [g]")
      .def_property_readonly("remainder_w_ia", &SensedInputBreakdown::remainder_w_ia,
                             "exact − first order, IA rate [rad/s]");

  bind_verb_result<verbs::ForceResult>(m, "SensedInput",
                                       "`ccal force` at one instant: its SensedInputDetail's fields are "
                                       "readable on it; str() is the CLI's text, to_json() its JSON.",
                                       "input")
      .def_readonly("config", &verbs::ForceResult::config)
      .def_readonly("input", &verbs::ForceResult::input,
                    "the sensed input itself (its fields are readable on the result) [SensedInputDetail]");

  m.def(
      "sensed_input",
      [](const Config& cfg, const std::variant<int, std::string>& run, const py::kwargs& keywords) {
        // time as --time takes it: a number in s, or text with its unit ("10 s"), read by the library's parser.
        py::kwargs rest;
        std::optional<double> time;
        for (const auto& [key, value] : keywords) {
          if (py::isinstance<py::str>(value) && py::cast<std::string>(py::str(key)) == "time")
            time = parse_as(py::cast<std::string>(value), kind::time, "time", true);
          else
            rest[key] = value;
        }
        auto o = options_from_keywords<verbs::ForceOptions>(rest, "sensed_input", {}, {"run"});
        if (time) o.time = *time;
        o.run = cfg.plan.runs[run_index(cfg, run)].name;
        return verbs::force(cfg, o);
      },
      py::arg("config"), py::arg("run") = 0,
      "Specific force and angular rate at time t [s] of a run (a name, or a 0-based index) with the "
      "configured errors (`ccal force`).");
  record_keywords<verbs::ForceOptions>(m, "sensed_input", {"run"}, {{"time", "Union[float, str]"}});
}

}  // namespace ccal::python
