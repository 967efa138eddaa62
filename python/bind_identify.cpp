// ccal.identify_file: `ccal identify FILE` from Python (docs/python.md): the same table, options and defaults
// (verbs::IdentifyOptions), the same result, text and JSON.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "option_keywords.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/render/identify.hpp"  // before bindings.hpp (keep this order)
#include "ccal/verbs/identify.hpp"

namespace ccal::python {

namespace {

// The SI → display factor of the table's output, which every term is in per something: 1 when the table does
// not give its output's unit (its values are then as the table has them).
double output_scale(const verbs::IdentifyResult& r) {
  return r.identification.output_unit.empty() ? 1.0 : display_scale_of(r.identification.output_unit);
}

}  // namespace

void bind_identify(py::module_& m) {
  py::class_<verbs::IdentifyResult>(m, "Identification",
                                    "`ccal identify`: the fit of a table of observations, with units and the "
                                    "observability of each term (and the calibration statement with "
                                    "statement=True); str() is the CLI's text, to_json() its JSON.")
      .def("to_json", [](const verbs::IdentifyResult& r) { return render::json(r); })
      .def("__str__", [](const verbs::IdentifyResult& r) { return render::text(r); })
      .def_readonly("source", &verbs::IdentifyResult::source, "the table's file [path]")
      .def_readonly("rows", &verbs::IdentifyResult::rows, "observations fitted [—]")
      .def_property_readonly(
          "fit",
          [](const verbs::IdentifyResult& r) {
            return fit_in_si(r.identification.fit, r.identification.units, output_scale(r), r.identification.weighted);
          },
          "the least-squares fit in SI (output SI per g^n; per the input column's unit where it is not in g), with "
          "units and display_scale; a table without its output's unit: in the table's units, display_scale 1 "
          "[Fit]")
      .def_property_readonly(
          "units", [](const verbs::IdentifyResult& r) { return r.identification.units; },
          "the display unit of each free term's coefficient, as the table gives it [—]")
      .def_property_readonly(
          "display_scale",
          [](const verbs::IdentifyResult& r) {
            return std::vector<double>(r.identification.units.size(), output_scale(r));
          },
          "SI → display unit factor per free term: fit.value × display_scale is the table's figure [display "
          "unit per SI]")
      .def_property_readonly(
          "has_statement", [](const verbs::IdentifyResult& r) { return r.statement.has_value(); },
          "True when statement=True gave the calibration statement [—]")
      .def_readonly("statement", &verbs::IdentifyResult::statement,
                    "the calibration statement with statement=True, else None [Statement]");

  m.def(
      "identify_file",
      [](const py::object& path, std::optional<Config> config, const py::kwargs& keywords) {
        // "" would be no weights, as weight_column left out: refused, as the command line refuses it.
        if (keywords.contains("weight_column") && py::isinstance<py::str>(keywords["weight_column"]))
          verbs::refuse_empty_weight_column(keywords["weight_column"].cast<std::string>());
        auto o = options_from_keywords<verbs::IdentifyOptions>(keywords, "identify_file", {}, {},
                                                               {"path", "config"});
        o.config = std::move(config);
        return verbs::identify(
            read_csv_file(path_argument(path, "identify_file", "path", "the path of a CSV file (str or os.PathLike)")),
            o);
      },
      py::arg("path"), py::kw_only(), py::arg("config") = py::none(),
      "Identifies coefficients from a CSV file as `ccal identify` does: an observations file of "
      "Simulation.to_csv() or `ccal simulate --observations-out` (terms, fixed terms and known columns from "
      "its '# ccal observations' line unless given), or any table with input and output columns. terms: e.g. "
      "['K0', 'K1', 'K2']; fix: ['K1=505.2 deg/s/g']; known: columns subtracted from the output (['none'] "
      "for none); statement=True with config (a Config whose tolerances give the Type B part): also the "
      "calibration statement.");
  record_keywords<verbs::IdentifyOptions>(m, "identify_file");
}

}  // namespace ccal::python
