// The configuration file's [certificate] table: the administrative fields of the calibration certificate
// (setup/certificate.hpp, docs/config.md), and its [certificate.traceability] table.
#include <fmt/ranges.h>

#include <algorithm>

#include "../core/text_shown.hpp"
#include "ccal/setup/certificate.hpp"
#include "config_reader.hpp"

namespace ccal::config_reading {
namespace {

// The ids a traceability key may name besides the kinds: those of [tolerances] and of [[inputs]], as written.
std::vector<std::string> input_ids(const toml::table& root) {
  std::vector<std::string> ids;
  if (const toml::table* t = root["tolerances"].as_table())
    for (const auto& [key, node] : *t) ids.emplace_back(key.str());
  if (const toml::array* a = root["inputs"].as_array())
    for (const toml::node& n : *a)
      if (const toml::table* input = n.as_table())
        if (const auto id = (*input)["id"].value<std::string>()) ids.push_back(*id);
  return ids;
}

// [certificate.traceability]: key = "the standard and its certificate", in the order written.
std::vector<std::pair<std::string, std::string>> read_traceability(const Reader& r,
                                                                   const toml::table& certificate,
                                                                   const toml::table& root,
                                                                   const Certificate& c) {
  std::vector<std::pair<std::string, std::string>> out;
  const toml::table* t = r.table(certificate, "certificate", "traceability", false);
  if (!t) return out;
  std::vector<std::string> accepted;
  for (const TraceabilityKind& k : kTraceabilityKinds) accepted.emplace_back(k.key);
  const std::vector<std::string> ids = input_ids(root);
  for (const auto& [key, node] : *t) {
    const std::string k(key.str()), p = Reader::path("certificate.traceability", k);
    if (std::find(accepted.begin(), accepted.end(), k) == accepted.end() &&
        std::find(ids.begin(), ids.end(), k) == ids.end())
      r.fail(node, p,
             fmt::format("names no quantity of the budget; accepted: {} or an input id of [tolerances] or "
                         "[[inputs]]",
                         fmt::join(accepted, ", ")));
    const auto* s = node.as_string();
    if (!s) r.fail(node, p, fmt::format("expected a string such as \"…\", got {}", type_name(node)));
    if (s->get().find_first_not_of(" \t\r\n") == std::string::npos)
      r.fail(node, p, "is empty; accepted: the standard and its certificate, or no key at all");
    // The kinds [certificate] can state with a key of its own: one place each.
    for (const auto& [kind, field, member] :
         {std::tuple{"radius", "radius_standard", &Certificate::radius_standard},
          {"rate", "rate_standard", &Certificate::rate_standard},
          {"fixed_terms", "fixed_terms_source", &Certificate::fixed_terms_source}})
      if (k == kind && !(c.*member).empty())
        r.fail(node, p, fmt::format("certificate.{} states it already; accepted: one of the two", field));
    out.emplace_back(k, s->get());
  }
  // toml++ iterates a table by key: the certificate lists them in the order the file writes them.
  std::sort(out.begin(), out.end(), [t](const auto& a, const auto& b) {
    const toml::source_position pa = t->get(a.first)->source().begin, pb = t->get(b.first)->source().begin;
    return pa.line != pb.line ? pa.line < pb.line : pa.column < pb.column;
  });
  return out;
}

// A field's text: a date as YYYY-MM-DD (a TOML date, or text that is one), a string, or the revision as a
// whole number; not empty, and without control characters (on one line for the numbers looked up).
std::string certificate_field_value(const Reader& r, const toml::node& n, const CertificateField& f) {
  const std::string p = Reader::path("certificate", f.key);
  std::string value;
  if (const auto* d = n.as_date(); d && f.date) {
    const toml::date& v = d->get();
    value = fmt::format("{:04}-{:02}-{:02}", v.year, v.month, v.day);
  } else if (const auto* s = n.as_string()) {
    value = s->get();
  } else if (const auto* i = n.as_integer(); i && f.key == "revision" && i->get() >= 0) {
    value = std::to_string(i->get());  // revision = 1
  } else {
    r.fail(n, p,
           fmt::format("expected {}, got {}",
                       f.date                ? "a date such as 2026-12-03"
                       : f.key == "revision" ? "a revision number such as 1, or a string such as \"A\""
                                             : "a string such as \"…\"",
                       type_name(n)));
  }
  if (value.find_first_not_of(" \t\r\n") == std::string::npos)
    r.fail(n, p, "is empty; accepted: the text the certificate shows, or no key at all");
  // A serial number or a certificate's number is looked up and printed on one line; free text may break
  // lines. No other control character (a NUL, an escape) is text a certificate can print.
  const bool one_line =
      f.key == "serial_number" || f.key == "number" || f.key == "replaces" || f.key == "revision";
  if (std::any_of(value.begin(), value.end(), [one_line](char ch) {
        return detail::is_control(ch) && (one_line || (ch != '\n' && ch != '\t'));
      }))
    r.fail(n, p,
           fmt::format("{} holds a control character; accepted: printable text{}",
                       detail::shown_text(value, '\''),
                       one_line ? " on one line, e.g. \"SN 0815\"" : " (line breaks and tabs allowed)"));
  if (f.date)
    if (const std::string problem = calendar_date_problem(value); !problem.empty()) r.fail(n, p, problem);
  return value;
}

// The fields together: the dates in order (receipt, calibration, issue), and an amendment naming its revision
// and another certificate than itself.
void check_certificate_fields(const Reader& r, const toml::table& t, const Certificate& c) {
  // YYYY-MM-DD compares as text in calendar order.
  if (!c.date_of_calibration.empty() && !c.date_of_issue.empty() && c.date_of_issue < c.date_of_calibration)
    r.fail(
        *t.get("date_of_issue"), "certificate.date_of_issue",
        fmt::format("{} is before the date of calibration {}; accepted: the day of the calibration or later",
                    c.date_of_issue, c.date_of_calibration));
  if (!c.date_of_receipt.empty() && !c.date_of_calibration.empty() &&
      c.date_of_calibration < c.date_of_receipt)
    r.fail(
        *t.get("date_of_receipt"), "certificate.date_of_receipt",
        fmt::format("{} is after the date of calibration {}; accepted: the day of the calibration or earlier",
                    c.date_of_receipt, c.date_of_calibration));
  // An amended certificate (ISO/IEC 17025 §7.8.8) names its revision beside the certificate it replaces.
  if (!c.replaces.empty() && c.revision.empty())
    r.fail(*t.get("replaces"), "certificate.replaces",
           "is set without certificate.revision; accepted: revision = 1 (or the amendment's revision) beside "
           "it");
  if (!c.replaces.empty() && c.replaces == c.number)
    r.fail(*t.get("replaces"), "certificate.replaces",
           fmt::format(
               "'{}' is this certificate's own number; accepted: the number of the certificate it replaces",
               c.replaces));
}

}  // namespace

std::optional<Certificate> read_certificate(const Reader& r, const toml::table& root) {
  const toml::table* t = r.table(root, "", "certificate", false);
  if (!t) return std::nullopt;
  Keys keys;
  for (const CertificateField& f : kCertificateFields) keys.emplace_back(f.key);
  keys.emplace_back("traceability");
  r.check_keys(*t, "certificate", keys);
  Certificate c;
  for (const CertificateField& f : kCertificateFields) {
    const toml::node* n = t->get(f.key);
    if (!n) continue;
    c.*f.member = certificate_field_value(r, *n, f);
  }
  check_certificate_fields(r, *t, c);
  c.traceability = read_traceability(r, *t, root, c);
  return c;
}

}  // namespace ccal::config_reading
