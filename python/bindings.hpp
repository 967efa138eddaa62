#pragma once
// The Python module `ccal`: the library's configuration, analyses and results, NumPy arrays in and out, SI
// values inside (as in C++), display units given alongside where the CLI shows them (docs/python.md).
#include <pybind11/pybind11.h>

#include <string>

#include "ccal/model_mode.hpp"

namespace ccal::python {

namespace py = pybind11;

// "exact" or "paper"; anything else is an InputError naming the accepted values.
ModelMode parse_mode(const std::string& mode);
const char* mode_name(ModelMode mode);

void bind_config(py::module_& m);       // Config, Run, Tolerance and their readers
void bind_analysis(py::module_& m);     // budget, sensed_input, observe, identify, fit
void bind_uncertainty(py::module_& m);  // monte_carlo, allocate

}  // namespace ccal::python
