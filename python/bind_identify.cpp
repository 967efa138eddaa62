// ccal.identify_file: `ccal identify FILE` from Python (docs/python.md): the same table, options and defaults
// (verbs::IdentifyOptions), the same result, text and JSON.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/render/identify.hpp"  // before bindings.hpp (keep this order)
#include "ccal/verbs/identify.hpp"

namespace ccal::python {

void bind_identify(py::module_& m) {
  py::class_<verbs::IdentifyResult>(m, "Identification",
                                    "`ccal identify`: the fit of a table of observations, with units and the "
                                    "observability of each term (and the calibration statement when a budget "
                                    "configuration is given); str() is the CLI's text, to_json() its JSON.")
      .def("to_json", [](const verbs::IdentifyResult& r) { return render::json(r); })
      .def("__str__", [](const verbs::IdentifyResult& r) { return render::text(r); })
      .def_readonly("source", &verbs::IdentifyResult::source, "the table's file [path]")
      .def_readonly("rows", &verbs::IdentifyResult::rows, "observations fitted [—]")
      .def_property_readonly(
          "fit", [](const verbs::IdentifyResult& r) { return r.identification.fit; },
          "the least-squares fit, in the table's own units [output unit / input unit^n]")
      .def_property_readonly(
          "units", [](const verbs::IdentifyResult& r) { return r.identification.units; },
          "the unit of each free term's coefficient [—]")
      .def_property_readonly(
          "has_statement", [](const verbs::IdentifyResult& r) { return r.statement.has_value(); },
          "True when a budget configuration gave the calibration statement [—]");

  const verbs::IdentifyOptions defaults;
  m.def(
      "identify_file",
      [](const std::string& path, std::optional<std::vector<std::string>> terms,
         std::optional<std::vector<std::string>> fix, std::optional<std::vector<std::string>> known,
         const std::string& input, const std::string& output, const std::string& weight,
         std::optional<Config> budget, std::optional<std::string> mode, double coverage_probability) {
        verbs::IdentifyOptions o;
        o.terms = std::move(terms);
        o.fix = std::move(fix);
        o.known = std::move(known);
        o.input = input;
        o.output = output;
        o.weight = weight;
        o.budget = std::move(budget);
        o.budget_option = "budget";
        if (mode) o.statement.mode = mode_argument(*mode);
        o.statement.coverage_probability = coverage_probability;
        return verbs::identify(read_csv_file(path), o);
      },
      py::arg("path"), py::arg("terms") = py::none(), py::arg("fix") = py::none(),
      py::arg("known") = py::none(), py::arg("input") = defaults.input, py::arg("output") = defaults.output,
      py::arg("weight") = defaults.weight, py::arg("budget") = py::none(), py::arg("mode") = py::none(),
      py::arg("coverage_probability") = defaults.statement.coverage_probability,
      "Identifies coefficients from a CSV file as `ccal identify` does: an observations file of "
      "Simulation.to_csv() or `ccal simulate --observations-out` (terms, fixed terms and known columns from "
      "its '# ccal observations' line unless given), or any table with input and output columns. terms: e.g. "
      "['K0', 'K1', 'K2']; fix: ['K1=505.2 deg/s/g']; known: columns subtracted from the output (['none'] "
      "for none); weight: the column of the σ of the output; budget: a Config whose tolerances give the "
      "calibration statement's Type B part, mode its kinematics ('exact' or 'paper'; default its own).");
}

}  // namespace ccal::python
