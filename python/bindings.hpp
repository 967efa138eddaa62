#pragma once
// The Python module `ccal`: the library's configuration, analyses and results, NumPy arrays in and out, SI
// values inside (as in C++), display units given alongside where the CLI shows them (docs/python.md).
#include <pybind11/pybind11.h>

#include <cstddef>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/render/allocate.hpp"
#include "ccal/render/budget.hpp"
#include "ccal/render/force.hpp"
#include "ccal/render/montecarlo.hpp"
#include "ccal/render/reduce.hpp"
#include "ccal/render/simulate.hpp"

namespace ccal::python {

namespace py = pybind11;

// "exact" or "paper"; anything else is an InputError naming the accepted values.
ModelMode mode_argument(const std::string& mode);

// Binds a verb's result: its report as str() (the CLI's text), to_json() (exactly the CLI's JSON), and every
// attribute of its inner result (`inner`) reachable on it, so that r.standard_uncertainty reads
// r.budget.standard_uncertainty.
template <class Result>
py::class_<Result> bind_verb_result(py::module_& m, const char* name, const char* doc, const char* inner) {
  py::class_<Result> c(m, name, doc, py::dynamic_attr());  // attributes: python/ccal/_results.py
  c.def(
       "to_json", [](const Result& r) { return render::json(r); }, "The report as the CLI's JSON (text).")
      .def("__str__", [](const Result& r) { return render::text(r); })
      .def("__getattr__", [inner](py::object self, const std::string& attr) -> py::object {
        return self.attr(inner).attr(attr.c_str());
      });
  c.attr("_inner") = inner;  // for dir() (python/ccal/_results.py) and the stubs (python/make_stubs.py)
  return c;
}

// The one unit rule of Python's results (docs/python.md): values in SI, with `units` (display) and
// `display_scale` beside them. The SI → display factor of a coefficient's (or an output's) display unit: 1 / the
// SI size of one unit (deg/s/g^3 → 180/π; a pulse counts as 1, as in the observations file); 1 for a unit ccal
// does not know, such as a table's column names ("output/a_i^2"), whose values stay as the table has them.
double display_scale_of(std::string_view unit);

// A least-squares fit as Python gives it (ccal.Fit): in SI where its data's units are known (identify(): the
// observations are SI; identify_file(): a table whose output unit is known), with the display unit and the
// SI → display factor of each term beside it; a fit of plain arrays (fit()) is in its data's units, its units ""
// and its display_scale 1.
struct UnitFit {
  FitResult fit;
  std::vector<std::string> units;
  std::vector<double> display_scale;
};
// A fit in display units (every term in the output unit per something, the output's SI → display factor
// `output_scale`; `weighted`: chi2 is then a number without unit) in SI, with `units` beside it.
UnitFit fit_in_si(const FitResult& fit, const std::vector<std::string>& units, double output_scale, bool weighted);

// Targets as Python gives them: coefficient id → a number in the coefficient's display unit (as on the command
// line) or a string with a unit; target_texts gives the library's "K3=0.001" / "K3=1e-3 deg/s/g^3".
using TargetMap = std::map<std::string, std::variant<double, std::string>>;
std::vector<std::string> target_texts(const TargetMap& targets);

// A run of the plan as Python names it (a name, or a 0-based index, negative from the last); InputError naming
// `field` (run=, or the logs' keys) otherwise.
std::size_t run_index(const Config& cfg, const std::variant<int, std::string>& run, std::string_view field = "run");

// One binding file per verb (module.cpp calls them in order).
// A path argument (str, bytes or os.PathLike) as a string; TypeError "<function>(): <name>: expected <accepted>, got
// <type>" otherwise.
std::string path_argument(const py::object& value, std::string_view function, std::string_view name,
                          std::string_view accepted);
// The log_layout argument.
inline constexpr std::string_view kLayoutArgument =
    "the path (str or os.PathLike) of a layout file: a manifest's [format] and [columns] tables in TOML";

void bind_config(py::module_& m);      // Config, Run, Tolerance and their readers
void bind_budget(py::module_& m);      // Budget and its parts, budget
void bind_force(py::module_& m);       // SensedInput and its parts, sensed_input
void bind_simulate(py::module_& m);    // Observations, Simulation, simulate, observe
void bind_fit(py::module_& m);         // Fit, Observability, observability, identify, fit
void bind_statement(py::module_& m);   // Statement
void bind_reduce(py::module_& m);      // LogReduction and its parts, Reduction, reduce, reduce_logs
void bind_montecarlo(py::module_& m);  // MonteCarlo and its parts, monte_carlo
void bind_allocate(py::module_& m);    // Allocation and its parts, allocate
void bind_design(py::module_& m);      // Design, design
void bind_report(py::module_& m);      // Report, report
void bind_identify(py::module_& m);    // Identification, identify_file
void bind_history(py::module_& m);     // History and its parts, history, history_add
void bind_derive(py::module_& m);      // Config.with_tolerance, .with_error, .with_plan

}  // namespace ccal::python
