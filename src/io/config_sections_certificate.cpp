// The configuration file's [certificate] table: the administrative fields of the calibration certificate
// (setup/certificate.hpp, docs/config.md).
#include "ccal/setup/certificate.hpp"
#include "config_reader.hpp"

namespace ccal::config_reading {

std::optional<Certificate> read_certificate(const Reader& r, const toml::table& root) {
  const toml::table* t = r.table(root, "", "certificate", false);
  if (!t) return std::nullopt;
  Keys keys;
  for (const CertificateField& f : kCertificateFields) keys.emplace_back(f.key);
  r.check_keys(*t, "certificate", keys);
  Certificate c;
  for (const CertificateField& f : kCertificateFields) {
    const toml::node* n = t->get(f.key);
    if (!n) continue;
    const std::string p = Reader::path("certificate", f.key);
    std::string value;
    if (const auto* d = n->as_date(); d && f.date) {
      const toml::date& v = d->get();
      value = fmt::format("{:04}-{:02}-{:02}", v.year, v.month, v.day);
    } else if (const auto* s = n->as_string()) {
      value = s->get();
    } else {
      r.fail(*n, p,
             fmt::format("expected {}, got {}", f.date ? "a date such as 2026-12-03" : "a string such as \"…\"",
                         type_name(*n)));
    }
    if (value.find_first_not_of(" \t\r\n") == std::string::npos)
      r.fail(*n, p, "is empty; accepted: the text the certificate shows, or no key at all");
    if (f.date)
      if (const std::string problem = calendar_date_problem(value); !problem.empty()) r.fail(*n, p, problem);
    c.*f.member = std::move(value);
  }
  // YYYY-MM-DD compares as text in calendar order.
  if (!c.date_of_calibration.empty() && !c.date_of_issue.empty() && c.date_of_issue < c.date_of_calibration)
    r.fail(*t->get("date_of_issue"), "certificate.date_of_issue",
           fmt::format("{} is before the date of calibration {}; accepted: the day of the calibration or later",
                       c.date_of_issue, c.date_of_calibration));
  return c;
}

}  // namespace ccal::config_reading
