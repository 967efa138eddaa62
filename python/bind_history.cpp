// `ccal history` from Python: an instrument's calibrations read from the store (History, history()) and a
// statement recorded (history_add()); display() and to_frame() are added in Python (python/ccal/_results.py).
#include <pybind11/stl.h>

#include <string>

#include "bindings.hpp"
#include "ccal/render/history.hpp"
#include "ccal/verbs/history.hpp"
#include "option_keywords.hpp"

namespace ccal::python {

void bind_history(py::module_& m) {
  py::class_<HistoryCoefficient>(m, "HistoryCoefficient", "One coefficient of a recorded calibration.")
      .def_readonly("name", &HistoryCoefficient::name, "the coefficient [—]")
      .def_readonly("unit", &HistoryCoefficient::unit, "its unit, as the statement wrote it [—]")
      .def_readonly("value", &HistoryCoefficient::value, "the corrected estimate [unit]")
      .def_readonly("expanded", &HistoryCoefficient::expanded, "U [unit]")
      .def_readonly("coverage_factor", &HistoryCoefficient::coverage_factor, "k [—]")
      .def_readonly("coverage_probability", &HistoryCoefficient::coverage_probability, "p [—]")
      .def_readonly("effective_dof", &HistoryCoefficient::effective_dof, "ν_eff, inf where infinite [—]");
  py::class_<HistoryRecord>(m, "HistoryRecord", "One recorded calibration.")
      .def_readonly("id", &HistoryRecord::id, "its id in the store [—]")
      .def_readonly("serial", &HistoryRecord::serial, "serial number [—]")
      .def_readonly("date", &HistoryRecord::date, "date of calibration, YYYY-MM-DD [—]")
      .def_readonly("instrument", &HistoryRecord::instrument, "the instrument as the certificate names it [—]")
      .def_readonly("ccal_version", &HistoryRecord::ccal_version, "of the ccal that wrote the statement [—]")
      .def_readonly("config", &HistoryRecord::config, "the configuration the statement names [—]")
      .def_readonly("statement_sha256", &HistoryRecord::statement_sha256, "of the statement's text [—]")
      .def_readonly("added_at", &HistoryRecord::added_at, "when it was recorded, UTC [—]")
      .def_readonly("coefficients", &HistoryRecord::coefficients, "list of HistoryCoefficient [—]")
      .def_readonly("superseded_by", &HistoryRecord::superseded_by, "the record that replaces it, or None [—]")
      .def_readonly("superseded_reason", &HistoryRecord::superseded_reason, "why; empty: not superseded [—]")
      .def_readonly("statement_json", &HistoryRecord::statement_json, "the statement as recorded (JSON text) [—]");
  py::class_<NormalisedError>(m, "NormalisedError", "E_n of a calibration against the one before.")
      .def_readonly("from_index", &NormalisedError::from, "index of the earlier calibration [—]")
      .def_readonly("to_index", &NormalisedError::to, "index of the later one [—]")
      .def_readonly("value", &NormalisedError::value, "(x₂ − x₁)/√(U₁² + U₂²) [—]")
      .def_readonly("disagree", &NormalisedError::disagree, "|E_n| > 1 [—]");
  py::class_<DriftLine>(m, "DriftLine", "The weighted straight line through a coefficient's calibrations.")
      .def_readonly("available", &DriftLine::available, "three calibrations at two dates at least [—]")
      .def_readonly("reference_years", &DriftLine::reference_years, "t̄, years from the first calibration [a]")
      .def_readonly("value", &DriftLine::value, "the line at t̄ [unit]")
      .def_readonly("std_value", &DriftLine::std_value, "its standard uncertainty [unit]")
      .def_readonly("slope", &DriftLine::slope, "the drift [unit per year]")
      .def_readonly("std_slope", &DriftLine::std_slope, "its standard uncertainty [unit per year]")
      .def_readonly("chi_squared", &DriftLine::chi_squared, "χ² about the line [—]")
      .def_readonly("dof", &DriftLine::dof, "n − 2 [—]")
      .def_readonly("birge_ratio", &DriftLine::birge_ratio, "√(χ²/dof) [—]");
  py::class_<DriftPrediction>(m, "DriftPrediction", "The drift line at a date.")
      .def_readonly("years", &DriftPrediction::years, "years from the first calibration [a]")
      .def_readonly("value", &DriftPrediction::value, "[unit]")
      .def_readonly("std_uncertainty", &DriftPrediction::std_uncertainty, "[unit]");
  py::class_<verbs::CoefficientHistory>(m, "CoefficientHistory",
                                        "One coefficient over the calibrations that are not superseded.")
      .def_readonly("name", &verbs::CoefficientHistory::name, "[—]")
      .def_readonly("unit", &verbs::CoefficientHistory::unit, "[—]")
      .def_readonly("dates", &verbs::CoefficientHistory::dates, "YYYY-MM-DD, oldest first [—]")
      .def_property_readonly(
          "values",
          [](const verbs::CoefficientHistory& h) {
            std::vector<double> v;
            for (const HistoryPoint& p : h.points) v.push_back(p.value);
            return v;
          },
          "the corrected estimates [unit]")
      .def_property_readonly(
          "expanded",
          [](const verbs::CoefficientHistory& h) {
            std::vector<double> v;
            for (const HistoryPoint& p : h.points) v.push_back(p.expanded);
            return v;
          },
          "U of each [unit]")
      .def_readonly("normalised_errors", &verbs::CoefficientHistory::agreement, "list of NormalisedError [—]")
      .def_readonly("drift", &verbs::CoefficientHistory::drift, "DriftLine [—]")
      .def_readonly("prediction", &verbs::CoefficientHistory::prediction, "DriftPrediction at `at`, or None [—]");
  py::class_<verbs::HistoryShowResult>(m, "History",
                                       "`ccal history show`: a serial number's calibrations; str() is the CLI's "
                                       "text, to_json() its JSON.")
      .def("to_json", [](const verbs::HistoryShowResult& r) { return render::json(r); },
           "The report as the CLI's JSON (text).")
      .def("__str__", [](const verbs::HistoryShowResult& r) { return render::text(r); })
      .def_readonly("db", &verbs::HistoryShowResult::db, "the store [—]")
      .def_readonly("serial", &verbs::HistoryShowResult::serial, "[—]")
      .def_readonly("records", &verbs::HistoryShowResult::records, "every calibration, list of HistoryRecord [—]")
      .def_readonly("coefficients", &verbs::HistoryShowResult::coefficients, "list of CoefficientHistory [—]");

  m.def(
      "history",
      [](const std::string& serial, const py::kwargs& keywords) {
        return verbs::history_show(serial, options_from_keywords<verbs::HistoryShowOptions>(keywords, "history"));
      },
      py::arg("serial"),
      "A serial number's calibrations from the history store (`ccal history show`): per coefficient E_n of "
      "successive calibrations, the drift line and its prediction at `at`.");
  record_keywords<verbs::HistoryShowOptions>(m, "history");
  m.def(
      "history_add",
      [](const std::string& statement, const py::kwargs& keywords) {
        return verbs::history_add(statement,
                                  options_from_keywords<verbs::HistoryAddOptions>(keywords, "history_add"))
            .id;
      },
      py::arg("statement"),
      "Records a calibration statement file in the history store (`ccal history add`); returns its id.");
  record_keywords<verbs::HistoryAddOptions>(m, "history_add");
}

}  // namespace ccal::python
