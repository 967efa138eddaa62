// The certificate's annexes: A, the uncertainty budget of each coefficient as a GUM table (each input in
// words, its unit, its type and what it rests on, its standard uncertainty, its sensitivity and its
// contribution); B, the runs (g-level, duration, mean output, residual).
#include <fmt/format.h>

#include <cmath>

#include "ccal/uncertainty/budget.hpp"
#include "certificate_parts.hpp"

namespace ccal::render::certificate_parts {
namespace {

using report_html::escape;

// The budget's name of an input (its words), else its id.
std::string input_name(const Doc& budget, const std::string& id) {
  for (const Json& s : budget.json["sources"])
    if (s["id"] == id) return s["name"].get<std::string>();
  return id;
}

// The distribution of an input's tolerance, as the budget has it ("" when the budget has none).
std::string input_distribution(const Doc& budget, const std::string& id) {
  for (const Json& s : budget.json["sources"])
    if (s["id"] == id) return s["distribution"].get<std::string>();
  return "";
}

// The table's two header rows: the input's columns, then a pair (c_i, u_i) under each coefficient.
std::pair<std::string, std::string> annex_header(const Json& st, const std::vector<std::string>& ids) {
  std::string head =
      "<tr><th rowspan=\"2\">input quantity</th><th rowspan=\"2\">type, evaluated from</th>"
      "<th rowspan=\"2\">u(x<sub>i</sub>)</th>";
  std::string sub = "<tr>";
  for (const std::string& id : ids) {
    head += fmt::format("<th colspan=\"2\">{} [{}]</th>", term_html(id),
                        unit_html(st["coefficients"][id]["unit"].get<std::string>()));
    sub += "<th>c<sub>i</sub></th><th>u<sub>i</sub></th>";
  }
  return {head, sub};
}

// A row per Type B input that acts on some coefficient beyond the derivatives' round-off (kRoundOffFloor of
// its u_c): its name, type and distribution, u(x_i), and c_i, u_i = |c_i| u(x_i) per coefficient. `silent`
// counts the others.
std::string annex_input_rows(const Json& st, const std::vector<std::string>& ids, const Doc& budget,
                             int& silent) {
  std::string rows;
  for (const Json& in : st["inputs"]) {
    bool acts = false;
    for (const std::string& id : ids)
      acts =
          acts || std::abs(in["effect"][id].get<double>()) >=
                      kRoundOffFloor * st["coefficients"][id]["combined_standard_uncertainty"].get<double>();
    if (!acts) {
      ++silent;
      continue;
    }
    const std::string id = in["id"].get<std::string>(), distribution = input_distribution(budget, id);
    const double u = in["u"].get<double>();
    rows += fmt::format("<tr><td>{}</td><td>B, {}</td><td class=\"num\">{} {}</td>",
                        words_html(input_name(budget, id)),
                        in["measured"].get<bool>()
                            ? std::string("measured in this test")
                            : "tolerance" + (distribution.empty() ? std::string() : ", " + distribution),
                        number_html(u, 2), unit_html(in["unit"].get<std::string>()));
    for (const std::string& k : ids) {
      const double effect = in["effect"][k].get<double>();
      rows += fmt::format("<td class=\"num\">{}</td><td class=\"num\">{}</td>",
                          u > 0 ? number_html(effect / u, 3) : "–", number_html(std::abs(effect), 2));
    }
    rows += "</tr>\n";
  }
  return rows;
}

// Type A, then the combination per coefficient: u_c, ν_eff, k (none for a Monte Carlo interval), U as the
// statement rounds it (or the Monte Carlo's interval) and how the interval is obtained; each row unclosed.
std::vector<std::string> annex_total_rows(const Json& st, const std::vector<std::string>& ids) {
  std::string type_a =
      "<tr><td>noise of the run means (instrument and drives)</td><td>A, this test</td><td "
      "class=\"num\">–</td>";
  std::string combined =
                  "<tr class=\"total\"><td colspan=\"3\">combined standard uncertainty u<sub>c</sub></td>",
              dof = "<tr><td colspan=\"3\">effective degrees of freedom ν<sub>eff</sub></td>",
              k_row = "<tr><td colspan=\"3\">coverage factor k</td>",
              expanded = "<tr class=\"total\"><td colspan=\"3\">expanded uncertainty U</td>",
              method = "<tr><td colspan=\"3\">how the interval is obtained</td>";
  for (const std::string& id : ids) {
    const Json& c = st["coefficients"][id];
    const bool mc = c["interval_method"] == "monte_carlo";
    type_a += fmt::format("<td class=\"num\">–</td><td class=\"num\">{}</td>",
                          number_html(c["type_a"]["u"].get<double>(), 2));
    combined += fmt::format("<td colspan=\"2\" class=\"num\">{}</td>",
                            number_html(c["combined_standard_uncertainty"].get<double>(), 2));
    dof += fmt::format("<td colspan=\"2\" class=\"num\">{}</td>", dof_text(c["effective_dof"]));
    k_row += fmt::format("<td colspan=\"2\" class=\"num\">{}</td>",
                         mc ? std::string("–") : coverage_factor_text(c["coverage_factor"].get<double>()));
    expanded +=
        fmt::format("<td colspan=\"2\" class=\"num\">{}</td>",
                    mc ? fmt::format("[{}, {}]", escape(c["rounded"]["interval"][0].get<std::string>()),
                                     escape(c["rounded"]["interval"][1].get<std::string>()))
                       : escape(c["rounded"]["expanded_uncertainty"].get<std::string>()));
    method += fmt::format("<td colspan=\"2\" data-method=\"{}\">{}</td>", escape(id), method_html(c));
  }
  return {type_a, combined, dof, k_row, expanded, method};
}

}  // namespace

std::string budget_annex(const Doc& doc, const Doc& budget) {
  const Json& st = doc.json["statement"];
  std::vector<std::string> ids;
  for (const auto& [id, c] : st["coefficients"].items()) ids.push_back(id);
  const auto [head, sub] = annex_header(st, ids);
  int silent = 0;
  const std::string rows = annex_input_rows(st, ids, budget, silent);
  const std::vector<std::string> totals = annex_total_rows(st, ids);
  return fmt::format(
      "<section id=\"annex-budget\" class=\"annex\"><h2>Annex A: Uncertainty budget</h2>\n<p>Per "
      "coefficient, each "
      "input quantity x<sub>i</sub> with its standard uncertainty u(x<sub>i</sub>), its sensitivity "
      "coefficient "
      "c<sub>i</sub> (the coefficient's unit per the input's unit) and its contribution u<sub>i</sub> = "
      "|c<sub>i</sub>| u(x<sub>i</sub>) to the coefficient's standard uncertainty. The inputs are "
      "independent "
      "but for the correlations of the model, so u<sub>c</sub>² is the sum of the u<sub>i</sub>² and of the "
      "Type A part.{}</p>\n<table "
      "class=\"gum\">\n{}</tr>\n{}</tr>\n{}{}</tr>\n{}</tr>\n{}</tr>\n{}</tr>\n{}</tr>\n"
      "{}</tr>\n</table>\n</section>\n",
      silent > 0 ? fmt::format(" {} further inputs contribute nothing to any coefficient and are not listed.",
                               silent)
                 : std::string(),
      head, sub, rows, totals[0], totals[1], totals[2], totals[3], totals[4], totals[5]);
}

std::string runs_annex(const verbs::ReportResult& r, const Doc& doc) {
  const Json& residuals = doc.json["residuals"];
  const std::string unit = unit_html(r.config.instrument.output_unit);
  std::string rows;
  std::size_t k = 0;
  for (const auto& [run, residual] : residuals.items()) {
    const Run* planned = nullptr;
    for (const Run& p : r.config.plan.runs)
      if (p.name == run) planned = &p;
    const double mean = k < r.observed_means.size() ? r.observed_means[k] : std::nan("");
    rows += fmt::format(
        "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td "
        "class=\"num\">{}</td></tr>\n",
        escape(run), planned ? number_html(planned->g_level, 6) : "–",
        planned ? number_html(planned->duration, 6) : "–", std::isfinite(mean) ? number_html(mean, 8) : "–",
        number_html(residual.get<double>(), 2));
    ++k;
  }
  const std::string g_symbol = r.config.site.unit_g > 0 ? "g<sub>n</sub>" : "g";
  return fmt::format(
      "<section id=\"annex-runs\" class=\"keep\"><h2>Annex B: The runs</h2>\n<p>Each run's g-level, duration "
      "and mean output, "
      "and its residual: the mean output less the model's value with the coefficients of the "
      "result.</p>\n<table "
      "class=\"runs\">\n<tr><th>run</th><th>g-level [{}]</th><th>duration [s]</th><th>mean output "
      "[{}]</th><th>"
      "residual [{}]</th></tr>\n{}</table>\n</section>\n",
      g_symbol, unit, unit, rows);
}

}  // namespace ccal::render::certificate_parts
