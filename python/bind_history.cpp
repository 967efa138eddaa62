// `ccal history` from Python: an instrument's calibrations read from the store (History, history()), a
// statement recorded (history_add()), the store's serials (history_list()), a record superseded
// (history_supersede()), a serial's history exported and an exported file imported (history_export(),
// history_import()); display() and to_frame() are added in Python (python/ccal/_results.py).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "ccal/render/history.hpp"
#include "ccal/verbs/history.hpp"
#include "option_keywords.hpp"

namespace ccal::python {

namespace {

// The one unit rule (docs/python.md): the store holds the statements' figures, each in its coefficient's unit;
// Python gives them in SI, that unit's display scale beside them (1 for a unit ccal does not know).
DriftLine drift_in_si(DriftLine d, double scale) {
  d.value /= scale;
  d.std_value /= scale;
  d.slope /= scale;
  d.std_slope /= scale;
  return d;
}

std::optional<DriftPrediction> prediction_in_si(std::optional<DriftPrediction> p, double scale) {
  if (p) {
    p->value /= scale;
    p->std_uncertainty /= scale;
  }
  return p;
}

std::vector<NormalisedError> agreement_in_si(std::vector<NormalisedError> errors, double scale) {
  for (NormalisedError& e : errors) e.shared_covariance /= scale * scale;
  return errors;
}

// Each calibration's value or U of a coefficient's history, in SI.
std::vector<double> points_in_si(const verbs::CoefficientHistory& h, double HistoryPoint::*field) {
  std::vector<double> v;
  for (const HistoryPoint& p : h.points) v.push_back(p.*field / display_scale_of(h.unit));
  return v;
}

// The store's records, its serial numbers and the set-up changes between records.
void bind_history_records(py::module_& m) {
  py::class_<HistoryCoefficient>(m, "HistoryCoefficient", "One coefficient of a recorded calibration.")
      .def_readonly("name", &HistoryCoefficient::name, "the coefficient [—]")
      .def_readonly("unit", &HistoryCoefficient::unit, "its display unit, as the statement wrote it [—]")
      .def_property_readonly(
          "display_scale", [](const HistoryCoefficient& c) { return display_scale_of(c.unit); },
          "SI → display unit factor [display unit per SI]")
      .def_property_readonly(
          "value", [](const HistoryCoefficient& c) { return c.value / display_scale_of(c.unit); },
          "the corrected estimate [coefficient SI]")
      .def_property_readonly(
          "expanded", [](const HistoryCoefficient& c) { return c.expanded / display_scale_of(c.unit); },
          "U [coefficient SI]")
      .def_readonly("coverage_factor", &HistoryCoefficient::coverage_factor, "k [—]")
      .def_readonly("coverage_probability", &HistoryCoefficient::coverage_probability, "p [—]")
      .def_readonly("effective_dof", &HistoryCoefficient::effective_dof, "ν_eff, inf where infinite [—]");
  py::class_<HistoryRecord>(m, "HistoryRecord", "One recorded calibration.")
      .def_readonly("id", &HistoryRecord::id, "its id in the store [—]")
      .def_readonly("serial", &HistoryRecord::serial, "serial number [—]")
      .def_readonly("date", &HistoryRecord::date, "date of calibration, YYYY-MM-DD [—]")
      .def_readonly("instrument", &HistoryRecord::instrument,
                    "the instrument as the certificate names it [—]")
      .def_readonly("ccal_version", &HistoryRecord::ccal_version, "of the ccal that wrote the statement [—]")
      .def_readonly("config", &HistoryRecord::config, "the configuration the statement names [—]")
      .def_readonly("statement_sha256", &HistoryRecord::statement_sha256, "of the statement's text [—]")
      .def_readonly("added_at", &HistoryRecord::added_at, "when it was recorded, UTC [—]")
      .def_readonly("coefficients", &HistoryRecord::coefficients, "list of HistoryCoefficient [—]")
      .def_readonly("superseded_by", &HistoryRecord::superseded_by,
                    "the record that replaces it, or None [—]")
      .def_readonly("superseded_reason", &HistoryRecord::superseded_reason, "why; empty: not superseded [—]")
      .def_readonly("statement_json", &HistoryRecord::statement_json,
                    "the statement as recorded (JSON text) [—]")
      .def_readonly("certificate_number", &HistoryRecord::certificate_number,
                    "the certificate's number; empty: none [—]")
      .def_property_readonly(
          "setup_sha256",
          [](const HistoryRecord& r) -> std::optional<std::string> {
            return r.shared ? std::optional<std::string>(r.shared->setup_sha256) : std::nullopt;
          },
          "the set-up's fingerprint, or None where the record does not know what it shares [—]");
  py::class_<HistoryStore::SerialSummary>(m, "HistorySerial",
                                          "A serial number of the store (`ccal history list`).")
      .def_readonly("serial", &HistoryStore::SerialSummary::serial, "[—]")
      .def_readonly("calibrations", &HistoryStore::SerialSummary::calibrations,
                    "recorded, superseded ones too [—]")
      .def_readonly("superseded", &HistoryStore::SerialSummary::superseded, "of them superseded [—]")
      .def_readonly("last_date", &HistoryStore::SerialSummary::last_date, "YYYY-MM-DD of the latest [—]");
  py::class_<HistoryImport>(m, "HistoryImport", "What `history_import` recorded (`ccal history import`).")
      .def_readonly("serial", &HistoryImport::serial, "the serial number of the file [—]")
      .def_readonly("added", &HistoryImport::added, "calibrations recorded [—]")
      .def_readonly("present", &HistoryImport::present, "calibrations already in the store [—]")
      .def_readonly("superseded", &HistoryImport::superseded, "supersessions recorded [—]");
  py::class_<verbs::SetupChange>(m, "SetupChange",
                                 "Where the set-up or its tolerances change between calibrations.")
      .def_readonly("from_id", &verbs::SetupChange::from, "the earlier record [—]")
      .def_readonly("to_id", &verbs::SetupChange::to, "the later record [—]")
      .def_readonly("from_date", &verbs::SetupChange::from_date, "[—]")
      .def_readonly("to_date", &verbs::SetupChange::to_date, "[—]")
      .def_readonly("setup", &verbs::SetupChange::setup, "another set-up: nothing shared across it [—]")
      .def_readonly("tolerances", &verbs::SetupChange::tolerances, "the same set-up, other tolerances [—]")
      .def_readonly("unknown", &verbs::SetupChange::unknown, "one of them does not know what it shares [—]");
}

// The trend of one coefficient: E_n, the drift line, its prediction.
void bind_history_trend(py::module_& m) {
  py::class_<NormalisedError>(m, "NormalisedError", "E_n of a calibration against the one before.")
      .def_readonly("from_index", &NormalisedError::from, "index of the earlier calibration [—]")
      .def_readonly("to_index", &NormalisedError::to, "index of the later one [—]")
      .def_readonly("value", &NormalisedError::value,
                    "(x₂ − x₁)/√(U₁² + U₂² − 2 k₁ k₂ C₁₂); 0 where undefined [—]")
      .def_readonly("defined", &NormalisedError::defined, "false: the difference has no uncertainty [—]")
      .def_readonly("shared_covariance", &NormalisedError::shared_covariance,
                    "C₁₂, shared by the two [coefficient SI²]")
      .def_readonly("disagree", &NormalisedError::disagree, "|E_n| > 1 [—]");
  py::class_<DriftLine>(m, "DriftLine", "The weighted straight line through a coefficient's calibrations.")
      .def_readonly("available", &DriftLine::available, "three calibrations at two dates at least [—]")
      .def_readonly("unavailable", &DriftLine::unavailable, "why not, where not available [—]")
      .def_readonly("correlated", &DriftLine::correlated,
                    "calibrations sharing errors were fitted with them [—]")
      .def_readonly("reference_years", &DriftLine::reference_years, "t̄, years from the first calibration [a]")
      .def_readonly("value", &DriftLine::value, "the line at t̄ [coefficient SI]")
      .def_readonly("std_value", &DriftLine::std_value, "its standard uncertainty [coefficient SI]")
      .def_readonly("slope", &DriftLine::slope, "the drift [coefficient SI per year]")
      .def_readonly("std_slope", &DriftLine::std_slope, "its standard uncertainty [coefficient SI per year]")
      .def_readonly("chi_squared", &DriftLine::chi_squared, "χ² about the line [—]")
      .def_readonly("dof", &DriftLine::dof, "n − 2 [—]")
      .def_readonly("birge_ratio", &DriftLine::birge_ratio, "√(χ²/dof) [—]");
  py::class_<DriftPrediction>(m, "DriftPrediction", "The drift line at a date.")
      .def_readonly("years", &DriftPrediction::years, "years from the first calibration [a]")
      .def_readonly("value", &DriftPrediction::value, "[coefficient SI]")
      .def_readonly("std_uncertainty", &DriftPrediction::std_uncertainty, "[coefficient SI]");
}

// What changes the store besides an addition: a record superseded, a serial's history exported and imported.
void bind_history_exchange(py::module_& m) {
  m.def(
      "history_supersede",
      [](const py::object& id_argument, const py::kwargs& keywords) {
        // As a keyword's integer: pybind11's own conversion took True for record 1.
        std::int64_t id = 0;
        keywords::assign(id, "id", id_argument);
        verbs::history_supersede(id, options_from_keywords<verbs::HistorySupersedeOptions>(
                                         keywords, "history_supersede", {}, {}, {"id"}));
      },
      py::arg("id"),
      "Marks calibration `id` of the history store superseded (`ccal history supersede`): by the record that "
      "replaces it (`by`, 0: none), for a `reason` (required). The record itself is never changed.");
  record_keywords<verbs::HistorySupersedeOptions>(m, "history_supersede");
  m.def(
      "history_export",
      [](const std::string& serial, const py::kwargs& keywords) {
        return verbs::history_export(serial, options_from_keywords<verbs::HistoryStoreOptions>(
                                                 keywords, "history_export", {}, {}, {"serial"}));
      },
      py::arg("serial"),
      "A serial number's history as the JSON text `ccal history export` writes (for history_import).");
  record_keywords<verbs::HistoryStoreOptions>(m, "history_export");
  m.def(
      "history_import",
      [](const py::object& file, const py::kwargs& keywords) {
        return verbs::history_import(
            path_argument(file, "history_import", "file", "the path of an exported history (str or os.PathLike)"),
            options_from_keywords<verbs::HistoryStoreOptions>(keywords, "history_import", {}, {}, {"file"}));
      },
      py::arg("file"),
      "Records the calibrations of an exported history file in the store (`ccal history import`), in one "
      "transaction: a HistoryImport.");
  record_keywords<verbs::HistoryStoreOptions>(m, "history_import");
}

// One coefficient over the calibrations, in SI.
void bind_coefficient_history(py::module_& m) {
  py::class_<verbs::CoefficientHistory>(m, "CoefficientHistory",
                                        "One coefficient over the calibrations that are not superseded.")
      .def_readonly("name", &verbs::CoefficientHistory::name, "[—]")
      .def_readonly("unit", &verbs::CoefficientHistory::unit, "the display unit, as the statements wrote it [—]")
      .def_property_readonly(
          "display_scale", [](const verbs::CoefficientHistory& h) { return display_scale_of(h.unit); },
          "SI → display unit factor [display unit per SI]")
      .def_readonly("dates", &verbs::CoefficientHistory::dates, "YYYY-MM-DD, oldest first [—]")
      .def_property_readonly(
          "values", [](const verbs::CoefficientHistory& h) { return points_in_si(h, &HistoryPoint::value); },
          "the corrected estimates [coefficient SI]")
      .def_property_readonly(
          "expanded", [](const verbs::CoefficientHistory& h) { return points_in_si(h, &HistoryPoint::expanded); },
          "U of each [coefficient SI]")
      .def_readonly("ids", &verbs::CoefficientHistory::ids, "the record of each calibration [—]")
      .def_property_readonly(
          "shared",
          [](const verbs::CoefficientHistory& h) {
            const double s = display_scale_of(h.unit);
            return Eigen::MatrixXd(h.shared / (s * s));
          },
          "C_ij: what calibrations i and j share of the coefficient's error [coefficient SI²]")
      .def_property_readonly(
          "normalised_errors",
          [](const verbs::CoefficientHistory& h) { return agreement_in_si(h.agreement, display_scale_of(h.unit)); },
          "list of NormalisedError [—]")
      .def_property_readonly(
          "drift", [](const verbs::CoefficientHistory& h) { return drift_in_si(h.drift, display_scale_of(h.unit)); },
          "DriftLine [—]")
      .def_property_readonly(
          "prediction",
          [](const verbs::CoefficientHistory& h) { return prediction_in_si(h.prediction, display_scale_of(h.unit)); },
          "DriftPrediction at `at`, or None [—]");
}

}  // namespace

void bind_history(py::module_& m) {
  bind_history_records(m);
  bind_history_trend(m);
  bind_history_exchange(m);
  bind_coefficient_history(m);
  py::class_<verbs::HistoryShowResult>(
      m, "History",
      "`ccal history show`: a serial number's calibrations; str() is the CLI's "
      "text, to_json() its JSON.")
      .def(
          "to_json", [](const verbs::HistoryShowResult& r) { return render::json(r); },
          "The report as the CLI's JSON (text).")
      .def("__str__", [](const verbs::HistoryShowResult& r) { return render::text(r); })
      .def_readonly("db", &verbs::HistoryShowResult::db, "the store [—]")
      .def_readonly("serial", &verbs::HistoryShowResult::serial, "[—]")
      .def_readonly("records", &verbs::HistoryShowResult::records,
                    "every calibration, list of HistoryRecord [—]")
      .def_readonly("coefficients", &verbs::HistoryShowResult::coefficients, "list of CoefficientHistory [—]")
      .def_property_readonly(
          "units",
          [](const verbs::HistoryShowResult& r) {
            std::vector<std::string> v;
            for (const verbs::CoefficientHistory& h : r.coefficients) v.push_back(h.unit);
            return v;
          },
          "the display unit of each coefficient, in the order of coefficients [—]")
      .def_property_readonly(
          "display_scale",
          [](const verbs::HistoryShowResult& r) {
            std::vector<double> v;
            for (const verbs::CoefficientHistory& h : r.coefficients) v.push_back(display_scale_of(h.unit));
            return v;
          },
          "SI → display unit factor per coefficient [display unit per SI]")
      .def_property_readonly(
          "setups",
          [](const verbs::HistoryShowResult& r) {
            std::vector<std::string> labels;
            for (const int s : r.setup_of) labels.push_back(verbs::setup_label(s));
            return labels;
          },
          "each record's set-up: S1, S2, … in order of first appearance, ? where not known [—]")
      .def_readonly("setup_changes", &verbs::HistoryShowResult::changes, "list of SetupChange [—]");

  m.def(
      "history",
      [](const std::string& serial, const py::kwargs& keywords) {
        return verbs::history_show(
            serial, options_from_keywords<verbs::HistoryShowOptions>(keywords, "history", {}, {}, {"serial"}));
      },
      py::arg("serial"),
      "A serial number's calibrations from the history store (`ccal history show`): per coefficient E_n of "
      "successive calibrations, the drift line and its prediction at `at`.");
  record_keywords<verbs::HistoryShowOptions>(m, "history");
  m.def(
      "history_add",
      [](const py::object& statement, const py::kwargs& keywords) {
        return verbs::history_add(path_argument(statement, "history_add", "statement",
                                                "the path of a statement's JSON file (str or os.PathLike)"),
                                  options_from_keywords<verbs::HistoryAddOptions>(keywords, "history_add", {}, {},
                                                                                  {"statement"}))
            .id;
      },
      py::arg("statement"),
      "Records a calibration statement file in the history store (`ccal history add`); returns its id.");
  record_keywords<verbs::HistoryAddOptions>(m, "history_add");
  m.def(
      "history_list",
      [](const py::kwargs& keywords) {
        return verbs::history_list(
                   options_from_keywords<verbs::HistoryStoreOptions>(keywords, "history_list", {}, {}, {}))
            .serials;
      },
      "The store's serial numbers (`ccal history list`): a list of HistorySerial.");
  record_keywords<verbs::HistoryStoreOptions>(m, "history_list");
}

}  // namespace ccal::python
