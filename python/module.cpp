#include <pybind11/eval.h>
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/version.hpp"
#include "ccal_extras.hpp"

namespace ccal::python {

ModelMode mode_argument(const std::string& mode) {
  if (const auto m = parse_mode(mode)) return *m;
  std::string accepted;
  for (std::string_view name : kModeNames)
    accepted += (accepted.empty() ? "'" : ", '") + std::string(name) + "'";
  throw InputError("mode: '" + mode + "' is not a model mode; accepted: " + accepted);
}

}  // namespace ccal::python

PYBIND11_MODULE(ccal, m) {
  namespace py = pybind11;
  m.doc() =
      "Precision-centrifuge calibration of accelerometers: exact kinematics, identification of the "
      "coefficients, and the error budget of the centrifuge's tolerances. Values are SI unless a name says "
      "otherwise (specific force in g); display units are given alongside.";
  m.attr("__version__") = ccal::version();
  m.attr("__commit__") = ccal::version_commit();  // the git commit built from, or "unknown"
  // Bad input (configuration, options, data) and ill-posed identifications, as ValueError subclasses.
  static py::exception<ccal::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<ccal::IllPosedFit> ill_posed(m, "IllPosedFit", input_error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ccal::IllPosedFit& e) {  // before its base class
      ill_posed(e.what());
    } catch (const ccal::InputError& e) {
      input_error(e.what());
    }
  });
  ccal::python::bind_config(m);
  ccal::python::bind_analysis(m);
  ccal::python::bind_uncertainty(m);
  ccal::python::bind_design(m);
  ccal::python::bind_identify(m);
  ccal::python::bind_derive(m);
  // Signatures, repr, display(), pickling and the remaining docstrings, written in Python.
  py::exec(ccal::python::kPropertyDocsSource, m.attr("__dict__"));
  py::exec(ccal::python::kExtrasSource, m.attr("__dict__"));
}
