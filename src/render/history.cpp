#include "ccal/render/history.hpp"

#include <fmt/format.h>

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

}  // namespace

std::string text(const verbs::HistoryAddResult& r) {
  return fmt::format(
      "Recorded calibration {} of {} on {} ({} coefficients) in {}; {} calibration{} of {} "
      "there.\n",
      r.id, r.entry.serial, r.entry.date, r.entry.coefficients.size(), r.db, r.calibrations,
      r.calibrations == 1 ? "" : "s", r.entry.serial);
}

std::string json(const verbs::HistoryAddResult& r) {
  Json j = head("history add", r.db);
  j["id"] = r.id;
  j["serial"] = r.entry.serial;
  j["date"] = r.entry.date;
  j["calibrations"] = r.calibrations;
  return j.dump(2) + "\n";
}

std::string text(const verbs::HistoryShowResult& r) {
  std::string out = fmt::format("Calibration history of {} ({}): {} calibration{}\n\n", r.serial, r.db,
                                r.records.size(), r.records.size() == 1 ? "" : "s");
  for (const HistoryRecord& rec : r.records)
    out += fmt::format("  #{:<4} {}  {}  ccal {}  statement {}{}\n", rec.id, rec.date,
                       rec.instrument.empty() ? "-" : rec.instrument, rec.ccal_version,
                       rec.statement_sha256.substr(0, 12),
                       rec.superseded_reason.empty() ? ""
                       : rec.superseded_by
                           ? fmt::format("  superseded by #{}: {}", *rec.superseded_by, rec.superseded_reason)
                           : "  superseded: " + rec.superseded_reason);
  for (const verbs::CoefficientHistory& h : r.coefficients) {
    out += fmt::format("\n{} [{}]\n  {:<10} {:>14} {:>12} {:>6} {:>8}\n", h.name, h.unit, "date", "value",
                       "U", "k", "E_n");
    for (std::size_t i = 0; i < h.points.size(); ++i) {
      const HistoryPoint& p = h.points[i];
      const NormalisedError* e = agreement_into(h, i);
      out += fmt::format("  {:<10} {:>14.7g} {:>12.3g} {:>6.3g} {:>8}{}\n", h.dates[i], p.value, p.expanded,
                         p.coverage_factor, !e ? "" : e->defined ? fmt::format("{:+.2f}", e->value) : "none",
                         e && e->disagree ? "  |E_n| > 1: disagrees with the calibration before" : "");
    }
    if (!h.drift.available) {
      out += "  drift: needs three calibrations at two dates at least\n";
      continue;
    }
    out += fmt::format(
        "  drift: {:+.4g} {} per year, u = {:.2g} (weighted straight line; Birge ratio {:.2f}{})\n",
        h.drift.slope, h.unit, h.drift.std_slope, h.drift.birge_ratio,
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
  for (const HistoryRecord& rec : r.records) {
    Json c{{"id", rec.id},
           {"date", rec.date},
           {"instrument", rec.instrument},
           {"ccal_version", rec.ccal_version},
           {"config", rec.config},
           {"statement_sha256", rec.statement_sha256},
           {"added_at", rec.added_at}};
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
    j["calibrations"].push_back(c);
  }
  j["coefficients"] = Json::object();
  for (const verbs::CoefficientHistory& h : r.coefficients) {
    Json c{{"unit", h.unit}, {"dates", h.dates}};
    c["normalised_errors"] = Json::array();
    for (const NormalisedError& e : h.agreement)
      c["normalised_errors"].push_back({{"from", h.dates[e.from]},
                                        {"to", h.dates[e.to]},
                                        {"en", e.defined ? Json(e.value) : Json(nullptr)},
                                        {"disagree", e.disagree}});
    if (h.drift.available) {
      c["drift"] = {{"slope_per_year", h.drift.slope},
                    {"std_slope", h.drift.std_slope},
                    {"reference_years", h.drift.reference_years},
                    {"value_at_reference", h.drift.value},
                    {"std_value", h.drift.std_value},
                    {"chi_squared", h.drift.chi_squared},
                    {"dof", h.drift.dof},
                    {"birge_ratio", h.drift.birge_ratio}};
    } else {
      c["drift"] = nullptr;
    }
    if (h.prediction)
      c["prediction"] = {
          {"date", r.at}, {"value", h.prediction->value}, {"std_uncertainty", h.prediction->std_uncertainty}};
    j["coefficients"][h.name] = c;
  }
  return j.dump(2) + "\n";
}

std::string csv(const verbs::HistoryShowResult& r) {
  std::string out =
      "serial,coefficient,unit,date,value,expanded_uncertainty,coverage_factor,en_to_previous\n";
  for (const verbs::CoefficientHistory& h : r.coefficients)
    for (std::size_t i = 0; i < h.points.size(); ++i) {
      const NormalisedError* e = agreement_into(h, i);
      out += fmt::format("\"{}\",{},\"{}\",{},{:.17g},{:.17g},{:.17g},{}\n", r.serial, h.name, h.unit,
                         h.dates[i], h.points[i].value, h.points[i].expanded, h.points[i].coverage_factor,
                         e && e->defined ? fmt::format("{:.17g}", e->value) : "");
    }
  return out;
}

}  // namespace ccal::render
