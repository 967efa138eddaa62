// The report's history section (`ccal report --history-db FILE`): the calibrations of the certificate's
// serial number from `ccal history show` (doc "history"), per coefficient a chart over time (each value with
// its U as a bar, the drift line from three calibrations on) and a table whose every number is that output's.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "ccal/history/history_store.hpp"
#include "ccal/uncertainty/history_trend.hpp"
#include "report_html.hpp"

namespace ccal::render::report_html {
namespace {

Json history_chart(const std::string& id, const Json& calibrations, const Json& c) {
  Json points = Json::array();
  for (const Json& cal : calibrations) {
    if (cal.contains("superseded") || !cal["coefficients"].contains(id)) continue;
    const Json& k = cal["coefficients"][id];
    const double v = k["value"].get<double>(), U = k["expanded_uncertainty"].get<double>();
    points.push_back({{"date", cal["date"]}, {"value", v}, {"low", v - U}, {"high", v + U}});
  }
  const std::string y_title = fmt::format("{} [{}]", id, c["unit"].get<std::string>());
  Json layers = Json::array(
      {{{"data", {{"values", points}}},
        {"mark", {{"type", "rule"}, {"color", "#4c78a8"}, {"strokeWidth", 2}}},
        {"encoding",
         {{"x",
           {{"field", "date"},
            {"type", "temporal"},
            {"title", "date of calibration"},
            // the year on every tick: calibrations a year or more apart, read across years
            {"axis", {{"format", "%Y-%m-%d"}, {"labelAngle", -30}}},
            {"scale", {{"padding", 16}}}}},  // the first and last calibration off the frame
          {"y",
           {{"field", "low"}, {"type", "quantitative"}, {"title", y_title}, {"scale", {{"zero", false}}}}},
          {"y2", {{"field", "high"}}}}}},
       {{"data", {{"values", points}}},
        {"mark", {{"type", "point"}, {"filled", true}, {"size", 60}, {"color", "#4c78a8"}}},
        {"encoding",
         {{"x", {{"field", "date"}, {"type", "temporal"}}},
          {"y", {{"field", "value"}, {"type", "quantitative"}}}}}}});
  if (c["drift"].is_object()) {  // a + b (t − t̄) at the first and the last date, t in years of 365.25 days
    const Json& d = c["drift"];
    const double origin = double(*calendar_day(c["dates"].front().get<std::string>()));
    Json line = Json::array();
    for (const Json& date : {c["dates"].front(), c["dates"].back()}) {
      const double t = (double(*calendar_day(date.get<std::string>())) - origin) / kDaysPerYear;
      line.push_back(
          {{"date", date},
           {"value", d["value_at_reference"].get<double>() +
                         d["slope_per_year"].get<double>() * (t - d["reference_years"].get<double>())}});
    }
    layers.push_back({{"data", {{"values", line}}},
                      {"mark", {{"type", "line"}, {"color", "#e45756"}, {"strokeDash", {6, 3}}}},
                      {"encoding",
                       {{"x", {{"field", "date"}, {"type", "temporal"}}},
                        {"y", {{"field", "value"}, {"type", "quantitative"}}}}}});
  }
  return {{"title", fmt::format("{} over the calibrations (bars: ± U; dashed: the drift line)", id)},
          {"width", 320},
          {"height", 200},
          {"layer", layers}};
}

std::string history_table(const Doc& doc, const std::string& id) {
  const Json& calibrations = doc.json["calibrations"];
  const Json& c = doc.json["coefficients"][id];
  std::string t = fmt::format(
      "<table class=\"history\"><caption>{0} [{1}]: its calibrations (U at each statement's k), and "
      "E<sub>n</sub> "
      "against the one before (|E<sub>n</sub>| &gt; 1: they "
      "disagree; the shared Type B of one set-up taken "
      "out)</caption>\n<tr><th>date</th><th>set-up</th><th>value</th>"
      "<th>U</th><th>k</th><th>E<sub>n</sub></th></tr>\n",
      escape(id), escape(c["unit"].get<std::string>()));
  std::size_t shown = 0;
  for (std::size_t j = 0; j < calibrations.size(); ++j) {
    const Json& cal = calibrations[j];
    if (cal.contains("superseded") || !cal["coefficients"].contains(id)) continue;
    const std::string k = fmt::format("/calibrations/{}/coefficients/{}", j, id);
    const std::string en = fmt::format("/coefficients/{}/normalised_errors/{}/en", id, shown - 1);
    t += "<tr><th>" + escape(cal["date"].get<std::string>()) + "</th>" +
         text_cell(cal["setup"].get<std::string>()) + num_cell(doc, k + "/value", 7) +
         num_cell(doc, k + "/expanded_uncertainty", 3) + num_cell(doc, k + "/coverage_factor", 3) +
         (shown == 0                                      ? std::string("<td></td>")
          : doc.json.at(Json::json_pointer(en)).is_null() ? std::string("<td>none (no uncertainty)</td>")
                                                          : num_cell(doc, en, 3)) +
         "</tr>\n";
    ++shown;
  }
  t += "</table>\n";
  if (c["drift"].is_object()) {
    const std::string d = "/coefficients/" + id + "/drift";
    t += "<p>Drift: " + num_span(doc, d + "/slope_per_year", 3) + " " + escape(c["unit"].get<std::string>()) +
         " per year, u = " + num_span(doc, d + "/std_slope", 2) +
         (c["drift"]["correlated"].get<bool>()
              ? " (generalised least squares, the shared Type B taken out; Birge ratio "
              : " (weighted straight line; Birge ratio ") +
         num_span(doc, d + "/birge_ratio", 3) + ").</p>\n";
  } else {
    t +=
        "<p>Drift: none: " + escape(c.value("drift_unavailable", std::string("from three calibrations on"))) +
        ".</p>\n";
  }
  return t;
}

// Which calibrations are on which set-up (they share its errors) and where the set-up or its tolerances
// change.
std::string setup_changes(const Json& history) {
  std::string out = "<p>Set-ups: ";
  std::vector<std::string> parts;
  for (const Json& s : history["setups"]) {
    std::vector<std::string> ids;
    for (const Json& id : s["calibrations"]) ids.push_back(fmt::format("#{}", id.get<std::int64_t>()));
    parts.push_back(fmt::format("{} (<code>{}</code>: {})", escape(s["setup"].get<std::string>()),
                                escape(s["setup_sha256"].get<std::string>().substr(0, 12)),
                                fmt::join(ids, ", ")));
  }
  std::vector<std::string> unknown;
  for (const Json& c : history["calibrations"])
    if (!c["shared_known"].get<bool>()) unknown.push_back(fmt::format("#{}", c["id"].get<std::int64_t>()));
  if (!unknown.empty())
    parts.push_back(
        fmt::format("? ({}: not known what they share; treated as independent)", fmt::join(unknown, ", ")));
  out += fmt::format(
      "{}. Calibrations on one set-up share the errors of the inputs both charge at their tolerance.",
      fmt::join(parts, "; "));
  for (const Json& c : history["setup_changes"])
    out += fmt::format(" Between {} and {}: {}.", escape(c["from_date"].get<std::string>()),
                       escape(c["to_date"].get<std::string>()),
                       c["setup_changed"].get<bool>()        ? "another set-up, nothing shared across it"
                       : c["tolerances_changed"].get<bool>() ? "the same set-up with other tolerances"
                                                             : "one of them does not know what it shares");
  return out + "</p>\n";
}

// The calibrations the section leaves out, each as superseded (by the record that replaces it, if one does)
// with its reason, as `ccal history show` lists them.
std::string superseded_ones(const Json& history) {
  std::vector<std::string> parts;
  for (const Json& c : history["calibrations"]) {
    if (!c.contains("superseded")) continue;
    const Json& s = c["superseded"];
    parts.push_back(fmt::format("#{} of {} ({}: {})", c["id"].get<std::int64_t>(),
                                escape(c["date"].get<std::string>()),
                                s["by"].is_null() ? std::string("superseded")
                                                  : fmt::format("superseded by #{}", s["by"].get<std::int64_t>()),
                                escape(s["reason"].get<std::string>())));
  }
  return parts.empty() ? std::string() : fmt::format("<p>Left out: {}.</p>\n", fmt::join(parts, "; "));
}

}  // namespace

std::string history_section(const Doc& doc) {
  std::string out = fmt::format(
      "<section id=\"history\"><h2>Calibration history of {}</h2>\n<p>Every calibration of this serial "
      "number "
      "in the history store (<code>ccal history show</code>), superseded ones left out: each value with its "
      "expanded uncertainty, E<sub>n</sub> of successive calibrations (ISO 13528) and, from three on, the "
      "drift "
      "by generalised least squares with its standard uncertainty from the stated ones, the Type B that "
      "calibrations on one set-up share taken out of both.</p>\n",
      escape(doc.json["serial"].get<std::string>()));
  out += setup_changes(doc.json) + superseded_ones(doc.json);
  for (const auto& [id, c] : doc.json["coefficients"].items())
    out += "<div class=\"pair\">\n" + chart("history-" + id, history_chart(id, doc.json["calibrations"], c)) +
           history_table(doc, id) + "</div>\n";
  return out + "</section>\n";
}

}  // namespace ccal::render::report_html
