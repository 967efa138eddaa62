// The certificate's first part: the result per coefficient, the model equation with its free and fixed terms
// and the unit g, the method in the customer's words, and the traceability of the quantities the budget
// holds.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>

#include "ccal/model/instrument.hpp"
#include "ccal/model/plan.hpp"
#include "certificate_parts.hpp"

namespace ccal::render::certificate_parts {
namespace {

using report_html::escape;

// Numbers joined in words: "5, 10 and 15".
std::string list_in_words(const std::vector<std::string>& items) {
  if (items.empty()) return "";
  if (items.size() == 1) return items.front();
  std::vector<std::string> head(items.begin(), items.end() - 1);
  return fmt::format("{} and {}", fmt::join(head, ", "), items.back());
}

// The distinct values of a list in increasing order, each with `digits` significant digits.
std::vector<std::string> distinct_sorted(std::vector<double> values, int digits) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  std::vector<std::string> out;
  for (double v : values) out.push_back(fmt::format("{:.{}g}", v, digits));
  return out;
}

// A term's regressor as typeset HTML (a_i², |a_i| a_i, ω_IA, …).
std::string regressor_html(const TermSpec& t) {
  const std::string ai = "a<sub>i</sub>", ap = "a<sub>p</sub>", ao = "a<sub>o</sub>";
  switch (t.kind) {
    case TermKind::power:
      return t.power == 0 ? "" : t.power == 1 ? ai : ai + "<sup>" + std::to_string(t.power) + "</sup>";
    case TermKind::abs_square:
      return "|" + ai + "| " + ai;
    case TermKind::p:
      return ap;
    case TermKind::o:
      return ao;
    case TermKind::ip:
      return ai + " " + ap;
    case TermKind::io:
      return ai + " " + ao;
    case TermKind::pp:
      return ap + "<sup>2</sup>";
    case TermKind::oo:
      return ao + "<sup>2</sup>";
    case TermKind::po:
      return ap + " " + ao;
    case TermKind::rate:
      return "ω<sub>IA</sub>";
  }
  return "";
}

// The statement's input of a fixed term (its uncertainty), or null when the budget holds none.
const Json* input_of(const Json& statement, const std::string& id) {
  for (const Json& in : statement["inputs"])
    if (in["id"] == id) return &in;
  return nullptr;
}

// What g stands for in the units: the local g with its value, or standard gravity.
std::string g_sentence(const Config& config) {
  if (config.site.unit_g > 0)
    return fmt::format(
        "g<sub>n</sub> is standard gravity, g<sub>n</sub> = {} m/s² (the unit of the g-levels and "
        "of the coefficients)",
        fmt::format("{:.10g}", config.site.unit_g));
  return fmt::format(
      "g is the local acceleration due to gravity at the test site, g = {} m/s² (the unit of the "
      "g-levels and of the coefficients)",
      fmt::format("{:.10g}", config.site.g));
}

}  // namespace

std::string result_section(const Doc& doc) {
  const Json& st = doc.json["statement"];
  // A stated k gives its normal coverage probability, which the certificate rounds; a stated probability is
  // shown as given.
  const double probability = st["coverage_probability"].get<double>();
  const std::string p_text =
      st["coverage_factor"].is_number() ? approximate_percent_text(probability) : percent_text(probability);
  std::string rows, notes;
  bool monte_carlo = false;
  for (const auto& [id, c] : st["coefficients"].items()) {
    const std::string p = "/statement/coefficients/" + id;
    const bool mc = c["interval_method"] == "monte_carlo";
    monte_carlo = monte_carlo || mc;
    rows += fmt::format(
        "<tr data-coefficient=\"{}\"><td>{}</td>{}{}<td>{}</td><td class=\"num\">{}</td><td class=\"num "
        "nowrap\">[{}, {}]</td><td data-method=\"{}\">{}</td></tr>\n",
        escape(id), term_html(id), report_html::text_num_cell(doc, p + "/rounded/estimate"),
        mc ? std::string("<td class=\"num\">–</td>")
           : report_html::text_num_cell(doc, p + "/rounded/expanded_uncertainty"),
        unit_html(c["unit"].get<std::string>()),
        mc ? "–" : coverage_factor_text(c["coverage_factor"].get<double>()),
        report_html::text_num_span(doc, p + "/rounded/interval/0"),
        report_html::text_num_span(doc, p + "/rounded/interval/1"), escape(id), method_html(c));
    if (!c["significant"].get<bool>())
      notes += fmt::format(
          "<li>The interval of {0} contains zero: this calibration does not distinguish {0} from "
          "zero at a coverage probability of {1}.</li>\n",
          term_html(id), p_text);
  }
  std::string out = fmt::format(
      "<section id=\"result\" class=\"keep\"><h2>Result</h2>\n<p>The coefficients of the instrument's model "
      "equation (see "
      "<i>Model and units</i>), each with its expanded uncertainty U and the interval that contains the "
      "value "
      "with a coverage probability of approximately {0}:</p>\n<table "
      "class=\"result\">\n<tr><th>coefficient</th>"
      "<th>value</th><th>U</th><th>unit</th><th>k</th><th>interval ({0})</th><th>how the interval is "
      "obtained</th></tr>\n{1}</table>\n",
      p_text, rows);
  if (!notes.empty()) out += "<ul class=\"notes\">\n" + notes + "</ul>\n";
  out += fmt::format(
      "<p>The reported expanded uncertainty U is the combined standard uncertainty u<sub>c</sub> multiplied "
      "by the "
      "coverage factor k, which for the normal distribution, or Student's t distribution at the stated "
      "effective "
      "degrees of freedom ν<sub>eff</sub>, corresponds to a coverage probability of approximately {}; the "
      "uncertainty was evaluated in accordance with EA-4/02 and JCGM 100 (GUM), U written to two significant "
      "digits and the value to the same decimal place.{}</p>\n</section>\n",
      p_text,
      monte_carlo ? " Where the interval is obtained by Monte Carlo (JCGM 101), it is the probabilistically "
                    "symmetric interval of the propagated distribution, stated by its ends: it need not be "
                    "centred on the value, so no U and k are given."
                  : "");
  return out;
}

std::string model_section(const verbs::ReportResult& r, const Doc& doc) {
  const Config& config = r.config;
  const IdentificationSpec& spec = config.identification;
  const Json& identify = doc.json;
  std::vector<std::string> terms, free_html, fixed_rows;
  for (const std::string& id : config.instrument.term_ids) {
    const bool free = std::find(spec.free_terms.begin(), spec.free_terms.end(), id) != spec.free_terms.end();
    const bool fixed = identify["fixed"].contains(id);
    if (!free && !fixed) continue;
    const auto term = parse_term(id);
    const std::string regressor = term ? regressor_html(*term) : std::string();
    terms.push_back(term_html(id) + (regressor.empty() ? "" : " " + regressor));
    if (free) free_html.push_back(term_html(id));
  }
  std::string equation = "y = " + fmt::format("{}", fmt::join(terms, " + "));
  if (config.instrument.rate_gain != 0) equation += fmt::format(" + s<sub>ω</sub> ω<sub>IA</sub>");
  const std::string output_unit = unit_html(config.instrument.output_unit);
  for (const auto& [id, f] : identify["fixed"].items()) {
    const Json* in = input_of(identify["statement"], id);
    const std::string source = config.certificate && !config.certificate->fixed_terms_source.empty()
                                   ? escape(config.certificate->fixed_terms_source)
                                   : "not stated";
    fixed_rows.push_back(fmt::format(
        "<tr><td>{}</td><td class=\"num\">{}</td><td>{}</td><td class=\"num\">{}</td><td>{}</td></tr>\n",
        term_html(id), number_html(f["value"].get<double>(), 10), unit_html(f["unit"].get<std::string>()),
        in ? number_html((*in)["u"].get<double>(), 2) + " " + unit_html((*in)["unit"].get<std::string>())
           : std::string("taken as exact"),
        source));
  }
  std::string out = fmt::format(
      "<section id=\"model\" class=\"keep\"><h2>Model and units</h2>\n<p class=\"equation\">{}</p>\n<p>where "
      "y is the "
      "instrument's output in {}, a<sub>i</sub>, a<sub>p</sub>, a<sub>o</sub> the specific force along its "
      "input, "
      "pendulous and output axes in g{}. {}. The coefficients {} were determined by this calibration",
      equation, output_unit,
      config.instrument.rate_gain != 0
          ? fmt::format(", ω<sub>IA</sub> the inertial angular rate about its input axis with the known gain "
                        "s<sub>ω</sub> = {:.6g} (the output in SI units per rad/s)",
                        config.instrument.rate_gain)
          : std::string(),
      g_sentence(config), list_in_words(free_html));
  if (fixed_rows.empty()) return out + ".</p>\n</section>\n";
  out +=
      "; the fixed terms were held at these values, whose uncertainty enters the budget (Annex A):</p>\n"
      "<table class=\"fixed\">\n<tr><th>fixed term</th><th>value</th><th>unit</th><th>standard "
      "uncertainty</th><th>source of the value</th></tr>\n";
  for (const std::string& row : fixed_rows) out += row;
  return out + "</table>\n</section>\n";
}

std::string method_section(const verbs::ReportResult& r, const Doc& doc) {
  const Config& config = r.config;
  const Json& st = doc.json["statement"];
  std::vector<double> g, duration;
  std::set<std::string> platforms;
  for (const Run& run : config.plan.runs) {
    g.push_back(run.g_level);
    duration.push_back(run.duration);
    platforms.insert(run.mode == PlatformMode::counter_rotating ? "counter-rotating" : "fixed");
  }
  const std::string g_symbol = config.site.unit_g > 0 ? "g<sub>n</sub>" : "g";
  std::string out = fmt::format(
      "<section id=\"method\"><h2>Method</h2>\n<p>The instrument was mounted on the platform of a precision "
      "centrifuge of arm radius {} m ({}) and tested in {} runs at the g-levels {} {}, each of {} s{}; the "
      "mean "
      "output of each run was recorded (Annex B). The specific force and the inertial rate at the instrument "
      "were "
      "computed for each run from the centrifuge's geometry and rotation rates ({}), and the coefficients "
      "were "
      "fitted to the run means by least squares{}.",
      fmt::format("{:.6g}", config.centrifuge.geometry.R0),
      platforms.size() == 1 ? "platform " + *platforms.begin()
                            : std::string("platform counter-rotating or fixed "
                                          "by run"),
      config.plan.runs.size(), list_in_words(distinct_sorted(g, 6)), g_symbol,
      list_in_words(distinct_sorted(duration, 6)),
      config.site.earth_rotation ? fmt::format(", at latitude {:.6g}°, the Earth's rotation included",
                                               config.site.latitude * 180 / std::numbers::pi)
                                 : "",
      st["mode"] == "exact" ? "the complete kinematic chain" : "the first-order model of the kinematic chain",
      doc.json["fixed"].empty() ? "" : ", the fixed terms held at their stated values");
  if (st["known_errors"].get<int>() > 0)
    out += st["compensated"].get<bool>()
               ? " The centrifuge's errors measured before the test are included in that computation."
               : " The result is corrected for the centrifuge's errors measured before the test.";
  out +=
      " The uncertainty was evaluated in accordance with JCGM 100 (GUM): Type A from the noise of the run "
      "means, Type B from the uncertainties of the inputs listed in Annex A (the centrifuge's geometry and "
      "rotation rates and the other quantities of the model), those measured during this test at the "
      "uncertainty of that measurement, the others at their stated tolerances.";
  if (!st["monte_carlo"].is_null()) {
    std::vector<std::string> replaced;
    for (const auto& [id, c] : st["coefficients"].items())
      if (c["interval_method"] == "monte_carlo") replaced.push_back(term_html(id));
    out += fmt::format(
        " Each interval was checked by a Monte Carlo propagation of the same distributions (JCGM 101, {} "
        "trials)"
        "{}.",
        st["monte_carlo"]["trials"].get<std::uint64_t>(),
        replaced.empty()
            ? std::string(", which confirmed it")
            : fmt::format("; where it did not confirm the interval ({}), the Monte Carlo interval is "
                          "stated",
                          list_in_words(replaced)));
  }
  return out + "</p>\n</section>\n";
}

std::string traceability_section(const verbs::ReportResult& r, const Doc& budget) {
  if (!r.config.certificate) return "";
  const std::vector<TraceabilityLine>& rows = r.traceability;
  if (rows.empty()) return "";
  std::string t =
      "<section id=\"traceability\" class=\"keep\"><h2>Traceability</h2>\n<p>The quantities of the "
      "uncertainty budget "
      "are traceable to national standards (SI) through these standards:</p>\n<table "
      "class=\"traceability\">\n<tr><th>quantity</th><th>standard and its certificate</th></tr>\n";
  for (const TraceabilityLine& line : rows) {
    std::string label(traceability_label(line.key));
    if (label == line.key)  // an input id: the budget's words for it
      for (const Json& s : budget.json["sources"])
        if (s["id"] == line.key) label = s["name"].get<std::string>();
    // A quantity of the budget whose standard the laboratory did not state is shown as such, not left out.
    t += fmt::format("<tr><td>{}</td><td>{}</td></tr>\n", words_html(label),
                     line.standard.empty() ? std::string("<em class=\"unstated\">not stated</em>")
                                           : escape(line.standard));
  }
  return t + "</table>\n</section>\n";
}

}  // namespace ccal::render::certificate_parts
