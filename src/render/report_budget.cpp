// The report's budget sections: per coefficient a Pareto chart of the variance shares and the GUM budget table
// (EA-4/02's columns) of its largest sources (the rest summed in one row), and the exact-vs-paper comparison.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "report_html.hpp"

namespace ccal::render::report_html {
namespace {

// A row of the budget: a source of `sources` or of `rate_noise`, by its pointer in the budget's JSON.
struct Contributor {
  std::string pointer;  // e.g. "/sources/3" or "/rate_noise/0"
  std::string id;
  double share = 0;
  bool type_a = false;
};

std::vector<Contributor> by_share(const Json& budget, const std::string& coefficient) {
  std::vector<Contributor> all;
  for (std::size_t s = 0; s < budget["sources"].size(); ++s) {
    const Json& j = budget["sources"][s];
    all.push_back({fmt::format("/sources/{}", s), j["id"].get<std::string>(),
                   j["share"][coefficient].get<double>(), false});
  }
  if (budget.contains("rate_noise"))
    for (std::size_t s = 0; s < budget["rate_noise"].size(); ++s) {
      const Json& j = budget["rate_noise"][s];
      all.push_back({fmt::format("/rate_noise/{}", s), j["id"].get<std::string>(),
                     j["share"][coefficient].get<double>(), true});
    }
  std::stable_sort(all.begin(), all.end(),
                   [](const Contributor& a, const Contributor& b) { return a.share > b.share; });
  return all;
}

// A cell computed from several numbers of the output: their sum ("sum") or root-sum-square ("rss"), each at
// its pointer; the cell lists them, so that the check can redo the sum.
std::string combined_cell(const Doc& doc, const std::vector<std::string>& pointers, const std::string& kind,
                          int digits, double scale) {
  double sum = 0;
  std::string list;
  for (const auto& p : pointers) {
    const double v = doc.json.at(Json::json_pointer(p)).get<double>();
    sum += kind == "rss" ? v * v : v;
    list += (list.empty() ? "" : " ") + p;
  }
  const double value = (kind == "rss" ? std::sqrt(sum) : sum) * scale;
  return fmt::format(
      "<td class=\"num\" data-{}=\"{}:{}\" data-digits=\"{}\" data-scale=\"{:g}\">{:.{}g}</td>", kind,
      escape(doc.name), escape(list), digits, scale, value, digits);
}

Json pareto_spec(const std::string& coefficient, const std::vector<Contributor>& top, double rest_share,
                 std::size_t rest_count) {
  Json values = Json::array();
  double cumulative = 0;
  int order = 0;
  for (const auto& c : top) {
    cumulative += c.share;
    values.push_back(
        {{"source", c.id}, {"share", 100 * c.share}, {"cumulative", 100 * cumulative}, {"order", ++order}});
  }
  if (rest_count > 0) {
    cumulative += rest_share;
    values.push_back({{"source", fmt::format("rest ({})", rest_count)},
                      {"share", 100 * rest_share},
                      {"cumulative", 100 * cumulative},
                      {"order", ++order}});
  }
  const std::string y_title = fmt::format("share of u²({}) [%]", coefficient);
  return {
      {"title", fmt::format("{}: where the variance comes from", coefficient)},
      {"width", 300},
      {"height", 220},
      {"data", {{"values", values}}},
      {"encoding",
       {{"x",
         {{"field", "source"},
          {"type", "nominal"},
          {"sort", {{"field", "order"}}},
          {"title", nullptr},
          {"axis", {{"labelAngle", -40}}}}}}},
      {"layer",
       Json::array(
           {{{"mark", {{"type", "bar"}, {"color", "#4c78a8"}}},
             {"encoding",
              {{"y",
                {{"field", "share"},
                 {"type", "quantitative"},
                 {"title", y_title},
                 {"scale", {{"domain", {0, 100}}}}}},
               {"tooltip", Json::array({{{"field", "source"}}, {{"field", "share"}, {"format", ".3g"}}})}}}},
            {{"mark", {{"type", "line"}, {"color", "#e45756"}, {"point", true}}},
             {"encoding", {{"y", {{"field", "cumulative"}, {"type", "quantitative"}}}}}}})}};
}

// The quantity X_i: its id (and group) and the catalogue's words for it.
std::string quantity_cell(const Json& line) {
  const std::string group = line.value("group", "");
  return fmt::format("<td class=\"quantity\"><code>{}</code>{}<br><span class=\"desc\">{}</span></td>",
                     escape(line["id"].get<std::string>()),
                     group.empty() ? std::string() : fmt::format(" ({})", escape(group)),
                     escape(line["name"].get<std::string>()));
}

// ν_i: "∞" where the output writes null (a value taken as exact), else the number.
std::string dof_cell(const Doc& doc, const std::string& line) {
  return doc.json.at(Json::json_pointer(line + "/dof")).is_null() ? text_cell("∞")
                                                                  : num_cell(doc, line + "/dof", 3);
}

// One line of the table (EA-4/02's columns): X_i with its description, x_i and u(x_i) in the unit the
// configuration wrote, the distribution and its divisor, the type of evaluation, ν_i, c_i, u_i(y) and its
// share, the last three 0 below the round-off floor.
std::string line_row(const Doc& doc, const Contributor& c, const std::string& id) {
  const Json& line = doc.json.at(Json::json_pointer(c.pointer));
  const std::string floor = c.pointer + "/below_round_off_floor/" + id;
  return fmt::format(
      "<tr>{}{}{}{}{}{}{}{}{}{}{}</tr>\n", quantity_cell(line), num_cell(doc, c.pointer + "/estimate"),
      num_cell(doc, c.pointer + "/standard_uncertainty"), text_cell(line["unit"].get<std::string>()),
      text_cell(line["distribution"].get<std::string>()), num_cell(doc, c.pointer + "/divisor"),
      text_cell(line["type"].get<std::string>()), dof_cell(doc, c.pointer),
      num_cell_or_zero(doc, c.pointer + "/sensitivity/" + id, floor),
      num_cell_or_zero(doc, c.pointer + (c.type_a ? "/u/" : "/effect/") + id, floor),
      num_cell_or_zero(doc, c.pointer + "/share/" + id, floor, 3, 100));
}

std::string coefficient_table(const Doc& doc, std::size_t k, const std::vector<Contributor>& all,
                              std::size_t top) {
  const Json& budget = doc.json;
  const std::string id = budget["coefficients"][k]["id"].get<std::string>();
  const std::string unit = budget["coefficients"][k]["unit"].get<std::string>();
  std::string t = fmt::format(
      "<table class=\"budget\" data-coefficient=\"{0}\"><caption>{0} [{1}]: uncertainty budget (JCGM 100, "
      "EA-4/02), largest sources</caption>\n<tr><th>quantity X<sub>i</sub></th><th>x<sub>i</sub></th>"
      "<th>u(x<sub>i</sub>)</th><th>unit</th><th>distribution</th><th>divisor</th><th>type</th>"
      "<th>ν<sub>i</sub></th><th>c<sub>i</sub> [{1} per unit]</th><th>u<sub>i</sub>(y) [{1}]</th>"
      "<th>share [%]</th></tr>\n",
      escape(id), escape(unit));
  std::size_t rest = 0;
  std::vector<std::string> rest_effects, rest_shares;  // of the rest above the round-off floor
  for (std::size_t n = 0; n < all.size(); ++n) {
    const Contributor& c = all[n];
    if (n < top) {
      t += line_row(doc, c, id);
      continue;
    }
    ++rest;
    if (budget.at(Json::json_pointer(c.pointer + "/below_round_off_floor/" + id)).get<bool>()) continue;
    rest_effects.push_back(c.pointer + (c.type_a ? "/u/" : "/effect/") + id);
    rest_shares.push_back(c.pointer + "/share/" + id);
  }
  if (rest > 0)
    t += fmt::format("<tr class=\"rest\"><td colspan=\"9\">{}</td>{}{}</tr>\n",
                     escape(fmt::format("the other {} sources (root-sum-square; those below the round-off "
                                        "floor as 0)",
                                        rest)),
                     combined_cell(doc, rest_effects, "rss", 4, 1.0),
                     combined_cell(doc, rest_shares, "sum", 3, 100));
  if (budget.contains("input_correlation"))  // the cross terms Σ_{s≠t} u_s(y) r_st u_t(y): one more line
    t += fmt::format(
        "<tr class=\"rest\"><td colspan=\"10\">correlations between sources ([[correlations]]: the cross "
        "terms, negative where correlated effects cancel)</td>{}</tr>\n",
        num_cell(doc, "/input_correlation/share_of_variance/" + id, 3, 100));
  const std::string c = fmt::format("/coefficients/{}", k);
  t += fmt::format(
      "<tr class=\"total\"><td colspan=\"9\">combined standard uncertainty u<sub>c</sub> "
      "(LPU)</td>{}<td></td>"
      "</tr>\n",
      num_cell(doc, c + "/standard_uncertainty"));
  t += fmt::format(
      "<tr class=\"total\"><td colspan=\"9\">expanded uncertainty U = k u<sub>c</sub>, k = {}, p = {} "
      "%{}</td>"
      "{}<td></td></tr>\n</table>\n",
      num_span(doc, "/coverage_factor", 3), num_span(doc, "/coverage_probability", 4, 100),
      doc.json.value("coverage_method", "") == "stated k" ? " for a normal quantity (k stated)" : "",
      num_cell(doc, c + "/expanded_uncertainty"));
  return t;
}

// The inputs' correlation matrix where it is not the identity: the sources that some correlation links
// (a group's members or a [[correlations]] pair), each r traced to the budget's JSON.
std::string input_correlation_table(const Doc& doc) {
  if (!doc.json.contains("input_correlation")) return {};
  const Json& ic = doc.json["input_correlation"];
  const Json& matrix = ic["matrix"];
  std::vector<std::size_t> linked;
  for (std::size_t a = 0; a < matrix.size(); ++a)
    for (std::size_t b = 0; b < matrix.size(); ++b)
      if (a != b && matrix[a][b].get<double>() != 0) {
        linked.push_back(a);
        break;
      }
  if (linked.empty()) return {};
  std::string t =
      "<table class=\"input-correlation\"><caption>Correlation coefficients r of the input quantities that "
      "are correlated ([[correlations]]; 1 within a group; JCGM 100 §5.2.2)</caption>\n<tr><th></th>";
  for (const std::size_t b : linked) t += "<th>" + escape(ic["sources"][b].get<std::string>()) + "</th>";
  t += "</tr>\n";
  for (const std::size_t a : linked) {
    t += "<tr><th>" + escape(ic["sources"][a].get<std::string>()) + "</th>";
    for (const std::size_t b : linked) t += num_cell(doc, fmt::format("/input_correlation/matrix/{}/{}", a, b), 3);
    t += "</tr>\n";
  }
  return t + "</table>\n";
}

// The chart beside the paper table: per coefficient, the effect of each of the largest sources by the exact
// chain and by the paper's rules, side by side (`values`: source, coefficient, model, effect).
Json paper_chart_spec(Json values) {
  return {
      {"title", "Effect of the largest sources: exact chain against the paper's rules"},
      {"data", {{"values", std::move(values)}}},
      // Two coefficients a row: three would be wider than an A4 page.
      {"facet", {{"field", "coefficient"}, {"type", "nominal"}, {"title", nullptr}}},
      {"columns", 2},
      {"resolve", {{"scale", {{"y", "independent"}}}}},
      {"spec",
       {{"width", 220},
        {"height", 200},
        {"mark", "bar"},
        {"encoding",
         {{"x",
           {{"field", "source"},
            {"type", "nominal"},
            {"title", nullptr},
            {"sort", nullptr},
            {"axis", {{"labelAngle", -40}}}}},
          {"xOffset", {{"field", "model"}, {"type", "nominal"}}},
          {"y",
           {{"field", "effect"}, {"type", "quantitative"}, {"title", "effect at u(x) (coefficient unit)"}}},
          {"color",
           {{"field", "model"}, {"type", "nominal"}, {"scale", {{"range", {"#4c78a8", "#f58518"}}}}}}}}}}};
}

}  // namespace

std::string budget_section(const Doc& doc, std::size_t top) {
  const Json& budget = doc.json;
  std::string out =
      "<section id=\"budget\"><h2>Uncertainty budget</h2>\n<p>Per input quantity X<sub>i</sub> (a tolerance, "
      "Type B, or a drive's rate noise, Type A): its estimate x<sub>i</sub>, the configured [errors] value "
      "at "
      "which c<sub>i</sub> is evaluated, and its standard uncertainty u(x<sub>i</sub>) = bound / divisor, "
      "both "
      "in the unit the configuration wrote; the distribution; the degrees of freedom ν<sub>i</sub> (∞: the "
      "bounds and the noise densities are stated values); the sensitivity coefficient c<sub>i</sub> = "
      "∂y/∂x<sub>i</sub> through kinematics, reduction and least squares, per that unit; the contribution "
      "u<sub>i</sub>(y) = c<sub>i</sub> u(x<sub>i</sub>) and its share of u<sub>c</sub>²(y). A contribution "
      "below " +
      num_span(doc, "/round_off_floor_relative", 3) +
      " u<sub>c</sub> is round-off of the derivatives and is shown as 0. From <code>ccal budget</code> (" +
      escape(budget["mode"].get<std::string>()) + " mode).</p>\n";
  for (std::size_t k = 0; k < budget["coefficients"].size(); ++k) {
    const std::string id = budget["coefficients"][k]["id"].get<std::string>();
    const std::vector<Contributor> all = by_share(budget, id);
    const std::size_t n_top = std::min(top, all.size());
    double rest = 0;
    for (std::size_t n = n_top; n < all.size(); ++n) rest += all[n].share;
    const std::vector<Contributor> head(all.begin(), all.begin() + std::ptrdiff_t(n_top));
    out += "<div class=\"pair\">\n" + chart("pareto-" + id, pareto_spec(id, head, rest, all.size() - n_top)) +
           coefficient_table(doc, k, all, n_top) + "</div>\n";
  }
  return out + input_correlation_table(doc) + "</section>\n";
}

std::string paper_section(const Doc& doc, std::size_t top) {
  const Json& budget = doc.json;
  if (budget["sources"].empty() || !budget["sources"][0].contains("paper_effect")) return {};
  std::vector<std::size_t> order(budget["sources"].size());
  std::iota(order.begin(), order.end(), 0);
  const std::size_t n = std::min(top, order.size());  // sources are in rank order already
  Json values = Json::array();
  std::string t =
      "<table class=\"paper\"><caption>Effect of each source at its u(x<sub>i</sub>): exact chain and the "
      "paper's first-order rules</caption>\n<tr><th>source</th>";
  for (const Json& c : budget["coefficients"])
    t += fmt::format("<th>{0} exact</th><th>{0} paper</th><th>{0}</th>", escape(c["id"].get<std::string>()));
  t += "</tr>\n";
  for (std::size_t r = 0; r < n; ++r) {
    const Json& s = budget["sources"][order[r]];
    const std::string p = fmt::format("/sources/{}", order[r]);
    t += "<tr>" + text_cell(s["id"].get<std::string>());
    for (const Json& c : budget["coefficients"]) {
      const std::string id = c["id"].get<std::string>();
      const bool counterpart = s.value("paper_counterpart", true);
      t += num_cell(doc, p + "/effect/" + id, 3) + num_cell(doc, p + "/paper_effect/" + id, 3) +
           text_cell(!counterpart                                ? "no paper rule"
                     : s["exact_paper_disagree"][id].get<bool>() ? "differ"
                                                                 : "agree");
      for (const char* model : {"exact", "paper"})
        values.push_back({{"source", s["id"]},
                          {"coefficient", id + " [" + c["unit"].get<std::string>() + "]"},
                          {"model", model},
                          {"effect", s[model == std::string("exact") ? "effect" : "paper_effect"][id]}});
    }
    t += "</tr>\n";
  }
  t += "</table>\n";
  const Json spec = paper_chart_spec(std::move(values));
  return "<section id=\"paper\"><h2>Exact chain against the paper's first-order rules</h2>\n<p>The same "
         "sources through the paper's first-order rules (Wang &amp; Ren 2014); \"differ\": by more than a "
         "factor of 2 or in sign where it matters (<code>ccal budget</code>).</p>\n<div class=\"pair\">\n" +
         chart("paper-vs-exact", spec) + t + "</div>\n</section>\n";
}

}  // namespace ccal::render::report_html
