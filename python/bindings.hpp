#pragma once
// The Python module `ccal`: the library's configuration, analyses and results, NumPy arrays in and out, SI
// values inside (as in C++), display units given alongside where the CLI shows them (docs/python.md).
#include <pybind11/pybind11.h>

#include <string>

#include "ccal/core/model_mode.hpp"
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
  py::class_<Result> c(m, name, doc, py::dynamic_attr());  // attributes: python/ccal_extras.py
  c.def(
       "to_json", [](const Result& r) { return render::json(r); }, "The report as the CLI's JSON (text).")
      .def("__str__", [](const Result& r) { return render::text(r); })
      .def("__getattr__", [inner](py::object self, const std::string& attr) -> py::object {
        return self.attr(inner).attr(attr.c_str());
      });
  return c;
}

void bind_config(py::module_& m);       // Config, Run, Tolerance and their readers
void bind_analysis(py::module_& m);     // budget, sensed_input, observe, identify, fit
void bind_uncertainty(py::module_& m);  // monte_carlo, allocate
void bind_derive(py::module_& m);       // Config.with_tolerance, .with_error, .with_plan
void bind_design(py::module_& m);       // design
void bind_identify(py::module_& m);     // identify_file

}  // namespace ccal::python
