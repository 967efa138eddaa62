// The calibration certificate (ISO/IEC 17025 §7.8, EA-4/02): `ccal report CONFIG --observations OBS` with a
// [certificate] table. One result in the customer's words: the administrative fields, the result, the model
// equation with its free and fixed terms and the unit g, the method, the traceability, the signatures; then
// Annex A (the uncertainty budget) and Annex B (the runs), and the end mark. Printed on A4 with the number,
// the revision and "page x of y" at the foot of every page; its PDF metadata from the <head>
// (render/pdf_info.hpp).
#include "certificate_page.hpp"

#include <fmt/format.h>

#include "ccal/core/sha256.hpp"
#include "ccal/render/budget.hpp"
#include "ccal/render/identify.hpp"
#include "ccal/version.hpp"
#include "certificate_parts.hpp"

namespace ccal::render {
namespace {

using report_html::css_string;
using report_html::escape;
using namespace certificate_parts;

constexpr const char* kStyle = R"(
body{font-family:"DejaVu Sans",system-ui,sans-serif;margin:24px auto;max-width:980px;color:#111;padding:0 16px;
font-size:10.5pt;line-height:1.35}
h1{font-size:1.7em;margin:0 0 2px}h2{font-size:1.15em;border-bottom:1.5px solid #333;padding-bottom:2px;
margin:1.3em 0 0.5em;break-after:avoid}
p.number{font-size:1.15em;margin:0 0 12px}
table{border-collapse:collapse;margin:6px 0;max-width:100%}
th,td{border:1px solid #999;padding:3px 6px;vertical-align:top;text-align:left}th{background:#eee}
td.num{text-align:right;font-variant-numeric:tabular-nums}.nowrap{white-space:nowrap}
table.fields{border:none;width:100%}table.fields th,table.fields td{border:none;border-bottom:1px solid #ddd;
background:none}table.fields th{width:15em;font-weight:600}
p.equation{font-size:1.15em;text-align:center;margin:10px 0}
table.gum{font-size:8.5pt}table.gum th,table.gum td{padding:2px 4px}tr.total td{font-weight:600}
.signatures{display:flex;gap:48px;margin:36px 0 12px;break-inside:avoid}.signature{flex:1;max-width:300px}
.signature .line{border-bottom:1px solid #111;height:44px;margin-bottom:4px}
.small{font-size:0.85em;color:#333}
p.end{text-align:center;font-weight:600;margin-top:24px;letter-spacing:0.05em}
table.gum{width:100%}table.gum td:first-child{min-width:12em}table.gum td:nth-child(2){min-width:9em}table.gum tr{break-inside:avoid}
.keep{break-inside:avoid}tr{break-inside:avoid}
@media print{body{max-width:none;margin:0;padding:0;font-size:9.5pt}table.gum{font-size:7.5pt}
table.gum td:first-child{min-width:9em}table.gum td:nth-child(2){min-width:7em}}
)";

// The certificate's fields: the administrative ones as written (those that sign, the traceability and the
// source of the fixed terms have their own places).
std::string fields_table(const Certificate& c) {
  std::string out = "<table class=\"fields\">\n";
  for (const CertificateField& f : kCertificateFields) {
    const std::string& value = c.*f.member;
    if (value.empty() || f.key == "operator" || f.key == "approved_by" || f.key == "remarks" ||
        f.key == "radius_standard" || f.key == "rate_standard" || f.key == "fixed_terms_source" ||
        f.key == "number" || f.key == "revision" || f.key == "replaces")
      continue;
    out += fmt::format("<tr><th>{}</th><td data-field=\"{}\">{}</td></tr>\n", escape(f.label), escape(f.key),
                       escape(value));
  }
  return out + "</table>\n";
}

// The number as the certificate names itself: with its revision and the certificate it replaces
// (ISO/IEC 17025 §7.8.8).
std::string identification(const Certificate& c) {
  std::string out =
      "No. <span data-field=\"number\">" + escape(c.number.empty() ? "(no number)" : c.number) + "</span>";
  if (!c.revision.empty())
    out += ", revision <span data-field=\"revision\">" + escape(c.revision) + "</span>";
  if (!c.replaces.empty())
    out += "; replaces certificate <span data-field=\"replaces\">" + escape(c.replaces) + "</span>";
  return out;
}

std::string signatures(const Certificate& c) {
  std::string out = "<section id=\"signatures\">\n";
  if (!c.remarks.empty())
    out += "<h2>Remarks</h2>\n<p data-field=\"remarks\">" + escape(c.remarks) + "</p>\n";
  out += "<div class=\"signatures\">\n";
  for (const auto& [label, name] :
       {std::pair<std::string_view, const std::string&>{"Calibrated by", c.operator_name},
        {"Approved by", c.approved_by}})
    out += fmt::format(
        "<div class=\"signature\"><div class=\"line\"></div><div>{}: {}</div><div>Date:</div></div>\n",
        escape(label), name.empty() ? "&nbsp;" : escape(name));
  return out +
         "</div>\n<p class=\"small\">This certificate may be reproduced only in full. The result refers only "
         "to the "
         "item calibrated, at the time of its calibration.</p>\n</section>\n";
}

// The laboratory's records of the test: the files by name and SHA-256 (never their folders).
std::string records(const verbs::ReportResult& r, const ReportProvenance& p) {
  return fmt::format(
      "<p class=\"small\" id=\"records\">Records of this calibration: observations {} (SHA-256 {}), set-up "
      "{} "
      "(SHA-256 {}).</p>\n",
      escape(base_name(r.observed->source)), escape(p.observations_sha256),
      escape(base_name(r.config.source)), sha256_hex(p.config_text));
}

std::string page_css(const Certificate& c) {
  std::string left = "Certificate " + (c.number.empty() ? std::string("(no number)") : c.number);
  if (!c.revision.empty()) left += ", revision " + c.revision;
  return fmt::format(
      "@page{{size:A4;margin:16mm 14mm 18mm;@bottom-left{{content:{};font-size:8pt;color:#333}}"
      "@bottom-right{{content:\"Page \" counter(page) \" of \" counter(pages);font-size:8pt;color:#333}}}}\n",
      css_string(left));
}

}  // namespace

std::string certificate_page(const verbs::ReportResult& r, const ReportProvenance& p) {
  const Certificate& c = *r.config.certificate;
  const report_html::Json identify_json = report_html::Json::parse(json(*r.observed)),
                          budget_json = report_html::Json::parse(json(r.budget));
  const Doc identify{"identify", identify_json}, budget{"budget", budget_json};
  const std::string title = "Certificate " + (c.number.empty() ? std::string("(no number)") : c.number);
  std::string subject = "Calibration certificate";
  if (!c.instrument.empty()) subject += " of " + c.instrument;
  if (!c.serial_number.empty()) subject += ", serial number " + c.serial_number;
  std::string page = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" "
      "content=\"width=device-width, initial-scale=1\">\n<title>{}</title>\n<meta name=\"author\" "
      "content=\"{}\">\n"
      "<meta name=\"description\" content=\"{}\">\n<meta name=\"generator\" content=\"{}\">\n<meta "
      "name=\"dcterms.created\" content=\"{}\">\n<style>{}{}</style>\n</head>\n<body>\n",
      escape(title), escape(c.laboratory), escape(subject), escape(version_line()), escape(p.date_utc),
      kStyle, page_css(c));
  page += fmt::format(
      "<header id=\"certificate\">\n<h1>Calibration certificate</h1>\n<p "
      "class=\"number\">{}</p>\n{}</header>\n",
      identification(c), fields_table(c));
  page += result_section(identify);
  page += model_section(r, identify);
  page += method_section(r, identify);
  page += traceability_section(r, budget);
  page += signatures(c);
  page += budget_annex(identify, budget);
  page += runs_annex(r, identify);
  page +=
      "<div class=\"keep\">" + records(r, p) + "<p class=\"end\" id=\"end\">End of certificate</p>\n</div>\n";
  page += "</body>\n</html>\n";
  return page;
}

}  // namespace ccal::render
