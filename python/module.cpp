#include <fmt/format.h>
#include <fmt/ranges.h>
#include <pybind11/pybind11.h>

#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/version.hpp"

namespace ccal::python {

// The library's parser of a choice, so the refusal is the command line's but for the option's name.
ModelMode mode_argument(const std::string& mode) {
  return static_cast<ModelMode>(parse_choice_option("mode", mode, kModeNames));
}

double display_scale_of(std::string_view unit) {
  try {
    return 1.0 / output_unit_si(unit);  // as to_unit(1, unit): the budget's display_scale, bit for bit
  } catch (const UnitError&) {
    return 1.0;  // a table's column names ("output/a_i^2"): its values are taken as they are
  }
}

std::vector<std::string> target_texts(const TargetMap& targets) {
  std::vector<std::string> texts;
  for (const auto& [id, value] : targets)
    texts.push_back(std::holds_alternative<double>(value) ? fmt::format("{}={:.17g}", id, std::get<double>(value))
                                                          : id + "=" + std::get<std::string>(value));
  return texts;
}

std::size_t run_index(const Config& cfg, const std::variant<int, std::string>& run, std::string_view field) {
  const int n = int(cfg.plan.runs.size());
  if (const int* i = std::get_if<int>(&run)) {
    if (*i < -n || *i >= n)
      throw InputError(fmt::format("{}: index {} is out of range for {} runs; accepted: 0 to {} (or -{} to -1 from "
                                   "the last)",
                                   field, *i, n, n - 1, n));
    return std::size_t(*i < 0 ? *i + n : *i);
  }
  // A string of digits that names no run is the same 0-based index as the int (run="1" is run=1, the
  // second run), not the command line's 1-based index.
  const std::string& text = std::get<std::string>(run);
  for (std::size_t k = 0; k < cfg.plan.runs.size(); ++k)
    if (cfg.plan.runs[k].name == text) return k;
  if (!text.empty() && text.find_first_not_of("0123456789") == std::string::npos && text.size() < 9)
    return run_index(cfg, std::stoi(text), field);
  std::vector<std::string> names;
  for (const Run& r : cfg.plan.runs) names.push_back(r.name);
  // The library's select_run words the command line's 1-based index: Python's are 0-based.
  throw InputError(fmt::format("{}: '{}' is no run; accepted: a run name ({}) or a 0-based index 0 to {}", field,
                               text, fmt::join(names, ", "), n - 1));
}

}  // namespace ccal::python

// The compiled part of the package ccal (python/ccal/__init__.py re-exports it).
PYBIND11_MODULE(_ccal, m) {
  namespace py = pybind11;
  // The public home of the classes and functions is the package: they are bound with `ccal` as their module
  // (their __module__, the type names in signatures and docstrings, pickling by name), then the module takes
  // back its own name.
  const py::object own_name = m.attr("__name__");
  m.attr("__name__") = "ccal";
  m.doc() =
      "Precision-centrifuge calibration of accelerometers: exact kinematics, identification of the "
      "coefficients, and the error budget of the centrifuge's tolerances. Values are SI unless a name says "
      "otherwise (specific force in g); display units are given alongside.";
  m.attr("__version__") = ccal::version();
  m.attr("__commit__") = ccal::version_commit();  // the git commit built from, or "unknown"
  // Bad input (configuration, options, data) and ill-posed identifications, as ValueError subclasses.
  static py::exception<ccal::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<ccal::IllPosedFit> ill_posed(m, "IllPosedFit", input_error.ptr());
  // An input file that cannot be opened: an InputError that is also Python's FileNotFoundError.
  static py::exception<ccal::FileNotFoundMark> file_not_found(
      m, "FileNotFound", py::make_tuple(input_error, py::handle(PyExc_FileNotFoundError)));
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ccal::IllPosedFit& e) {  // before its base class
      ill_posed(e.what());
    } catch (const ccal::InputError& e) {
      if (dynamic_cast<const ccal::FileNotFoundMark*>(&e) != nullptr)
        file_not_found(e.what());
      else
        input_error(e.what());
    }
  });
  // In this order: a class is bound before the functions and classes that name it in their signatures.
  ccal::python::bind_config(m);
  ccal::python::bind_budget(m);
  ccal::python::bind_force(m);
  ccal::python::bind_history(m);
  ccal::python::bind_simulate(m);
  ccal::python::bind_fit(m);
  ccal::python::bind_statement(m);
  ccal::python::bind_reduce(m);
  ccal::python::bind_montecarlo(m);
  ccal::python::bind_allocate(m);
  ccal::python::bind_design(m);
  ccal::python::bind_identify(m);
  ccal::python::bind_report(m);
  ccal::python::bind_derive(m);
  m.attr("__name__") = own_name;
}
