// The report's design section (`ccal report --design`): the configured plan against the designed one (u and U
// per coefficient, full budget and tolerances alone), both plans' runs side by side, the mechanism, the
// leading sources before and after, and a chart of the ratios of U. The numbers are read from the JSON of
// `ccal design`, of `ccal budget` of each plan and of `ccal force --run k` for the configured runs.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "ccal/core/constants.hpp"
#include "report_html.hpp"

namespace ccal::render::report_html {
namespace {

std::string comparison_table(const Doc& doc) {
  std::string t =
      "<table class=\"design-coefficients\"><caption>Configured against designed plan, full budget (k as "
      "<code>ccal budget</code>) and the tolerances alone (U<sub>tol</sub>; * counted by the "
      "objective)</caption>\n"
      "<tr><th>coefficient</th><th>unit</th><th>u configured</th><th>u designed</th><th>U configured</th>"
      "<th>U designed</th><th>ratio</th><th>U<sub>tol</sub> configured</th><th>U<sub>tol</sub> designed</th>"
      "<th>ratio</th></tr>\n";
  for (const auto& [id, c] : doc.json["coefficients"].items()) {
    const std::string p = "/coefficients/" + id;
    t += "<tr>" + text_cell(id + (c["weight"].get<double>() > 0 ? " *" : "")) +
         text_cell(c["unit"].get<std::string>()) + num_cell(doc, p + "/configured_std_uncertainty") +
         num_cell(doc, p + "/designed_std_uncertainty") + num_cell(doc, p + "/configured_expanded") +
         num_cell(doc, p + "/designed_expanded") +
         ratio_cell(doc, p + "/designed_expanded", p + "/configured_expanded") +
         num_cell(doc, p + "/configured_tolerance_expanded") +
         num_cell(doc, p + "/designed_tolerance_expanded") +
         ratio_cell(doc, p + "/designed_tolerance_expanded", p + "/configured_tolerance_expanded") +
         "</tr>\n";
  }
  return t + "</table>\n";
}

// Bars of U designed / U configured per coefficient on a log axis, from 1 (no change) to the ratio, for the
// full budget and the tolerances alone, with the rule at 1.
Json ratio_spec(const Json& design) {
  Json values = Json::array();
  for (const auto& [id, c] : design["coefficients"].items()) {
    values.push_back(
        {{"coefficient", id},
         {"budget", "full budget"},
         {"ratio", c["designed_expanded"].get<double>() / c["configured_expanded"].get<double>()}});
    values.push_back({{"coefficient", id},
                      {"budget", "tolerances alone"},
                      {"ratio", c["designed_tolerance_expanded"].get<double>() /
                                    c["configured_tolerance_expanded"].get<double>()}});
  }
  return {
      {"title", "U of the designed plan / U of the configured plan"},
      {"width", 220},
      {"height", 220},
      {"layer", Json::array({{{"data", {{"values", values}}},
                              {"mark", "bar"},
                              {"encoding",
                               {{"x", {{"field", "coefficient"}, {"type", "nominal"}, {"title", nullptr}}},
                                {"xOffset", {{"field", "budget"}, {"type", "nominal"}}},
                                {"y",
                                 {{"field", "ratio"},
                                  {"type", "quantitative"},
                                  {"scale", {{"type", "log"}}},
                                  {"title", "U designed / U configured (log scale)"}}},
                                {"y2", {{"datum", 1}}},  // from 1 (no change; a log axis has no 0)
                                {"color",
                                 {{"field", "budget"},
                                  {"type", "nominal"},
                                  {"title", nullptr},
                                  {"scale", {{"range", {"#4c78a8", "#f58518"}}}},
                                  {"legend", {{"orient", "bottom"}}}}},
                                {"tooltip", Json::array({{{"field", "coefficient"}},
                                                         {{"field", "budget"}},
                                                         {{"field", "ratio"}, {"format", ".3g"}}})}}}},
                             {{"data", {{"values", Json::array({{{"y", 1.0}}})}}},
                              {"mark", {{"type", "rule"}, {"strokeDash", {4, 3}}, {"color", "#555"}}},
                              {"encoding", {{"y", {{"field", "y"}, {"type", "quantitative"}}}}}}})}};
}

// One run of a plan: the output it is read from and where ("/run" of `ccal force`, "/designed_plan/k" of
// `ccal design`).
struct PlanRow {
  const Doc& doc;
  std::string at;
  const Json& run() const { return doc.json.at(Json::json_pointer(at)); }
};

// The runs in the units `ccal design` prints them (g, s, degrees); the mounting and the platform control as
// columns when they differ between runs, else once in the caption.
std::string plan_table(const std::string& caption, const std::vector<PlanRow>& rows) {
  bool same_mounting = true, same_platform = true;
  for (const PlanRow& r : rows) {
    same_mounting = same_mounting && r.run()["mounting"] == rows.front().run()["mounting"];
    same_platform = same_platform && r.run()["platform"] == rows.front().run()["platform"];
  }
  std::string note;
  if (!rows.empty() && same_mounting) note += "mounting " + rows.front().run()["mounting"].get<std::string>();
  if (!rows.empty() && same_platform)
    note += (note.empty() ? "" : ", ") + rows.front().run()["platform"].get<std::string>() + " platform";
  std::string t = "<table class=\"design-plan\"><caption>" + escape(caption) +
                  (note.empty() ? "" : " (every run: " + escape(note) + ")") +
                  "</caption>\n<tr><th>run</th><th>g-level [g]</th><th>duration [s]</th><th>φ<sub>0</sub> "
                  "[deg]</th><th>arm azimuth [deg]</th>" +
                  (same_mounting ? "" : "<th>mounting</th>") + (same_platform ? "" : "<th>platform</th>") +
                  "</tr>\n";
  for (const PlanRow& r : rows) {
    t += "<tr>" + text_cell(r.run()["name"].get<std::string>()) + num_cell(r.doc, r.at + "/g_level_g", 6) +
         num_cell(r.doc, r.at + "/duration_s", 7) +
         num_cell(r.doc, r.at + "/initial_phase_rad", 5, constants::degrees_per_rad) +
         num_cell(r.doc, r.at + "/arm_azimuth_rad", 5, constants::degrees_per_rad) +
         (same_mounting ? "" : text_cell(r.run()["mounting"].get<std::string>())) +
         (same_platform ? "" : text_cell(r.run()["platform"].get<std::string>())) + "</tr>\n";
  }
  return t + "</table>\n";
}

std::string plans(const DesignDocs& d) {
  std::vector<PlanRow> configured, designed;
  for (const Doc& run : d.configured_runs) configured.push_back({run, "/run"});
  for (std::size_t k = 0; k < d.design.json["designed_plan"].size(); ++k)
    designed.push_back({d.design, fmt::format("/designed_plan/{}", k)});
  return plan_table("Configured plan", configured) + plan_table("Designed plan", designed);
}

// The run sheet of `ccal design` (its "run_sheet"): each run in the order made, in g, rpm, s and degrees, the
// phase the plan sets named, and the U expected if run as written.
std::string run_sheet_table(const Doc& doc) {
  const Json& sheet = doc.json["run_sheet"];
  std::string t =
      "<table class=\"run-sheet\"><caption>Run sheet: the designed plan as the operator runs it (each run "
      "starts "
      "its record as the arm passes its start azimuth, from East counter-clockwise, with the platform at its "
      "start phase, the input axis from the outward radial)</caption>\n"
      "<tr><th>#</th><th>run</th><th>g-level [g]</th><th>main axis [rpm]</th><th>platform [rpm]</th>"
      "<th>duration [s]</th><th>turns</th><th>arm start az. [deg]</th><th>start phase [deg]</th>"
      "<th>stop phase [deg]</th><th>phase set</th><th>mounting</th></tr>\n";
  for (std::size_t k = 0; k < sheet["runs"].size(); ++k) {
    const Json& line = sheet["runs"][k];
    const std::string p = fmt::format("/run_sheet/runs/{}", k);
    const bool stop = line["sets"] == "stop_phase";
    t += "<tr><th>" + std::to_string(k + 1) + "</th>" + text_cell(line["run"].get<std::string>()) +
         num_cell(doc, p + "/g_level_g", 6) + num_cell(doc, p + "/main_speed_rpm", 6) +
         (line["platform"] == "fixed" ? text_cell("fixed") : num_cell(doc, p + "/platform_speed_rpm", 6)) +
         num_cell(doc, p + "/duration_s", 7) + num_cell(doc, p + "/turns", 6) +
         num_cell(doc, p + "/arm_azimuth_deg", 4) + num_cell(doc, p + "/start_phase_deg", 4) +
         num_cell(doc, p + "/stop_phase_deg", 4) + text_cell(stop ? "stop" : "start") +
         text_cell(line["mounting"].get<std::string>()) + "</tr>\n";
  }
  t += "</table>\n<p class=\"run-sheet-expected\">Expected if run as written (the full budget of the sheet's "
       "values, k = " +
       num_span(doc, "/run_sheet/coverage_factor", 3) + "):";
  for (const auto& [id, u] : sheet["expected_if_run_as_written"].items())
    t += fmt::format(" U({}) = ", escape(id)) +
         num_span(doc, "/run_sheet/expected_if_run_as_written/" + id + "/expanded", 3) + " " +
         escape(u["unit"].get<std::string>()) + ";";
  t.back() = '.';
  return t + "</p>\n";
}

// The indices of a budget's sources by |effect| on one coefficient, largest first, at most n.
std::vector<std::size_t> leading(const Json& budget, const std::string& id, std::size_t n) {
  std::vector<std::size_t> order(budget["sources"].size());
  std::iota(order.begin(), order.end(), 0);
  auto size = [&](std::size_t s) { return std::abs(budget["sources"][s]["effect"][id].get<double>()); };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return size(a) > size(b); });
  order.resize(std::min(n, order.size()));
  return order;
}

std::string leading_table(const DesignDocs& d, const std::string& id, const std::string& unit) {
  const auto a = leading(d.before.json, id, 5), b = leading(d.after.json, id, 5);
  std::string t = fmt::format(
      "<table class=\"design-leading\" data-coefficient=\"{0}\"><caption>{0} [{1}]: leading sources, "
      "configured and designed plan</caption>\n<tr><th>rank</th><th>configured: source</th><th>1σ effect</th>"
      "<th>share [%]</th><th>designed: source</th><th>1σ effect</th><th>share [%]</th></tr>\n",
      escape(id), escape(unit));
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    const std::string p0 = fmt::format("/sources/{}", a[i]), p1 = fmt::format("/sources/{}", b[i]);
    t += "<tr><th>" + std::to_string(i + 1) + "</th>" +
         text_cell(d.before.json["sources"][a[i]]["id"].get<std::string>()) +
         num_cell(d.before, p0 + "/effect/" + id, 3) + num_cell(d.before, p0 + "/share/" + id, 3, 100) +
         text_cell(d.after.json["sources"][b[i]]["id"].get<std::string>()) +
         num_cell(d.after, p1 + "/effect/" + id, 3) + num_cell(d.after, p1 + "/share/" + id, 3, 100) +
         "</tr>\n";
  }
  return t + "</table>\n";
}

std::string list_text(const Json& items) {
  std::string out;
  for (const Json& s : items) out += (out.empty() ? "" : "; ") + escape(s.get<std::string>());
  return out.empty() ? "none" : out;
}

}  // namespace

std::string design_section(const DesignDocs& d) {
  const Json& j = d.design.json;
  std::string out = fmt::format(
      "<section id=\"design\"><h2>Test-plan design: configured against designed</h2>\n<p>The test plan "
      "within the configuration's design space ([design]) under which the centrifuge's tolerances, the "
      "drives' rate noise and the instrument's noise cost the chosen coefficients least (objective {}), "
      "re-scored by the full budget. Free: {}. Kept: {}. Total test time at most {} s; {} candidate runs. "
      "Objective: {} for the configured plan, {} for the designed one. From <code>ccal design</code>; the "
      "budgets of both plans from <code>ccal budget</code> of the configuration and of the plan that "
      "<code>ccal design --plan-out</code> writes ({} mode).</p>\n",
      escape(j["objective"].get<std::string>()), list_text(j["free"]), list_text(j["kept"]),
      num_span(d.design, "/total_time_limit_s", 6), num_span(d.design, "/candidates", 12),
      num_span(d.design, "/objective_value/configured", 4),
      num_span(d.design, "/objective_value/designed", 4), escape(d.after.json["mode"].get<std::string>()));
  out += "<div class=\"pair\">\n" + chart("design-ratio", ratio_spec(j)) + comparison_table(d.design) +
         "</div>\n";
  out += "<div class=\"pair\">\n" + plans(d) + "</div>\n" + run_sheet_table(d.design);
  const std::string mechanism = j["mechanism"].get<std::string>();
  if (!mechanism.empty()) {
    out += "<h3>Mechanism</h3>\n";
    std::size_t start = 0;
    while (start < mechanism.size()) {
      const std::size_t end = std::min(mechanism.find('\n', start), mechanism.size());
      if (end > start)
        out += "<p class=\"mechanism\">" + escape(mechanism.substr(start, end - start)) + "</p>\n";
      start = end + 1;
    }
  }
  out += "<div class=\"pair\">\n";
  for (const auto& [id, c] : j["coefficients"].items())
    if (c["weight"].get<double>() > 0) out += leading_table(d, id, c["unit"].get<std::string>());
  return out + "</div>\n</section>\n";
}

}  // namespace ccal::render::report_html
