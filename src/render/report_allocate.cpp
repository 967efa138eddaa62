// The report's allocation section (`ccal report --allocate-target`): per coefficient its target and U at the
// configured and at the allocated tolerances, every tolerance before and after in the unit the configuration
// wrote it in, the common scale, the Monte Carlo verification, and a chart of each tolerance's factor λ.
// Every number is read from the JSON of `ccal allocate` (render::json of the AllocateResult).
#include <fmt/format.h>

#include <algorithm>

#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"
#include "ccal/render/allocate.hpp"
#include "report_html.hpp"

namespace ccal::render::report_html {
namespace {

std::string coefficient_table(const Doc& doc) {
  const Json& j = doc.json;
  const bool verified = j["verification"].is_object();
  std::string t =
      "<table class=\"allocate-coefficients\"><caption>Expanded uncertainty U per coefficient: target, at "
      "the configured and at the allocated tolerances</caption>\n<tr><th>coefficient</th><th>unit</th>"
      "<th>target U</th><th>U configured</th><th>U allocated</th><th>U, one common scale</th>"
      "<th>u allocated</th>";
  if (verified) t += "<th>Monte Carlo half-width</th><th>half-width / target</th><th>verdict</th>";
  t += "</tr>\n";
  for (const auto& [id, c] : j["coefficients"].items()) {
    const std::string p = "/coefficients/" + id;
    const bool target = c["target"].is_number();
    t += "<tr>" + text_cell(id) + text_cell(c["unit"].get<std::string>()) +
         (target                   ? num_cell(doc, p + "/target")
          : c.value("held", false) ? text_cell("none (held at its configured U)")
          : c.value("grew", false) ? text_cell("none (U grew)")
                                   : text_cell("none")) +
         num_cell(doc, p + "/configured_expanded") + num_cell(doc, p + "/allocated_expanded") +
         num_cell(doc, p + "/common_scale_expanded") + num_cell(doc, p + "/allocated_std_uncertainty");
    if (verified) {
      t += num_cell(doc, p + "/mc/half_width");
      if (target) {
        const std::string verdict = c["verdict"].get<std::string>();
        t += ratio_cell(doc, p + "/mc/half_width", p + "/target") +
             fmt::format("<td class=\"{}\">{}</td>", verdict == "fail" ? "bad" : "good", escape(verdict));
      } else {
        t += "<td></td><td></td>";
      }
    }
    t += "</tr>\n";
  }
  return t + "</table>\n";
}

// Every tolerance, tightened most first (the output's order), in the configuration's unit: the SI value of
// the output times 1/(the unit's size in SI), which the cell states as its scale.
std::string tolerance_table(const Doc& doc, const verbs::AllocateResult& r) {
  const Json& j = doc.json;
  std::string t =
      "<table class=\"allocate-tolerances\"><caption>Every tolerance, configured against allocated, in the "
      "configuration's units (λ = allocated / configured; shares of the targets' variances at the allocated "
      "tolerances)</caption>\n<tr><th>source</th><th>distribution</th><th>unit</th><th>configured</th>"
      "<th>allocated</th><th>λ</th>";
  for (const Json& id : j["targets"]) t += "<th>share " + escape(id.get<std::string>()) + " [%]</th>";
  t += "</tr>\n";
  for (std::size_t s = 0; s < j["sources"].size(); ++s) {
    const Json& src = j["sources"][s];
    const AllocatedSource& a = r.allocation.sources.at(s);
    if (a.id != src["id"].get<std::string>())
      throw std::logic_error("report: the allocation's sources are not in the order of its JSON");
    const std::string unit = tolerance_display_unit(r.config, a.parameter);
    const double per_si = 1.0 / parse_unit(unit).value_si;
    const std::string p = fmt::format("/sources/{}", s), group = src["group"].get<std::string>();
    t += "<tr>" + text_cell(a.id + (group.empty() ? "" : " (" + group + ")")) +
         text_cell(src["distribution"].get<std::string>()) + text_cell(unit) +
         num_cell(doc, p + "/bound_si", 4, per_si) + num_cell(doc, p + "/allocated_bound_si", 4, per_si) +
         num_cell(doc, p + "/scale", 4);
    for (const Json& id : j["targets"]) t += num_cell(doc, p + "/share/" + id.get<std::string>(), 3, 100);
    t += "</tr>\n";
  }
  return t + "</table>\n";
}

// Horizontal bars of λ per source on a log axis, from 1 (the configured tolerance) to λ, tightened (λ < 1)
// and loosened (λ > 1) in two colours, with rules at λ = 1 and at the largest factor allowed.
Json scale_spec(const Json& j) {
  Json values = Json::array();
  for (const Json& s : j["sources"]) {
    const double scale = s["scale"].get<double>();
    values.push_back({{"source", s["id"]},
                      {"scale", scale},
                      {"change", scale < 1   ? "tightened"
                                 : scale > 1 ? "loosened"
                                             : "kept"}});
  }
  const double rows = double(values.size());
  return {
      {"title", "Allocated / configured tolerance (λ) per source"},
      {"width", 300},
      {"height", std::max(120.0, 13 * rows)},
      {"layer",
       Json::array(
           {{{"data", {{"values", values}}},
             {"mark", "bar"},
             {"encoding",
              {{"y", {{"field", "source"}, {"type", "nominal"}, {"sort", nullptr}, {"title", nullptr}}},
               {"x",
                {{"field", "scale"},
                 {"type", "quantitative"},
                 {"scale", {{"type", "log"}}},
                 {"title", "λ = allocated / configured (log scale)"}}},
               {"x2", {{"datum", 1}}},  // from λ = 1 (a log axis has no 0)
               {"color",
                {{"field", "change"},
                 {"type", "nominal"},
                 {"title", nullptr},
                 {"scale",
                  {{"domain", {"tightened", "kept", "loosened"}},
                   {"range", {"#e45756", "#bab0ac", "#54a24b"}}}},
                 {"legend", {{"orient", "bottom"}}}}},
               {"tooltip", Json::array({{{"field", "source"}}, {{"field", "scale"}, {"format", ".4g"}}})}}}},
            {{"data", {{"values", Json::array({{{"x", 1.0}}, {{"x", j["max_scale"]}}})}}},
             {"mark", {{"type", "rule"}, {"strokeDash", {4, 3}}, {"color", "#555"}}},
             {"encoding", {{"x", {{"field", "x"}, {"type", "quantitative"}}}}}}})}};
}

std::string verification_text(const Doc& doc) {
  const Json& v = doc.json["verification"];
  if (!v.is_object()) return "<p>No Monte Carlo verification (<code>--verify-trials 0</code>).</p>\n";
  const bool passed = v["passed"].get<bool>();
  return fmt::format(
      "<p class=\"verification\">Monte Carlo verification on the allocated tolerances (JCGM 101, {} trials, "
      "seed {}): per target the half-width of the symmetric interval about the Monte Carlo mean against the "
      "target; a half-width up to target × (1 + {}) (3 standard errors of the half-width, relative standard "
      "error {}) passes within sampling error. Verification <span class=\"{}\">{}</span>.</p>\n",
      num_span(doc, "/verification/trials", 12), num_span(doc, "/verification/seed", 20),
      num_span(doc, "/verification/allowance", 3), num_span(doc, "/verification/half_width_rel_error", 3),
      passed ? "good" : "bad", passed ? "passed" : "failed");
}

}  // namespace

std::string allocation_section(const Doc& doc, const verbs::AllocateResult& r) {
  const Json& j = doc.json;
  std::string toml;
  for (const Json& s : j["sources"]) toml += s["toml"].get<std::string>() + "\n";
  const Json& solver = j["solver"];
  std::string out = fmt::format(
      "<section id=\"allocation\"><h2>Tolerance allocation: configured against allocated</h2>\n<p>The "
      "largest centrifuge tolerances for which every target on the expanded uncertainty U = k<sub>p</sub> "
      "u holds (p = {}, k<sub>p</sub> = {}; {} mode sensitivities at the configured errors): minimise "
      "Σ cost<sub>s</sub>/λ<sub>s</sub>, each tolerance λ<sub>s</sub> times its configured value, "
      "λ<sub>s</sub> ≤ {}. The objective is {} at the configured tolerances, {} allocated, and {} with one "
      "common scale λ = {} for every source; solved by {} ({}). From <code>ccal allocate</code>.</p>\n",
      num_span(doc, "/coverage_probability", 4), num_span(doc, "/coverage_factor", 6),
      escape(j["mode"].get<std::string>()), num_span(doc, "/max_scale", 4),
      num_span(doc, "/objective/configured", 6), num_span(doc, "/objective/allocated", 6),
      num_span(doc, "/objective/common_scale", 6), num_span(doc, "/common_scale", 4),
      escape(solver["method"].get<std::string>()),
      solver["converged"].get<bool>() ? "converged" : "not converged");
  out += coefficient_table(doc) + verification_text(doc);
  out += "<div class=\"pair\">\n" + chart("allocate-scale", scale_spec(j)) + tolerance_table(doc, r) +
         "</div>\n";
  out +=
      "<details><summary>The allocated [tolerances] in configuration style (bounds rounded down to 4 "
      "digits)</summary>\n<pre class=\"toml\">" +
      escape(toml) + "</pre>\n</details>\n";
  return out + "</section>\n";
}

}  // namespace ccal::render::report_html
