// `ccal history` from Python: an instrument's calibrations read from the store (History, history()), a
// statement recorded (history_add()), the store's serials (history_list()), a record superseded
// (history_supersede()), a serial's history exported and an exported file imported (history_export(),
// history_import()); display() and to_frame() are added in Python (python/ccal/_results.py).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <string>

#include "bindings.hpp"
#include "ccal/render/history.hpp"
#include "ccal/verbs/history.hpp"
#include "option_keywords.hpp"

namespace ccal::python {

namespace {

// The store's records, its serial numbers and the set-up changes between records.
void bind_history_records(py::module_& m) {
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
                    "C₁₂, shared by the two [unit²]")
      .def_readonly("disagree", &NormalisedError::disagree, "|E_n| > 1 [—]");
  py::class_<DriftLine>(m, "DriftLine", "The weighted straight line through a coefficient's calibrations.")
      .def_readonly("available", &DriftLine::available, "three calibrations at two dates at least [—]")
      .def_readonly("unavailable", &DriftLine::unavailable, "why not, where not available [—]")
      .def_readonly("correlated", &DriftLine::correlated,
                    "calibrations sharing errors were fitted with them [—]")
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

}  // namespace

void bind_history(py::module_& m) {
  bind_history_records(m);
  bind_history_trend(m);
  bind_history_exchange(m);
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
      .def_readonly("ids", &verbs::CoefficientHistory::ids, "the record of each calibration [—]")
      .def_readonly("shared", &verbs::CoefficientHistory::shared,
                    "C_ij: what calibrations i and j share of the coefficient's error [unit²]")
      .def_readonly("normalised_errors", &verbs::CoefficientHistory::agreement, "list of NormalisedError [—]")
      .def_readonly("drift", &verbs::CoefficientHistory::drift, "DriftLine [—]")
      .def_readonly("prediction", &verbs::CoefficientHistory::prediction,
                    "DriftPrediction at `at`, or None [—]");
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
