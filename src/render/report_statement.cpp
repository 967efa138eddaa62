// The report's calibration statement section (`ccal report --observations`): per coefficient the estimate,
// the correction for known errors, the Type A part with its degrees of freedom, the Type B part, u_c, ν_eff,
// k, U and the interval, a reading guide, and a chart of the Type A / Type B split of u_c². Every number is
// read from the JSON of `ccal identify OBS.csv --statement --config CONFIG` (render::json of the IdentifyResult).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "ccal/uncertainty/budget.hpp"
#include "certificate_parts.hpp"
#include "report_html.hpp"

namespace ccal::render::report_html {
namespace {

// A number of degrees of freedom, or ∞ where the JSON has null (a part known exactly).
std::string statement_dof_cell(const Doc& doc, const std::string& pointer) {
  return doc.json.at(Json::json_pointer(pointer)).is_null() ? text_cell("∞") : num_cell(doc, pointer, 4);
}

std::string statement_table(const Doc& doc) {
  std::string t =
      "<table class=\"statement\"><caption>Calibration statement per identified coefficient (JCGM 100 "
      "§7)</caption>\n<tr><th>coefficient</th><th>unit</th><th>estimate</th><th>correction</th>"
      "<th>corrected estimate</th><th>u<sub>A</sub> (noise)</th><th>ν<sub>A</sub></th>"
      "<th>u<sub>B</sub> (inputs)</th><th>u<sub>c</sub></th><th>ν<sub>eff</sub></th><th>k</th><th>U</th>"
      "<th colspan=\"2\">interval</th></tr>\n";
  for (const auto& [id, c] : doc.json["statement"]["coefficients"].items()) {
    const std::string p = "/statement/coefficients/" + id;
    t += "<tr>" + text_cell(id) + text_cell(c["unit"].get<std::string>()) +
         num_cell(doc, p + "/estimate", 8) + num_cell(doc, p + "/correction", 4) +
         num_cell(doc, p + "/corrected_estimate", 8) + num_cell(doc, p + "/type_a/u") +
         statement_dof_cell(doc, p + "/type_a/dof") + num_cell(doc, p + "/type_b/u") +
         num_cell(doc, p + "/combined_standard_uncertainty") + statement_dof_cell(doc, p + "/effective_dof") +
         num_cell(doc, p + "/coverage_factor", 4) + num_cell(doc, p + "/expanded_uncertainty", 3) +
         num_cell(doc, p + "/interval/0", 6) + num_cell(doc, p + "/interval/1", 6) + "</tr>\n";
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
    values.push_back({{"coefficient", id}, {"part", "Type A (noise)"}, {"share", 100 * a * a / total}});
    values.push_back({{"coefficient", id}, {"part", "Type B (inputs)"}, {"share", 100 * b * b / total}});
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
              {"scale", {{"domain", {"Type A (noise)", "Type B (inputs)"}}, {"range", {"#f58518", "#4c78a8"}}}},
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

// The result as a certificate states it: per coefficient the rounded value ± U (JCGM 100 §7.2.6), unit, k, p,
// ν_eff and the interval; then a note for each term whose interval holds 0.
std::string result_table(const Doc& doc) {
  const Json& st = doc.json["statement"];
  std::string t =
      "<table class=\"result\"><caption>Result: U = k u<sub>c</sub> to two significant digits, the value to the "
      "same decimal place (JCGM 100 §7.2.6); where the method is Monte Carlo (JCGM 101), the interval is its "
      "ends</caption>\n<tr><th>coefficient</th><th>value</th><th>± U</th>"
      "<th>unit</th><th>k</th><th>p [%]</th><th>ν<sub>eff</sub></th><th colspan=\"2\">interval</th>"
      "<th>method</th></tr>\n";
  std::string notes;
  for (const auto& [id, c] : st["coefficients"].items()) {
    const std::string p = "/statement/coefficients/" + id;
    // The Monte Carlo's interval is not centred on the value: its ends are the statement, not ± U and k.
    const bool mc = c["interval_method"] == "monte_carlo";
    t += "<tr>" + text_cell(id) + text_num_cell(doc, p + "/rounded/estimate") +
         (mc ? text_cell("–") : text_num_cell(doc, p + "/rounded/expanded_uncertainty")) +
         text_cell(c["unit"].get<std::string>()) +
         (mc ? text_cell("–") : num_cell(doc, p + "/coverage_factor", 4)) +
         num_cell(doc, "/statement/coverage_probability", 4, 100) +
         statement_dof_cell(doc, p + "/effective_dof") + text_num_cell(doc, p + "/rounded/interval/0") +
         text_num_cell(doc, p + "/rounded/interval/1") + text_cell(mc ? "Monte Carlo" : "Student t") +
         "</tr>\n";
    if (!c["significant"].get<bool>())
      notes += fmt::format(
          "<li><b>{0} is not resolved from zero</b>: its interval holds 0 (|{0}| ≤ U). A plan with higher or "
          "more g-levels lowers U({0}); <code>ccal design CONFIG --target {0}=U</code> finds one for the U "
          "needed.</li>\n",
          escape(id));
  }
  t += "</table>\n";
  return notes.empty() ? t : t + "<ul class=\"advice\">\n" + notes + "</ul>\n";
}

// The correlation of the corrected estimates (Type A + Type B); the covariance is in the JSON.
std::string correlation_table(const Doc& doc) {
  const Json& order = doc.json["statement"]["covariance"]["order"];
  std::string t = "<table class=\"statement-correlation\"><caption>Correlation of the corrected estimates (Type "
                  "A + Type B)</caption>\n<tr><th></th>";
  for (const auto& id : order) t += "<th>" + escape(id.get<std::string>()) + "</th>";
  t += "</tr>\n";
  for (std::size_t i = 0; i < order.size(); ++i) {
    t += "<tr>" + text_cell(order[i].get<std::string>());
    for (std::size_t j = 0; j < order.size(); ++j)
      t += num_cell(doc, fmt::format("/statement/covariance/correlation/{}/{}", i, j), 4);
    t += "</tr>\n";
  }
  return t + "</table>\n";
}

// The modelled output of each run with its uncertainty from the covariance.
std::string modelled_output_table(const Doc& doc) {
  const Json& outputs = doc.json["statement"]["modelled_output"];
  if (outputs.empty()) return "";
  std::string t = fmt::format(
      "<table class=\"statement-output\"><caption>Modelled output of each run, ŷ = hᵀ(K̂ + b), with u(ŷ)² = "
      "hᵀ C h from the covariance C [{}]</caption>\n<tr><th>run</th><th>g-level [g]</th><th>ŷ</th>"
      "<th>u<sub>c</sub></th><th>ν<sub>eff</sub></th><th>k</th><th>U</th></tr>\n",
      escape(outputs[0]["unit"].get<std::string>()));
  for (std::size_t r = 0; r < outputs.size(); ++r) {
    const std::string p = fmt::format("/statement/modelled_output/{}", r);
    t += "<tr>" + text_cell(outputs[r]["run"].get<std::string>()) +
         (outputs[r]["g_level"].is_null() ? text_cell("–") : num_cell(doc, p + "/g_level", 6)) +
         num_cell(doc, p + "/corrected_estimate", 8) + num_cell(doc, p + "/combined_standard_uncertainty") +
         statement_dof_cell(doc, p + "/effective_dof") + num_cell(doc, p + "/coverage_factor", 4) +
         num_cell(doc, p + "/expanded_uncertainty", 3) + "</tr>\n";
  }
  return t + "</table>\n";
}

// The Monte Carlo check of each coefficient's Student-t interval (JCGM 101 §8).
std::string monte_carlo_check_table(const Doc& doc) {
  const Json& st = doc.json["statement"];
  if (st["monte_carlo"].is_null()) return "";
  std::string t = fmt::format(
      "<table class=\"statement-check\"><caption>Monte Carlo check of the intervals (JCGM 101 §8, M = {}, seed "
      "{}): the Student-t interval holds where d<sub>low</sub> and d<sub>high</sub> are at most δ</caption>\n"
      "<tr><th>coefficient</th><th>u (MC)</th><th colspan=\"2\">MC interval</th><th>d<sub>low</sub></th>"
      "<th>d<sub>high</sub></th><th>δ</th><th>stated</th></tr>\n",
      num_span(doc, "/statement/monte_carlo/trials", 10), num_span(doc, "/statement/monte_carlo/seed", 20));
  for (const auto& [id, c] : st["coefficients"].items()) {
    if (c["monte_carlo"].is_null()) continue;
    const std::string p = "/statement/coefficients/" + id + "/monte_carlo";
    t += "<tr>" + text_cell(id) + num_cell(doc, p + "/standard_uncertainty") +
         num_cell(doc, p + "/interval_symmetric/0", 6) + num_cell(doc, p + "/interval_symmetric/1", 6) +
         num_cell(doc, p + "/d_low", 2) + num_cell(doc, p + "/d_high", 2) + num_cell(doc, p + "/delta", 2) +
         text_cell(c["interval_method"] == "monte_carlo"       ? "Monte Carlo"
                   : c["interval_method"] == "coverage_factor" ? "stated k"
                   : c["monte_carlo"]["validated"].get<bool>()
                       ? "Student t"
                       : fmt::format("Student t (M too small to tell: {} trials would)",
                                     c["monte_carlo"]["trials_needed"].get<std::uint64_t>())) +
         "</tr>\n";
  }
  return t + "</table>\n";
}

// What the residuals' check found, in words.
std::string residual_check_text(const Json& st) {
  const Json& a = st["type_a"];
  if (!a["from_noise_model"].get<bool>())
    return "no noise is stated for this set-up: Type A is the fit's standard error, from that scatter, with ν = "
           "runs − free terms";
  const Json& c = a["residual_check"];
  return c["excess"].get<bool>()
             ? fmt::format("here the scatter exceeds the prediction, p-value {:.2g}, and its excess is charged",
                           c["p_value"].get<double>())
             : fmt::format("here the prediction explains the scatter, p-value {:.2g}, and nothing more is charged",
                           c["p_value"].get<double>());
}

// The Type B part's inputs (the GUM table): each input's standard uncertainty, whether this test measured it or
// its tolerance bounds it, and its signed effect on each coefficient. Inputs that act on no coefficient (every
// effect below 1e-12 of that coefficient's u_c) are counted, not listed.
std::string inputs_table(const Doc& doc) {
  const Json& st = doc.json["statement"];
  if (!st.contains("inputs") || st["inputs"].empty()) return "";
  std::vector<std::string> ids;
  for (const auto& [id, c] : st["coefficients"].items()) ids.push_back(id);
  std::string head = "<tr><th>input</th><th>u</th><th>unit</th><th>from</th>";
  for (const std::string& id : ids) head += "<th>u<sub>i</sub>(" + escape(id) + ")</th>";
  std::string rows;
  int silent = 0, measured = 0;
  for (std::size_t i = 0; i < st["inputs"].size(); ++i) {
    const Json& in = st["inputs"][i];
    bool acts = false;
    for (const std::string& id : ids)
      acts = acts || std::abs(in["effect"][id].get<double>()) >=
                         kRoundOffFloor * st["coefficients"][id]["combined_standard_uncertainty"].get<double>();
    if (!acts) {
      ++silent;
      continue;
    }
    measured += in["measured"].get<bool>();
    const std::string p = fmt::format("/statement/inputs/{}", i);
    // u in the unit its tolerance was written in (else its own: rad, um, ppm, a declared input's unit)
    rows += "<tr>" + text_cell(in["id"].get<std::string>()) + num_cell(doc, p + "/u", 3) +
            text_cell(in["unit"].get<std::string>()) +
            text_cell(in["measured"].get<bool>() ? "measured in this test" : "its tolerance");
    for (const std::string& id : ids) rows += num_cell(doc, p + "/effect/" + id, 3);
    rows += "</tr>\n";
  }
  return fmt::format("<table class=\"statement-inputs\"><caption>Type B inputs: u of each input, what it rests on, "
                     "and its signed effect u<sub>i</sub> = c u on each coefficient ({} measured in this test, "
                     "charged at the uncertainty of that measurement; {} more act on no coefficient)</caption>\n",
                     measured, silent) +
         head + "</tr>\n" + rows + "</table>\n";
}

}  // namespace

std::string statement_section(const Doc& doc) {
  const Json& st = doc.json["statement"];
  std::string out = fmt::format(
      "<section id=\"statement\"><h2>Calibration statement</h2>\n{}<p>The observations <code>{}</code> ({} "
      "runs) identified as <code>ccal identify</code> does, with the uncertainty the laboratory reports for "
      "each coefficient (JCGM 100 §7 and Annex G, docs/model.md §10.5). <b>Type A</b> is the random part: "
      "the noise of the instrument (its noise density and output quantum) and of the drives' rates, the σ of "
      "each run mean, propagated through the fit (ν = ∞); the scatter of the run means about the model is "
      "tested against what that noise and the inputs' run-to-run effects predict, and an excess would be "
      "charged with ν = runs − free terms ({}). <b>Type B</b> is the propagation of the inputs ({} mode): "
      "those this test measured (the drives' rates and rate ripple, from the encoders) at the uncertainty of "
      "that measurement, the others at their tolerances; it is known exactly (ν = ∞). They are independent, "
      "so u<sub>c</sub>² = u<sub>A</sub>² + u<sub>B</sub>²; ν<sub>eff</sub> by Welch–Satterthwaite; k the "
      "Student's t quantile for ⌊ν<sub>eff</sub>⌋ at p = {}; U = k u<sub>c</sub>; the interval is the "
      "corrected estimate ∓ U. A Monte Carlo of the same quantity (the inputs drawn through the exact model, "
      "the Type A part by its distribution) checks each interval (JCGM 101 §8); where it does not hold, the "
      "Monte Carlo's probabilistically symmetric interval is stated, and U is half its width. {} "
      "Units: the coefficients' (the instrument's output unit per gⁿ).</p>\n",
      result_table(doc), escape(certificate_parts::base_name(doc.json["file"].get<std::string>())),
      num_span(doc, "/rows", 6),
      residual_check_text(st), escape(st["mode"].get<std::string>()),
      num_span(doc, "/statement/coverage_probability", 4),
      known_errors_text(st));
  out +=
      "<div class=\"pair\">\n" + chart("statement-split", split_spec(st)) + statement_table(doc) + "</div>\n" +
      "<div class=\"pair\">\n" + correlation_table(doc) + modelled_output_table(doc) + "</div>\n" +
      inputs_table(doc) + monte_carlo_check_table(doc);
  return out + "</section>\n";
}

}  // namespace ccal::render::report_html
