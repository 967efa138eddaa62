// The certificate page of `ccal report --observations` with a [certificate] table: the administrative fields as
// the configuration writes them, the method in a paragraph (the plan and the model), and the signature lines.
// The result itself is the statement section (report_statement.cpp); the budget and the rest of the report
// follow as the annex.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <vector>

#include "ccal/core/units.hpp"
#include "ccal/model/plan.hpp"
#include "report_html.hpp"

namespace ccal::render::report_html {
namespace {

// Numbers of a list, each written with `digits` significant digits, joined ("5, 10, 15, 20").
std::string number_list(const std::vector<double>& values, int digits) {
  std::vector<std::string> out;
  for (double v : values) out.push_back(fmt::format("{:.{}g}", v, digits));
  return fmt::format("{}", fmt::join(out, ", "));
}

// The distinct values of a list, in order of first appearance.
std::vector<double> distinct(const std::vector<double>& values) {
  std::vector<double> out;
  for (double v : values)
    if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
  return out;
}

std::string plan_sentence(const Config& config) {
  const std::vector<Run>& runs = config.plan.runs;
  std::vector<double> g, duration;
  std::set<std::string> platforms;
  for (const Run& run : runs) {
    g.push_back(run.g_level);
    duration.push_back(run.duration);
    platforms.insert(run.mode == PlatformMode::counter_rotating ? "counter-rotating" : "fixed");
  }
  std::sort(g.begin(), g.end());
  const std::vector<double> levels = distinct(g), durations = distinct(duration);
  return fmt::format(
      "The instrument was tested on a precision centrifuge of arm radius R<sub>0</sub> = {} m, its platform {}, in "
      "{} runs at the g-levels {} g, each of {} s{}.",
      fmt::format("{:.6g}", config.centrifuge.geometry.R0),
      platforms.size() == 1 ? *platforms.begin() : "counter-rotating or fixed by run",
      runs.size(), number_list(levels, 6), number_list(durations, 6),
      config.site.earth_rotation ? fmt::format(", at latitude {:.6g}° with the Earth's rotation in the model",
                                               config.site.latitude * 180 / std::numbers::pi)
                                 : "");
}

// Which intervals the Monte Carlo check (JCGM 101 §8) left to the Student t, and which it replaced.
std::string monte_carlo_sentence(const Json& statement) {
  if (statement["monte_carlo"].is_null()) return "";
  std::vector<std::string> replaced;
  for (const auto& [id, c] : statement["coefficients"].items())
    if (c["interval_method"] == "monte_carlo") replaced.push_back(escape(id));
  const std::string trials = fmt::format("{}", statement["monte_carlo"]["trials"].get<std::uint64_t>());
  if (replaced.empty())
    return fmt::format(" A Monte Carlo propagation of the same quantities (JCGM 101, {} trials) validated every "
                       "interval.", trials);
  return fmt::format(" A Monte Carlo propagation of the same quantities (JCGM 101, {} trials) did not validate "
                     "the interval of {}, whose stated interval is therefore the Monte Carlo's.",
                     trials, fmt::join(replaced, ", "));
}

std::string model_sentence(const Config& config, const Doc& identify) {
  const IdentificationSpec& spec = config.identification;
  std::vector<std::string> held;
  for (const auto& [id, value] : spec.fixed_terms) held.push_back(escape(id));
  const std::string mode = escape(identify.json["statement"]["mode"].get<std::string>());
  return fmt::format(
      "The mean output of each run was modelled as the instrument's model equation of the specific force and "
      "the inertial rate that the centrifuge's kinematic chain gives it ({} kinematics), and the "
      "coefficients {} were identified from the run means by least squares{}. The uncertainty follows JCGM 100: "
      "Type A from the scatter of the run means about the fitted model, Type B from the centrifuge's stated "
      "tolerances ({} error sources, the budget of the annex) propagated through the same model; their "
      "combination, ν<sub>eff</sub> by Welch–Satterthwaite and k from Student's t give U and the interval.{}",
      mode, escape(fmt::format("{}", fmt::join(spec.free_terms, ", "))),
      held.empty()       ? std::string()
      : held.size() == 1 ? fmt::format(", the term {} held at the instrument's configured value", held.front())
                         : fmt::format(", the terms {} held at the instrument's configured values",
                                       fmt::join(held, ", ")),
      config.tolerances.size(), monte_carlo_sentence(identify.json["statement"]));
}

}  // namespace

std::string css_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\' || c == '<' || c == '>' || c == '\n' || c == '\r' || c == '&')
      out += fmt::format("\\{:x} ", static_cast<unsigned char>(c));
    else
      out += c;
  }
  return out + "\"";
}

std::string certificate_head(const Certificate& certificate) {
  std::string out = "<header id=\"certificate\">\n<table class=\"certificate\">\n";
  for (const CertificateField& f : kCertificateFields) {
    const std::string& value = certificate.*f.member;
    if (value.empty() || f.key == "operator" || f.key == "approved_by") continue;  // those sign below
    out += fmt::format("<tr><th>{}</th><td data-field=\"{}\">{}</td></tr>\n", escape(f.label), escape(f.key),
                       escape(value));
  }
  return out + "</table>\n</header>\n";
}

std::string method_section(const Config& config, const Doc& identify) {
  return fmt::format(
      "<section id=\"method\"><h2>Method</h2>\n<p>{} {} The observations <code>{}</code> and the configuration "
      "<code>{}</code> are identified by their SHA-256 under Provenance.</p>\n</section>\n",
      plan_sentence(config), model_sentence(config, identify), escape(identify.json["file"].get<std::string>()),
      escape(config.source));
}

std::string signature_section(const Certificate& certificate) {
  std::string out = "<section id=\"signatures\" class=\"signatures\">\n";
  for (const auto& [label, name] : {std::pair<std::string_view, const std::string&>{"Calibrated by",
                                                                                      certificate.operator_name},
                                    {"Approved by", certificate.approved_by}})
    out += fmt::format(
        "<div class=\"signature\"><div class=\"line\"></div><div>{}: {}</div><div>Date:</div></div>\n",
        escape(label), name.empty() ? "&nbsp;" : escape(name));
  return out +
         "</section>\n<p class=\"small\">This certificate may be reproduced only in full. The result refers only "
         "to the item calibrated, at the time of its calibration.</p>\n";
}

}  // namespace ccal::render::report_html
