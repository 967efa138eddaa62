#include "ccal/render/history.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "budget_parts.hpp"
#include "ccal/version.hpp"

namespace ccal::render {

namespace {

using Json = nlohmann::ordered_json;

// The first keys of both commands' JSON: which command, which ccal, which store.
Json head(const char* command, const std::string& db) {
  Json j;
  j["command"] = command;
  j["ccal_version"] = version();
  j["db"] = db;
  return j;
}

Json number_or_null(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

// E_n of calibration i against the one before (none for the first).
const NormalisedError* agreement_into(const verbs::CoefficientHistory& h, std::size_t i) {
  for (const NormalisedError& e : h.agreement)
    if (e.to == i) return &e;
  return nullptr;
}

// Which records are on which set-up, where it changes, and the records that do not know what they share.
std::string setups_text(const verbs::HistoryShowResult& r) {
  std::string out;
  for (std::size_t s = 0; s < r.setups.size(); ++s) {
    std::vector<std::string> ids;
    for (std::size_t i = 0; i < r.records.size(); ++i)
      if (r.setup_of[i] == int(s)) ids.push_back(fmt::format("#{}", r.records[i].id));
    out += fmt::format(
        "  set-up {}: {} ({}); its calibrations share the errors of the inputs both charge at "
        "their tolerance\n",
        verbs::setup_label(int(s)), r.setups[s].substr(0, 12), fmt::join(ids, ", "));
  }
  std::vector<std::string> unknown;
  for (std::size_t i = 0; i < r.records.size(); ++i)
    if (r.setup_of[i] < 0) unknown.push_back(fmt::format("#{}", r.records[i].id));
  if (!unknown.empty())
    out += fmt::format(
        "  set-up ?: {}: recorded without what it shares (schema 1, or a statement without "
        "setup_sha256); treated as independent of every other\n",
        fmt::join(unknown, ", "));
  for (const verbs::SetupChange& c : r.changes)
    out += fmt::format("  change between #{} ({}) and #{} ({}): {}\n", c.from, c.from_date, c.to, c.to_date,
                       c.setup ? "another set-up; nothing shared across it"
                       : c.tolerances
                           ? "the same set-up with other tolerances; only the inputs both charge are shared"
                           : "one of them does not know what it shares; treated as independent");
  return out;
}

// Calibration i of the history: its record, its set-up and what it shares, its supersession, its
// coefficients.
Json calibration_json(const verbs::HistoryShowResult& r, std::size_t i) {
  const HistoryRecord& rec = r.records[i];
  Json c{{"id", rec.id},
         {"date", rec.date},
         {"instrument", rec.instrument},
         {"ccal_version", rec.ccal_version},
         {"config", rec.config},
         {"statement_sha256", rec.statement_sha256},
         {"added_at", rec.added_at},
         {"certificate_number", rec.certificate_number},
         {"setup", verbs::setup_label(r.setup_of[i])},
         {"setup_sha256", rec.shared ? Json(rec.shared->setup_sha256) : Json(nullptr)},
         {"shared_known", rec.shared.has_value()}};
  if (!rec.superseded_reason.empty())
    c["superseded"] = {{"by", rec.superseded_by ? Json(*rec.superseded_by) : Json(nullptr)},
                       {"reason", rec.superseded_reason}};
  c["coefficients"] = Json::object();
  for (const HistoryCoefficient& k : rec.coefficients)
    c["coefficients"][k.name] = {{"unit", k.unit},
                                 {"value", k.value},
                                 {"expanded_uncertainty", k.expanded},
                                 {"coverage_factor", k.coverage_factor},
                                 {"coverage_probability", k.coverage_probability},
                                 {"effective_dof", number_or_null(k.effective_dof)}};
  return c;
}

// The set-ups with the calibrations on each, and the changes between successive calibrations.
void add_setups_json(Json& j, const verbs::HistoryShowResult& r) {
  j["setups"] = Json::array();
  for (std::size_t s = 0; s < r.setups.size(); ++s) {
    Json ids = Json::array();
    for (std::size_t i = 0; i < r.records.size(); ++i)
      if (r.setup_of[i] == int(s)) ids.push_back(r.records[i].id);
    j["setups"].push_back(
        {{"setup", verbs::setup_label(int(s))}, {"setup_sha256", r.setups[s]}, {"calibrations", ids}});
  }
  j["setup_changes"] = Json::array();
  for (const verbs::SetupChange& c : r.changes)
    j["setup_changes"].push_back({{"from", c.from},
                                  {"to", c.to},
                                  {"from_date", c.from_date},
                                  {"to_date", c.to_date},
                                  {"setup_changed", c.setup},
                                  {"tolerances_changed", c.tolerances},
                                  {"shared_unknown", c.unknown}});
}

// One coefficient's history: E_n of each calibration against the one before, the drift line (or why there is
// none) and the prediction at `at`, when asked for.
Json coefficient_history_json(const verbs::CoefficientHistory& h, const std::string& at) {
  Json c{{"unit", h.unit}, {"dates", h.dates}, {"calibrations", h.ids}};
  c["normalised_errors"] = Json::array();
  for (const NormalisedError& e : h.agreement)
    c["normalised_errors"].push_back({{"from", h.dates[e.from]},
                                      {"to", h.dates[e.to]},
                                      {"en", e.defined ? Json(e.value) : Json(nullptr)},
                                      {"disagree", e.disagree},
                                      {"shared_covariance", e.shared_covariance}});
  if (h.drift.available) {
    c["drift"] = {{"slope_per_year", h.drift.slope},
                  {"std_slope", h.drift.std_slope},
                  {"reference_years", h.drift.reference_years},
                  {"value_at_reference", h.drift.value},
                  {"std_value", h.drift.std_value},
                  {"chi_squared", h.drift.chi_squared},
                  {"dof", h.drift.dof},
                  {"birge_ratio", h.drift.birge_ratio},
                  {"correlated", h.drift.correlated}};
  } else {
    c["drift"] = nullptr;
    c["drift_unavailable"] = h.drift.unavailable;
  }
  if (h.prediction)
    c["prediction"] = {
        {"date", at}, {"value", h.prediction->value}, {"std_uncertainty", h.prediction->std_uncertainty}};
  return c;
}

}  // namespace

std::string text(const verbs::HistoryAddResult& r) {
  std::string out = fmt::format(
      "Recorded calibration {} of {} on {} ({} coefficients) in {}; {} calibration{} of {} "
      "there.\n",
      r.id, r.entry.serial, r.entry.date, r.entry.coefficients.size(), r.db, r.calibrations,
      r.calibrations == 1 ? "" : "s", r.entry.serial);
  for (const std::int64_t old : r.replaced)
    out += fmt::format("Calibration {} superseded: its certificate {} is replaced by certificate {}.\n", old,
                       r.entry.replaces,
                       r.entry.certificate_number.empty() ? "(unnumbered)" : r.entry.certificate_number);
  if (!r.entry.shared)
    out +=
        "The statement states no set-up fingerprint (setup_sha256): nothing known to be shared with other "
        "calibrations; treated as independent.\n";
  return out;
}

std::string json(const verbs::HistoryAddResult& r) {
  Json j = head("history add", r.db);
  j["id"] = r.id;
  j["serial"] = r.entry.serial;
  j["date"] = r.entry.date;
  j["calibrations"] = r.calibrations;
  j["certificate_number"] = r.entry.certificate_number;
  j["replaced"] = r.replaced;
  j["shared_known"] = r.entry.shared.has_value();
  return j.dump(2) + "\n";
}

std::string text(const verbs::HistoryShowResult& r) {
  std::string out = fmt::format("Calibration history of {} ({}): {} calibration{}\n\n", r.serial, r.db,
                                r.records.size(), r.records.size() == 1 ? "" : "s");
  for (std::size_t i = 0; i < r.records.size(); ++i) {
    const HistoryRecord& rec = r.records[i];
    out += fmt::format("  #{:<4} {}  set-up {:<3} {}  ccal {}  statement {}{}{}\n", rec.id, rec.date,
                       verbs::setup_label(r.setup_of[i]), rec.instrument.empty() ? "-" : rec.instrument,
                       rec.ccal_version, rec.statement_sha256.substr(0, 12),
                       rec.certificate_number.empty() ? "" : "  certificate " + rec.certificate_number,
                       rec.superseded_reason.empty() ? ""
                       : rec.superseded_by
                           ? fmt::format("  superseded by #{}: {}", *rec.superseded_by, rec.superseded_reason)
                           : "  superseded: " + rec.superseded_reason);
  }
  out += setups_text(r);
  for (const verbs::CoefficientHistory& h : r.coefficients) {
    out += fmt::format("\n{} [{}]\n  {:<10} {:>14} {:>12} {:>6} {:>8}\n", h.name, h.unit, "date", "value",
                       "U", "k", "E_n");
    for (std::size_t i = 0; i < h.points.size(); ++i) {
      const HistoryPoint& p = h.points[i];
      const NormalisedError* e = agreement_into(h, i);
      out += fmt::format("  {:<10} {:>14.7g} {:>12.3g} {:>6.3g} {:>8}{}\n", h.dates[i], p.value, p.expanded,
                         p.coverage_factor,
                         !e           ? ""
                         : e->defined ? fmt::format("{:+.2f}", e->value)
                                      : "none",
                         e && e->disagree ? "  |E_n| > 1: disagrees with the calibration before" : "");
    }
    if (!h.drift.available) {
      out += fmt::format("  drift: none: {}\n", h.drift.unavailable);
      continue;
    }
    out += fmt::format("  drift: {:+.4g} {} per year, u = {:.2g} ({}; Birge ratio {:.2f}{})\n", h.drift.slope,
                       h.unit, h.drift.std_slope,
                       h.drift.correlated ? "generalised least squares, the shared Type B taken out"
                                          : "weighted straight line",
                       h.drift.birge_ratio,
                       h.drift.birge_ratio > 1 ? ": the scatter exceeds the stated uncertainties" : "");
    if (h.prediction)
      out += fmt::format("  predicted on {}: {:.7g} {}, u = {:.2g} (U = {:.2g} for k = 2)\n", r.at,
                         h.prediction->value, h.unit, h.prediction->std_uncertainty,
                         2 * h.prediction->std_uncertainty);
  }
  return out;
}

std::string json(const verbs::HistoryShowResult& r) {
  Json j = head("history show", r.db);
  j["serial"] = r.serial;
  j["calibrations"] = Json::array();
  for (std::size_t i = 0; i < r.records.size(); ++i) j["calibrations"].push_back(calibration_json(r, i));
  add_setups_json(j, r);
  j["coefficients"] = Json::object();
  for (const verbs::CoefficientHistory& h : r.coefficients)
    j["coefficients"][h.name] = coefficient_history_json(h, r.at);
  return j.dump(2) + "\n";
}

std::string csv(const verbs::HistoryShowResult& r) {
  std::string out =
      "serial,coefficient,unit,date,value,expanded_uncertainty,coverage_factor,en_to_previous,id,setup,"
      "shared_covariance_to_previous\n";
  for (const verbs::CoefficientHistory& h : r.coefficients)
    for (std::size_t i = 0; i < h.points.size(); ++i) {
      const NormalisedError* e = agreement_into(h, i);
      const auto record = std::find_if(r.records.begin(), r.records.end(),
                                       [&](const HistoryRecord& x) { return x.id == h.ids[i]; });
      const int setup = r.setup_of[std::size_t(record - r.records.begin())];
      out +=
          fmt::format("\"{}\",{},\"{}\",{},{:.17g},{:.17g},{:.17g},{},{},{},{}\n", r.serial, h.name, h.unit,
                      h.dates[i], h.points[i].value, h.points[i].expanded, h.points[i].coverage_factor,
                      e && e->defined ? fmt::format("{:.17g}", e->value) : "", h.ids[i],
                      verbs::setup_label(setup), e ? fmt::format("{:.17g}", e->shared_covariance) : "");
    }
  return out;
}

std::string text(const verbs::HistoryListResult& r) {
  if (r.serials.empty()) return fmt::format("No calibration recorded in {}.\n", r.db);
  std::string out = fmt::format("Serial numbers in {}:\n  {:<24} {:>12} {:>10}  {}\n", r.db, "serial",
                                "calibrations", "superseded", "last");
  for (const HistoryStore::SerialSummary& s : r.serials)
    out += fmt::format("  {:<24} {:>12} {:>10}  {}\n", s.serial, s.calibrations, s.superseded, s.last_date);
  return out;
}

std::string json(const verbs::HistoryListResult& r) {
  Json j = head("history list", r.db);
  j["serials"] = Json::array();
  for (const HistoryStore::SerialSummary& s : r.serials)
    j["serials"].push_back({{"serial", s.serial},
                            {"calibrations", s.calibrations},
                            {"superseded", s.superseded},
                            {"last_date", s.last_date}});
  return j.dump(2) + "\n";
}

std::string csv(const verbs::HistoryListResult& r) {
  std::string out = "serial,calibrations,superseded,last_date\n";
  for (const HistoryStore::SerialSummary& s : r.serials)
    out += fmt::format("\"{}\",{},{},{}\n", s.serial, s.calibrations, s.superseded, s.last_date);
  return out;
}

}  // namespace ccal::render
