// The HTML report of `ccal report`: the page around its sections (report_*.cpp), the summary, the provenance
// and the script that draws the charts.
#include "ccal/render/report.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <ctime>
#include <stdexcept>

#include "ccal/core/sha256.hpp"
#include "ccal/render/allocate.hpp"
#include "ccal/render/budget.hpp"
#include "ccal/render/design.hpp"
#include "ccal/render/force.hpp"
#include "ccal/render/history.hpp"
#include "ccal/render/identify.hpp"
#include "ccal/render/montecarlo.hpp"
#include "ccal/version.hpp"
#include "certificate_page.hpp"
#include "certificate_parts.hpp"
#include "report_html.hpp"

namespace ccal::render {
namespace {

using namespace report_html;

constexpr std::size_t kTopSources = 8;  // rows of each budget table before "the other sources"

constexpr const char* kStyle = R"(
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;margin:24px auto;
max-width:1440px;color:#222;padding:0 16px}
h1{font-size:1.6em;margin-bottom:0}h2{border-bottom:2px solid #4c78a8;padding-bottom:4px;margin-top:2em}
.sub{color:#555;margin-top:4px}
.pair{display:flex;flex-wrap:wrap;gap:24px;align-items:flex-start;margin:16px 0}
.chart{min-width:340px}
table{border-collapse:collapse;font-size:0.86em;margin:8px 0}
caption{text-align:left;font-weight:600;padding:4px 0}
th,td{border:1px solid #ccc;padding:3px 7px;vertical-align:top}th{background:#f2f5f9;text-align:left}
td.num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
tr.total td{font-weight:600;background:#f7f7f7}tr.rest td{font-style:italic}
td.quantity{min-width:8em}td.quantity .desc{font-size:0.85em;color:#555}
td.good{color:#1a7f37;font-weight:600}td.bad{color:#b42318;font-weight:600}
.setup-grid{display:flex;flex-wrap:wrap;gap:20px;align-items:flex-start}
pre{background:#f6f8fa;border:1px solid #ddd;padding:10px;overflow:auto;font-size:0.8em;max-height:480px}
.advice{max-width:520px;color:#8a4b00}
code{background:#f2f2f2;padding:0 3px}
table.result{font-size:1.05em}table.result td{padding:4px 10px}
table.certificate{font-size:0.95em}table.certificate th{width:14em}
.signatures{display:flex;gap:48px;margin:40px 0 12px}.signature{flex:1;max-width:300px}
.signature .line{border-bottom:1px solid #222;height:44px;margin-bottom:4px}.small{font-size:0.8em;color:#555}
@media print{body{max-width:none;margin:0;padding:0;font-size:9pt}.chart{break-inside:avoid;min-width:0}
pre{max-height:none;white-space:pre-wrap;overflow-wrap:anywhere}tr,.signatures{break-inside:avoid}
h2{break-after:avoid}.annex{break-before:page}details::details-content{content-visibility:visible;display:block}
td.num{white-space:normal}table.result td{padding:3px 6px}table.design-coefficients th,table.design-coefficients td{padding:2px 4px}table.statement{font-size:6.5pt}table.statement th,table.statement td{padding:1px 2px}
table.statement caption{font-size:9pt}
table.budget{font-size:6.5pt}table.budget th,table.budget td{padding:1px 2px}table.budget td.num{white-space:nowrap}
table.budget caption{font-size:9pt}
table.result,table.statement,table.certificate,table.summary,table.statement-correlation,table.statement-output{
break-inside:avoid}}
)";

// Draws every chart of the page; window.ccalReport resolves when all are drawn (rejects if one fails, after
// writing the error to the console).
constexpr const char* kDraw = R"(
(function () {
  var jobs = [];
  document.querySelectorAll('script.vl-spec').forEach(function (s) {
    var target = document.getElementById(s.dataset.target);
    jobs.push(vegaEmbed(target, JSON.parse(s.textContent), {renderer: 'svg', actions: false})
      .then(function (r) { target.dataset.rendered = 'yes'; return r; }));
  });
  window.ccalReport = Promise.all(jobs).then(function () {
    document.body.dataset.charts = String(jobs.length);
  }, function (e) { console.error('ccal report: a chart failed: ' + e); throw e; });
  // A printed page shows what a collapsed block holds.
  window.addEventListener('beforeprint', function () {
    document.querySelectorAll('details').forEach(function (d) { d.open = true; });
  });
})();
)";

}  // namespace

// "</script" would end the element early, so it is written "<\/script" (the same characters to JavaScript,
// inside a string or a regular expression alike).
std::string script_text(std::string_view scripts) {
  std::string out(scripts);
  for (std::size_t at = 0; (at = out.find("</script", at)) != std::string::npos; at += 2)
    out.replace(at, 2, "<\\/");
  return out;
}

namespace {

// An argument as a POSIX shell reads it back: as it is when it has only safe characters, else in quotes.
std::string shell_word(const std::string& a) {
  const bool safe = !a.empty() && a.find_first_not_of(
                                      "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                      "0123456789_-+=.,/:@%^") == std::string::npos;
  if (safe) return a;
  std::string out = "'";
  for (char c : a) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// A file as the report names it: its name without the folders of the machine it was made on.
std::string shown_file(std::string_view path) { return certificate_parts::base_name(path); }

// The command line as typed, every absolute path in it (a word, or an option's value after '=') written as its
// file name: no folder of the machine stands in the report.
std::string without_folders(std::string_view line) {
  std::string out;
  std::size_t i = 0;
  while (i < line.size()) {
    const std::size_t end = std::min(line.find(' ', i), line.size());
    std::string word(line.substr(i, end - i));
    const std::size_t eq = word.rfind('=', word.find('/'));
    const std::size_t from = word.starts_with("/") || word.starts_with("'/") ? 0
                             : eq != std::string::npos && word.find('/') == eq + 1 ? eq + 1
                                                                                    : std::string::npos;
    if (from != std::string::npos) {
      const bool quoted = word[from] == '\'';
      std::string path = word.substr(from + (quoted ? 1 : 0));
      if (quoted && path.ends_with("'")) path.pop_back();
      word = word.substr(0, from) + (quoted ? "'" : "") + shown_file(path) + (quoted ? "'" : "");
    }
    out += word;
    if (end < line.size()) out += ' ';
    i = end + 1;
  }
  return out;
}

// The command line of a verb: its name, the configuration (none for the bundled example), its options;
// `config` replaces the configuration's path when it is given.
std::string command_text(const std::vector<std::string>& args, const Config& config,
                         const std::string& extra = {}, const std::string& config_path = {}) {
  std::vector<std::string> words{"ccal"};
  for (const auto& a : args) {
    words.push_back(shell_word(a));
    if (&a != &args.front()) continue;
    if (!config_path.empty())
      words.push_back(shell_word(config_path));
    else if (config.source.rfind("bundled:", 0) != 0)
      words.push_back(shell_word(shown_file(config.source)));
  }
  std::string out;
  for (const auto& w : words) out.append(out.empty() ? "" : " ").append(w);
  return out.append(extra).append(" --format json");
}

constexpr const char* kDesignedPlan = "designed.toml";  // the file `ccal design --plan-out` writes

// `ccal identify OBS.csv --statement --config CONFIG … --format json` from the command's words (identify,
// OBS.csv, --statement, …); the bundled example's file is its copy in the source tree.
std::string identify_command_text(const std::vector<std::string>& args, const Config& config) {
  std::vector<std::string> words = args;
  const bool bundled = config.source.rfind("bundled:", 0) == 0;
  words.insert(words.begin() + std::min<std::ptrdiff_t>(3, std::ptrdiff_t(words.size())),
               {"--config", bundled ? "examples/" + config.source.substr(8) : shown_file(config.source)});
  std::string out = "ccal";
  for (const auto& w : words) out.append(" ").append(shell_word(w));
  return out.append(" --format json");
}

std::string summary(const Doc& budget, const Doc& mc) {
  // Each U names its method and its k and p: the LPU's normal k beside the Monte Carlo's interval of the
  // same p (coverage.hpp).
  std::string t = fmt::format(
      "<table class=\"summary\"><caption>Summary per identified coefficient</caption>\n<tr><th>coefficient</th>"
      "<th>unit</th><th>u<sub>c</sub> (LPU)</th><th>U (LPU, k = {}, p = {} %)</th><th>Monte Carlo u(y)</th>"
      "<th colspan=\"2\">Monte Carlo {} % interval</th><th>LPU validated</th></tr>\n",
      num_span(budget, "/coverage_factor", 3), num_span(budget, "/coverage_probability", 4, 100),
      num_span(mc, "/coverage_probability", 4, 100));
  for (std::size_t k = 0; k < budget.json["coefficients"].size(); ++k) {
    const Json& c = budget.json["coefficients"][k];
    const std::string id = c["id"].get<std::string>(), b = fmt::format("/coefficients/{}", k),
                      m = "/coefficients/" + id;
    const bool ok = mc.json["coefficients"][id]["lpu"]["validated"].get<bool>();
    t += "<tr>" + text_cell(id) + text_cell(c["unit"].get<std::string>()) +
         num_cell(budget, b + "/standard_uncertainty") + num_cell(budget, b + "/expanded_uncertainty") +
         num_cell(mc, m + "/std_dev") + num_cell(mc, m + "/symmetric_interval/0") +
         num_cell(mc, m + "/symmetric_interval/1") +
         fmt::format("<td class=\"{}\">{}</td></tr>\n", ok ? "good" : "bad", ok ? "yes" : "no");
  }
  return t + "</table>\n";
}

// The command lines of the allocation and the design sections, for the provenance table.
std::string section_commands(const verbs::ReportResult& r, const ReportProvenance& p) {
  std::string out;
  if (r.allocation)
    out += "<br><code id=\"cmd-allocate\">" + escape(command_text(p.allocate_command, r.config)) + "</code>";
  if (r.design) {
    out +=
        "<br><code id=\"cmd-design\">" +
        escape(command_text(p.design_command, r.config, std::string(" --plan-out ") + kDesignedPlan)) +
        "</code><br><code>" + escape(command_text({"budget"}, r.config)) + "</code>, <code>" +
        escape(command_text({"budget"}, r.config, {}, kDesignedPlan)) +
        "</code> (the budgets of both plans)<br><code>ccal force … --run K --time 0</code> (the configured "
        "plan's runs)";
  }
  if (r.observed)
    out += "<br><code id=\"cmd-identify\">" + escape(identify_command_text(p.identify_command, r.config)) +
           "</code> (the calibration statement)";
  return out;
}

// The run logs of the observations, each by run, file and fingerprint ("" when the file records none).
std::string log_rows(const std::vector<ObservationsHeader::Log>& logs) {
  if (logs.empty()) return "";
  std::string cells;
  for (const ObservationsHeader::Log& log : logs)
    cells += fmt::format("{}<span class=\"log\" data-run=\"{}\">{}: <code>{}</code>, SHA-256 <code>{}</code></span>",
                         cells.empty() ? "" : "<br>", escape(log.run), escape(log.run),
                         escape(log.file.starts_with("/") ? shown_file(log.file) : log.file),
                         escape(log.sha256));
  return fmt::format("<tr><th>run logs ({})</th><td>{}</td></tr>\n", logs.size(), cells);
}

// The observations file of the statement, by name and fingerprint, as the configuration is.
std::string observations_rows(const verbs::ReportResult& r, const ReportProvenance& p) {
  if (!r.observed) return "";
  return fmt::format(
      "<tr><th>observations</th><td><code>{}</code></td></tr>\n"
      "<tr><th>SHA-256 of the observations</th><td><code id=\"observations-sha256\">{}</code></td></tr>\n{}",
      escape(shown_file(r.observed->source)), escape(p.observations_sha256), log_rows(p.observation_logs));
}

std::string provenance_section(const verbs::ReportResult& r, const ReportProvenance& p) {
  return fmt::format(
      "<section id=\"provenance\"><h2>Provenance</h2>\n<table class=\"provenance\">\n"
      "<tr><th>program</th><td>{}</td></tr>\n<tr><th>command line</th><td><code>{}</code></td></tr>\n"
      "<tr><th>date (UTC)</th><td>{}</td></tr>\n<tr><th>configuration</th><td><code>{}</code></td></tr>\n"
      "<tr><th>SHA-256 of the configuration</th><td><code id=\"config-sha256\">{}</code></td></tr>\n{}"
      "<tr><th>the same numbers from</th><td><code id=\"cmd-budget\">{}</code><br><code "
      "id=\"cmd-montecarlo\">{}"
      "</code><br><code>ccal force … --run {} --time T</code> (the input table){}</td></tr>\n</table>\n"
      "<h3>The configuration ({} bytes)</h3>\n<pre id=\"config-text\">{}</pre>\n</section>\n",
      escape(version_line()), escape(without_folders(p.command_line)), escape(p.date_utc),
      escape(shown_file(r.config.source)),
      sha256_hex(p.config_text), observations_rows(r, p), escape(command_text(p.budget_command, r.config)),
      escape(command_text(p.montecarlo_command, r.config)), r.sensed_input.run_index + 1,
      section_commands(r, p), p.config_text.size(), escape(p.config_text));
}

// The allocation and the design sections (when the result has them), each output their cells name added to
// `sources` with its command line.
std::string optional_sections(const verbs::ReportResult& r, const ReportProvenance& p, Json& sources) {
  std::string out;
  if (r.allocation) {
    const Json allocate_json = Json::parse(json(*r.allocation));
    sources["allocate"] = {{"command", p.allocate_command}};
    out += allocation_section(Doc{"allocate", allocate_json}, *r.allocation);
  }
  if (r.design) {
    const Json design_json = Json::parse(json(*r.design)), before_json = Json::parse(json(r.design->before)),
               after_json = Json::parse(json(r.design->after));
    sources["design"] = {{"command", p.design_command}, {"writes", {{"--plan-out", kDesignedPlan}}}};
    sources["design-before"] = {{"command", {"budget"}}};
    sources["design-after"] = {{"command", {"budget"}}, {"config", kDesignedPlan}};
    std::vector<Json> run_jsons;
    std::vector<Doc> runs;
    for (const auto& f : r.configured_runs) run_jsons.push_back(Json::parse(json(f)));
    for (std::size_t k = 0; k < run_jsons.size(); ++k) {
      const std::string name = fmt::format("configured-run{}", k + 1);
      sources[name] = {{"command", {"force", "--run", std::to_string(k + 1), "--time", "0"}}};
      runs.push_back(Doc{name, run_jsons[k]});
    }
    const Doc design{"design", design_json}, before{"design-before", before_json},
        after{"design-after", after_json};
    out += design_section(DesignDocs{design, before, after, runs});
  }
  return out;
}

// The calibration statement (with observations): the page's first section, the result a laboratory files.
std::string statement_first(const verbs::ReportResult& r, const ReportProvenance& p, Json& sources) {
  if (!r.observed) return "";
  const Json identify_json = Json::parse(json(*r.observed));
  sources["identify"] = {{"command", p.identify_command}, {"config_option", "--config"}};
  return statement_section(Doc{"identify", identify_json});
}

// The printed page: A4, its number and count at the foot beside the report's name.
std::string page_css(const verbs::ReportResult& r) {
  const std::string left =
      r.config.certificate && !r.config.certificate->number.empty()
          ? "Engineering report for certificate " + r.config.certificate->number
          : "ccal report: " + shown_file(r.config.source);
  return fmt::format(
      "@page{{size:A4;margin:14mm 12mm 16mm;@bottom-left{{content:{};font-size:8pt;color:#555}}"
      "@bottom-right{{content:\"Page \" counter(page) \" of \" counter(pages);font-size:8pt;color:#555}}}}\n",
      css_string(left));
}

// The command lines a section names must be there: report_commands fills them from the report's options.
void require_commands(const verbs::ReportResult& r, const ReportProvenance& p) {
  if (r.allocation && p.allocate_command.empty())
    throw std::logic_error(
        "report: the allocation's command line is missing (report_commands with its options)");
  if (r.design && p.design_command.empty())
    throw std::logic_error("report: the design's command line is missing (report_commands with its options)");
  if (r.observed && p.identify_command.empty())
    throw std::logic_error(
        "report: the statement's command line is missing (report_commands with its options)");
}

// The verbs' outputs as the cells name them (the check reads them back), with their command lines: the
// budget, the Monte Carlo and `ccal force` at each instant of the sensed input.
Json verb_sources(const verbs::ReportResult& r, const ReportProvenance& p,
                  const std::vector<Json>& instants) {
  Json sources = {{"budget", {{"command", p.budget_command}}},
                  {"montecarlo", {{"command", p.montecarlo_command}}}};
  for (std::size_t i = 0; i < instants.size(); ++i)
    sources[fmt::format("force{}", i)] = {
        {"command",
         {"force", "--run", std::to_string(r.sensed_input.run_index + 1), "--time",
          fmt::format("{:.17g}", instants[i]["run"]["time_s"].get<double>())}}};
  return sources;
}

// The page's head and title: the configuration (and the certificate it reports for), the mode, the date and
// the program that wrote it.
std::string page_head(const verbs::ReportResult& r, const ReportProvenance& p, const std::string& mode) {
  const std::string name =
      r.config.certificate && !r.config.certificate->number.empty()
          ? "certificate " + r.config.certificate->number + " · " + shown_file(r.config.source)
          : shown_file(r.config.source);
  const char* title = r.observed ? "Centrifuge calibration: engineering report"
                                 : "Centrifuge calibration: uncertainty report";
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{5}: "
      "{0}</title>\n<meta name=\"generator\" content=\"{4}\">\n<meta name=\"dcterms.created\" "
      "content=\"{3}\">\n"
      "<style>{1}{6}</style>\n</head>\n<body>\n<h1>{5}</h1>\n"
      "<p class=\"sub\">{0} · {2} mode · {3} · {4}</p>\n",
      escape(name), kStyle, escape(mode), escape(p.date_utc), escape(version_line()), title, page_css(r));
}

}  // namespace

std::string report_date_utc() {
  std::time_t t = std::time(nullptr);
  if (const char* e = std::getenv("SOURCE_DATE_EPOCH"); e && *e) t = std::time_t(std::strtoll(e, nullptr, 10));
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", fmt::gmtime(t));
}

void report_commands(const verbs::ReportResult& r, const verbs::ReportOptions& o, ReportProvenance& p) {
  // Each section's command: the verb and every option the report gave it that is not the verb's default.
  const verbs::ReportSections s = verbs::report_sections(o);
  const auto command = [](std::string verb, const auto& options) {
    std::vector<std::string> c{std::move(verb)};
    for (std::string& a : option_arguments(options, option_table<std::remove_cvref_t<decltype(options)>>()))
      c.push_back(std::move(a));
    return c;
  };
  p.budget_command = command("budget", s.budget);
  p.montecarlo_command = command("montecarlo", s.monte_carlo);
  if (s.allocate) p.allocate_command = command("allocate", *s.allocate);
  if (s.design) p.design_command = command("design", *s.design);
  if (o.observations && r.observed) {
    // As verbs::report identifies them (the configuration, --config, is added where the command is shown).
    p.identify_command = command("identify", s.identify);
    p.identify_command.insert(p.identify_command.begin() + 1, shown_file(r.observed->source));
    p.observations_sha256 = o.observations->text_sha256;
    if (const auto header = observations_header(*o.observations)) p.observation_logs = header->logs;
  }
}

std::string html(const verbs::ReportResult& r, const ReportProvenance& provenance, std::string_view scripts,
                 const std::vector<ReportSection>& extra_sections) {
  ReportProvenance p = provenance;
  if (p.budget_command.empty()) report_commands(r, {}, p);
  require_commands(r, p);
  // With observations and a [certificate] table the page is the certificate, unless the engineering report was
  // asked for (verbs::gives_certificate).
  if (r.certificate) return certificate_page(r, p);
  const Json budget_json = Json::parse(json(r.budget)), mc_json = Json::parse(json(r.monte_carlo));
  std::vector<Json> instants;
  for (const auto& f : r.sensed_input.instants) instants.push_back(Json::parse(json(f)));
  const Doc budget{"budget", budget_json}, mc{"montecarlo", mc_json};
  Json sources = verb_sources(r, p, instants);

  std::string statement_html = statement_first(r, p, sources);
  if (r.history) {  // beside the statement: the same instrument's earlier calibrations
    sources["history"] = {{"command", {"history", "show", r.history->serial, "--db", r.history->db}},
                          {"no_config", true}};
    statement_html += history_section(Doc{"history", Json::parse(json(*r.history))});
  }
  const std::string section_html = optional_sections(r, p, sources);

  std::vector<std::string> advice;
  for (const std::string& line : validation_advice_lines(r.monte_carlo)) advice.push_back(line);

  std::string page = page_head(r, p, budget_json["mode"].get<std::string>());
  page += "<script type=\"application/json\" id=\"ccal-sources\">" + script_json(sources) + "</script>\n";
  page += statement_html;
  page += summary(budget, mc);
  page += setup_section(r.config, p.config_text);
  page += budget_section(budget, kTopSources);
  page += section_html;
  for (const auto& s : extra_sections)
    page +=
        "<section id=\"" + escape(s.id) + "\"><h2>" + escape(s.title) + "</h2>\n" + s.html + "</section>\n";
  page += montecarlo_section(mc, advice);
  page += paper_section(budget, kTopSources);
  page += sensed_input_section(r.sensed_input, instants);
  page += provenance_section(r, p);
  page += "<script>" + script_text(scripts) + "</script>\n<script>" + kDraw + "</script>\n</body>\n</html>\n";
  return page;
}

}  // namespace ccal::render
