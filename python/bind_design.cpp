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

  py::class_<verbs::DesignResult>(
      m, "Design",
      "`ccal design`: the configured and the designed plan with their full budgets; "
      "str() is the CLI's text, to_json() its JSON.")
      .def("to_json", [](const verbs::DesignResult& r) { return render::json(r); })
      .def("__str__", [](const verbs::DesignResult& r) { return render::text(r); })
      .def_readonly("config", &verbs::DesignResult::config, "the configuration as given [Config]")
      .def_readonly("designed", &verbs::DesignResult::designed,
                    "the configuration with the designed plan [Config]")
      .def_readonly("before", &verbs::DesignResult::before, "the full budget of the configured plan [Budget]")
      .def_readonly("after", &verbs::DesignResult::after, "the full budget of the designed plan [Budget]")
      .def_readonly("targets", &verbs::DesignResult::targets,
                    "the objective's coefficients, list of DesignTarget [—]")
      .def_readonly("candidates", &verbs::DesignResult::candidates, "the number of candidate runs cached [—]")
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
      .def_readonly("mechanism", &verbs::DesignResult::mechanism,
                    "a sentence on what the designed plan does differently, where one can be named [—]")
      .def(
          "config_text",
          [](const verbs::DesignResult& r, const std::string& original) {
            return render::config_with_plan(original, r.designed);
          },
          py::arg("original"),
          "The configuration text `original` with its [plan] replaced by the designed one (as --plan-out).");

  const verbs::DesignOptions defaults;  // the CLI's defaults
  m.def(
      "design",
      [](const Config& cfg, const std::map<std::string, std::variant<double, std::string>>& targets,
         std::optional<std::string> objective, std::optional<int> starts, std::optional<std::uint64_t> seed,
         int threads, std::int64_t verify_trials, const std::vector<double>& tradeoff) {
        verbs::DesignOptions o;
        for (const auto& [id, value] : targets)
          o.targets.push_back(std::holds_alternative<double>(value)
                                  ? fmt::format("{}={:.17g}", id, std::get<double>(value))
                                  : id + "=" + std::get<std::string>(value));
        if (objective) {
          if (*objective == "uncertainty")
            o.objective = DesignObjective::uncertainty;
          else if (*objective == "d_optimal")
            o.objective = DesignObjective::d_optimal;
          else if (*objective == "a_optimal")
            o.objective = DesignObjective::a_optimal;
          else
            throw InputError("objective: '" + *objective +
                             "' is not an objective; accepted: 'uncertainty', 'd_optimal', 'a_optimal'");
        }
        o.starts = starts;
        o.seed = seed;
        o.threads = threads;
        o.verify_trials = verify_trials;
        o.tradeoff = tradeoff;
        py::gil_scoped_release release;
        return verbs::design(cfg, o);
      },
      py::arg("config"), py::arg("targets") = std::map<std::string, std::variant<double, std::string>>{},
      py::arg("objective") = py::none(), py::arg("starts") = py::none(), py::arg("seed") = py::none(),
      py::arg("threads") = defaults.threads, py::arg("verify_trials") = defaults.verify_trials,
      py::arg("tradeoff") = defaults.tradeoff,
      "The test plan within the configuration's [design] space under which the tolerances cost least "
      "(`ccal design`), re-scored by the full budget. The defaults are the CLI's.");
}

}  // namespace ccal::python
