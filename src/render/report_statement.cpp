// The report's calibration statement section (`ccal report --observations`): per coefficient the estimate,
// the correction for known errors, the Type A part with its degrees of freedom, the Type B part, u_c, ν_eff,
// k, U and the interval, a reading guide, and a chart of the Type A / Type B split of u_c². Every number is
// read from the JSON of `ccal identify OBS.csv --statement --config CONFIG` (render::json of the IdentifyResult).
#include <fmt/format.h>

#include <algorithm>

#include "report_html.hpp"

namespace ccal::render::report_html {
namespace {

// A number of degrees of freedom, or ∞ where the JSON has null (a part known exactly).
std::string dof_cell(const Doc& doc, const std::string& pointer) {
  return doc.json.at(Json::json_pointer(pointer)).is_null() ? text_cell("∞") : num_cell(doc, pointer, 4);
}

std::string statement_table(const Doc& doc) {
  std::string t =
      "<table class=\"statement\"><caption>Calibration statement per identified coefficient (JCGM 100 "
      "§7)</caption>\n<tr><th>coefficient</th><th>unit</th><th>estimate</th><th>correction</th>"
      "<th>corrected estimate</th><th>u<sub>A</sub> (fit)</th><th>ν<sub>A</sub></th>"
      "<th>u<sub>B</sub> (budget)</th><th>u<sub>c</sub></th><th>ν<sub>eff</sub></th><th>k</th><th>U</th>"
      "<th colspan=\"2\">interval</th></tr>\n";
  for (const auto& [id, c] : doc.json["statement"]["coefficients"].items()) {
    const std::string p = "/statement/coefficients/" + id;
    t += "<tr>" + text_cell(id) + text_cell(c["unit"].get<std::string>()) +
         num_cell(doc, p + "/estimate", 8) + num_cell(doc, p + "/correction", 4) +
         num_cell(doc, p + "/corrected_estimate", 8) + num_cell(doc, p + "/type_a/u") +
         dof_cell(doc, p + "/type_a/dof") + num_cell(doc, p + "/type_b/u") +
         num_cell(doc, p + "/combined_standard_uncertainty") + dof_cell(doc, p + "/effective_dof") +
         num_cell(doc, p + "/coverage_factor", 4) + num_cell(doc, p + "/expanded_uncertainty", 3) +
         num_cell(doc, p + "/interval/0", 8) + num_cell(doc, p + "/interval/1", 8) + "</tr>\n";
  }
  return t + "</table>\n";
}

// Per coefficient one bar of 100 % of u_c², stacked: Type A's share u_A²/u_c² and Type B's u_B²/u_c².
Json split_spec(const Json& statement) {
  Json values = Json::array();
  for (const auto& [id, c] : statement["coefficients"].items()) {
    const double a = c["type_a"]["u"].get<double>(), b = c["type_b"]["u"].get<double>();
    const double total = a * a + b * b;
    if (!(total > 0)) continue;  // nothing to split
    values.push_back({{"coefficient", id}, {"part", "Type A (fit)"}, {"share", 100 * a * a / total}});
    values.push_back({{"coefficient", id}, {"part", "Type B (budget)"}, {"share", 100 * b * b / total}});
  }
  const double rows = double(statement["coefficients"].size());
  return {{"title", "Type A and Type B shares of u_c²"},
          {"width", 300},
          {"height", std::max(60.0, 28 * rows)},
          {"data", {{"values", values}}},
          {"mark", "bar"},
          {"encoding",
           {{"y", {{"field", "coefficient"}, {"type", "nominal"}, {"sort", nullptr}, {"title", nullptr}}},
            {"x",
             {{"field", "share"},
              {"type", "quantitative"},
              {"stack", "zero"},
              {"scale", {{"domain", {0, 100}}}},
              {"title", "share of u_c² [%]"}}},
            {"color",
             {{"field", "part"},
              {"type", "nominal"},
              {"title", nullptr},
              {"scale", {{"domain", {"Type A (fit)", "Type B (budget)"}}, {"range", {"#f58518", "#4c78a8"}}}},
              {"legend", {{"orient", "bottom"}}}}},
            {"tooltip", Json::array({{{"field", "coefficient"}},
                                     {{"field", "part"}},
                                     {{"field", "share"}, {"format", ".4g"}}})}}}};
}

std::string known_errors_text(const Json& st) {
  if (st["known_errors"].get<int>() == 0)
    return "The configuration has no known <code>[errors]</code>, so every correction is 0.";
  return st["compensated"].get<bool>()
             ? "The model computes the regressors with the configuration's known <code>[errors]</code> "
               "(compensated), so no correction is needed."
             : "The correction is minus the shift the configuration's known <code>[errors]</code> give the "
               "identified coefficients when the model leaves them out (the bias row of <code>ccal "
               "budget</code>).";
}

}  // namespace

std::string statement_section(const Doc& doc) {
  const Json& st = doc.json["statement"];
  std::string out = fmt::format(
      "<section id=\"statement\"><h2>Calibration statement</h2>\n<p>The observations <code>{}</code> ({} "
      "runs) identified as <code>ccal identify</code> does, with the uncertainty the laboratory reports for "
      "each coefficient (JCGM 100 §7 and Annex G, docs/model.md §10.5). <b>Type A</b> is evaluated from "
      "these "
      "data: the fit's standard error, from the scatter of the run means about the model, with ν<sub>A</sub> "
      "= runs − free terms degrees of freedom (∞ for a weighted fit, whose σ are taken as known); the "
      "drives' "
      "rate noise is in that scatter. <b>Type B</b> is the propagation of the configuration's "
      "<code>[tolerances]</code> ({} mode, the budget above without the rate noise, which would otherwise be "
      "counted twice), known exactly (ν = ∞). They are independent, so u<sub>c</sub>² = u<sub>A</sub>² + "
      "u<sub>B</sub>²; ν<sub>eff</sub> by Welch–Satterthwaite; k the Student's t quantile for "
      "⌊ν<sub>eff</sub>⌋ at p = {}; U = k u<sub>c</sub>; the interval is the corrected estimate ∓ U. {} "
      "Units: the coefficients' (the instrument's output unit per gⁿ).</p>\n",
      escape(doc.json["file"].get<std::string>()), num_span(doc, "/rows", 6),
      escape(st["mode"].get<std::string>()), num_span(doc, "/statement/coverage_probability", 4),
      known_errors_text(st));
  out +=
      "<div class=\"pair\">\n" + chart("statement-split", split_spec(st)) + statement_table(doc) + "</div>\n";
  return out + "</section>\n";
}

}  // namespace ccal::render::report_html
