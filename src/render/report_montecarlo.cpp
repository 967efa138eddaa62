// The report's Monte Carlo section (per coefficient: the histogram of the trials, the LPU's Gaussian over it,
// both 100p % intervals, the validation of JCGM 101 §8) and its sensed-input section.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "report_html.hpp"

namespace ccal::render::report_html {
namespace {

// Histogram bars, the LPU's normal density N(estimate, u_c²) scaled to trials per bin (M·w·φ), and the ends
// of the Monte Carlo symmetric interval and of the LPU interval estimate ± U_p.
Json histogram_spec(const std::string& id, const Json& c, double M, double p) {
  const Json& h = c["histogram"];
  const double lowest = h["lowest"].get<double>(), width = h["bin_width"].get<double>();
  Json bars = Json::array();
  for (std::size_t b = 0; b < h["counts"].size(); ++b)
    bars.push_back({{"x0", lowest + width * double(b)},
                    {"x1", lowest + width * double(b + 1)},
                    {"trials", h["counts"][b]}});
  const double mu = c["estimate"].get<double>(), u = c["lpu"]["std_uncertainty"].get<double>();
  const double highest = h["highest"].get<double>();
  Json curve = Json::array();
  if (u > 0)
    for (int k = 0; k <= 160; ++k) {
      const double x = lowest + (highest - lowest) * k / 160.0, z = (x - mu) / u;
      curve.push_back(
          {{"x", x}, {"trials", M * width * std::exp(-0.5 * z * z) / (u * std::sqrt(2 * std::numbers::pi))}});
    }
  const std::string pct = fmt::format("{:g} %", 100 * p);
  const std::string mc = "Monte Carlo " + pct, lpu = "LPU " + pct;
  const double U = c["lpu"]["expanded_uncertainty"].get<double>();
  Json rules = Json::array({{{"x", c["symmetric_interval"][0]}, {"interval", mc}},
                            {{"x", c["symmetric_interval"][1]}, {"interval", mc}},
                            {{"x", mu - U}, {"interval", lpu}},
                            {{"x", mu + U}, {"interval", lpu}}});
  const std::string x_title = fmt::format("{} deviation [{}]", id, c["unit"].get<std::string>());
  const Json x = {{"field", "x0"},
                  {"type", "quantitative"},
                  {"title", x_title},
                  {"scale", {{"domain", {lowest, highest}}, {"nice", false}}}};
  return {{"title", fmt::format("{}: distribution of {} trials", id, M)},
          {"width", 320},
          {"height", 220},
          {"layer",
           Json::array(
               {{{"data", {{"values", bars}}},
                 {"mark", {{"type", "bar"}, {"color", "#9ecae9"}}},
                 {"encoding",
                  {{"x", x},
                   {"x2", {{"field", "x1"}}},
                   {"y", {{"field", "trials"}, {"type", "quantitative"}, {"title", "trials per bin"}}},
                   {"y2", {{"datum", 0}}}}}},
                {{"data", {{"values", curve}}},
                 {"mark", {{"type", "line"}, {"color", "#e45756"}}},
                 {"encoding",
                  {{"x", {{"field", "x"}, {"type", "quantitative"}}},
                   {"y", {{"field", "trials"}, {"type", "quantitative"}}}}}},
                {{"data", {{"values", rules}}},
                 {"mark", {{"type", "rule"}, {"strokeWidth", 2}}},
                 {"encoding",
                  {{"x", {{"field", "x"}, {"type", "quantitative"}}},
                   {"color",
                    {{"field", "interval"},
                     {"type", "nominal"},
                     {"title", nullptr},
                     {"scale", {{"range", {"#54a24b", "#f58518"}}}},
                     {"legend", {{"orient", "bottom"}}}}},
                   {"strokeDash", {{"field", "interval"}, {"type", "nominal"}, {"legend", nullptr}}}}}}})}};
}

std::string row(const std::string& label, const std::string& cells) {
  return "<tr><th>" + label + "</th>" + cells + "</tr>\n";
}

std::string coefficient_table(const Doc& doc, const std::string& id, const std::string& advice) {
  const std::string c = "/coefficients/" + id;
  const Json& j = doc.json["coefficients"][id];
  std::string t = fmt::format("<table class=\"mc\" data-coefficient=\"{0}\"><caption>{0} [{1}]</caption>\n",
                              escape(id), escape(j["unit"].get<std::string>()));
  t += row("mean y", num_cell(doc, c + "/mean") + "<td></td>");
  t += row("standard deviation u(y)", num_cell(doc, c + "/std_dev") + "<td></td>");
  t += row("symmetric interval",
           num_cell(doc, c + "/symmetric_interval/0") + num_cell(doc, c + "/symmetric_interval/1"));
  t += row("shortest interval",
           num_cell(doc, c + "/shortest_interval/0") + num_cell(doc, c + "/shortest_interval/1"));
  t += row("LPU estimate", num_cell(doc, c + "/estimate") + "<td></td>");
  t += row("LPU u<sub>c</sub>", num_cell(doc, c + "/lpu/std_uncertainty") + "<td></td>");
  t += row("LPU U<sub>p</sub> = k u<sub>c</sub>",
           num_cell(doc, c + "/lpu/expanded_uncertainty") + "<td></td>");
  t += row("d<sub>low</sub>, d<sub>high</sub>",
           num_cell(doc, c + "/lpu/d_low", 3) + num_cell(doc, c + "/lpu/d_high", 3));
  t += row("tolerance δ", num_cell(doc, c + "/lpu/delta", 3) + "<td></td>");
  t += row("sampling error of the ends", num_cell(doc, c + "/lpu/interval_end_std_error", 3) + "<td></td>");
  const bool ok = j["lpu"]["validated"].get<bool>();
  t += fmt::format("<tr><th>LPU validated (§8)</th><td class=\"{}\">{}</td><td></td></tr>\n",
                   ok ? "good" : "bad", ok ? "yes" : "no");
  t += "</table>\n";
  if (!advice.empty()) t += "<p class=\"advice\">" + escape(advice) + "</p>\n";
  return t;
}

}  // namespace

std::string montecarlo_section(const Doc& doc, const std::vector<std::string>& advice) {
  const Json& j = doc.json;
  const double M = j["trials"].get<double>(), p = j["coverage_probability"].get<double>();
  std::string out = fmt::format(
      "<section id=\"montecarlo\"><h2>Monte Carlo distribution (JCGM 101)</h2>\n<p>{} trials"
      " ({}), seed {}: every tolerance drawn from its distribution, the plan simulated and the coefficients "
      "identified; the bars are the trials' deviations, the red curve the normal distribution the LPU "
      "assumes "
      "(mean the estimate, standard deviation u<sub>c</sub>); the rules mark the Monte Carlo "
      "probabilistically "
      "symmetric {:g} % interval and the LPU's estimate ± U<sub>p</sub>. The LPU is validated when both ends "
      "agree within δ (§8). From <code>ccal montecarlo</code>.</p>\n",
      num_span(doc, "/trials", 12), j["adaptive"].get<bool>() ? "adaptive procedure" : "fixed M",
      num_span(doc, "/seed", 20), 100 * p);
  std::size_t k = 0;
  for (const auto& [id, c] : j["coefficients"].items()) {
    out += "<div class=\"pair\">\n" + chart("mc-" + id, histogram_spec(id, c, M, p)) +
           coefficient_table(doc, id, k < advice.size() ? advice[k] : std::string()) + "</div>\n";
    ++k;
  }
  return out + "</section>\n";
}

std::string sensed_input_section(const verbs::SensedInputSeries& s, const std::vector<Json>& instants) {
  Json values = Json::array();
  for (std::size_t i = 0; i < s.time.size(); ++i)
    for (const auto& [axis, v] :
         {std::pair{"IA", s.ia[i]}, std::pair{"PA", s.pa[i]}, std::pair{"OA", s.oa[i]}})
      values.push_back({{"t", s.time[i]}, {"axis", axis}, {"f", v}});
  const Json spec = {
      {"title", fmt::format("Specific force sensed in run {} ({:g} g)", s.run_name, s.g_level)},
      {"data", {{"values", values}}},
      {"facet",
       {{"row", {{"field", "axis"}, {"type", "nominal"}, {"sort", {"IA", "PA", "OA"}}, {"title", nullptr}}}}},
      {"resolve", {{"scale", {{"y", "independent"}}}}},
      {"spec",
       {{"width", 420},
        {"height", 90},
        {"mark", {{"type", "line"}, {"strokeWidth", 1.5}}},
        {"encoding",
         {{"x", {{"field", "t"}, {"type", "quantitative"}, {"title", "time into the run [s]"}}},
          {"y", {{"field", "f"}, {"type", "quantitative"}, {"title", "[g]"}, {"scale", {{"zero", false}}}}},
          {"color", {{"field", "axis"}, {"type", "nominal"}, {"legend", nullptr}}}}}}}};
  std::string t =
      "<table class=\"input\"><caption>The exact input at three instants (<code>ccal "
      "force</code>)</caption>\n"
      "<tr><th>t [s]</th><th>IA [g]</th><th>PA [g]</th><th>OA [g]</th><th>IA, first order [g]</th></tr>\n";
  for (std::size_t i = 0; i < instants.size(); ++i) {
    const Doc d{fmt::format("force{}", i), instants[i]};
    t += "<tr>" + num_cell(d, "/run/time_s", 6) + num_cell(d, "/specific_force_g/IA", 8) +
         num_cell(d, "/specific_force_g/PA", 6) + num_cell(d, "/specific_force_g/OA", 6) +
         num_cell(d, "/first_order/total/f_IA_g", 8) + "</tr>\n";
  }
  t += "</table>\n";
  const bool whole = s.window >= s.duration;
  return fmt::format(
      "<section id=\"input\"><h2>The sensed input over one run</h2>\n<p>Run {} ({:g} g, {:g} s): the "
      "specific "
      "force along the instrument's input (IA), pendulous (PA) and output (OA) axes from the exact kinematic "
      "chain with the configured [errors], {}.</p>\n<div class=\"pair\">\n{}{}</div>\n</section>\n",
      escape(s.run_name), s.g_level, s.duration,
      whole ? std::string("over the whole run")
            : fmt::format(
                  "over its first three platform revolutions ({:.4g} s; the rest of the run repeats them)",
                  s.window),
      chart("sensed-input", spec), t);
}

}  // namespace ccal::render::report_html
