// The [certificate] table (docs/config.md): every field read as written, the dates as TOML dates or strings of
// a real day, and every bad value refused on its line, naming the key and what is accepted.
#include <fmt/format.h>

#include "config_test_support.hpp"

namespace ccal {
namespace {

using namespace config_test;

// A TOML basic string of a text: quotes and backslashes escaped.
std::string toml_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) out += c == '"' || c == '\\' ? std::string{'\\', c} : std::string{c};
  return out + "\"";
}

// The text each field is given in the test: markup, an ampersand, a non-ASCII letter and a quote, all kept.
std::string written(const CertificateField& f) {
  return f.date ? std::string("2026-12-03") : fmt::format("<{}> & \u00fc \"", f.key);
}

TEST(CertificateTable, AbsentIsUnsetAndEveryFieldIsReadAsWritten) {
  EXPECT_FALSE(parse_config(kBase, "case.toml").certificate.has_value());
  std::string text = kBase + "\n[certificate]\n";
  for (const CertificateField& f : kCertificateFields)
    text += fmt::format("{} = {}\n", f.key, toml_string(written(f)));
  const Config c = parse_config(text, "case.toml");
  ASSERT_TRUE(c.certificate.has_value());
  for (const CertificateField& f : kCertificateFields) EXPECT_EQ((*c.certificate).*f.member, written(f)) << f.key;
  EXPECT_EQ(c.certificate->operator_name, "<operator> & \u00fc \"");  // the key "operator" sets operator_name
}

TEST(CertificateTable, DatesAreTomlDatesOrStrings) {
  const Config c = parse_config(kBase + "\n[certificate]\ndate_of_calibration = 2024-02-29\n"
                                        "date_of_issue = \"2024-03-01\"",
                                "case.toml");
  EXPECT_EQ(c.certificate->date_of_calibration, "2024-02-29");
  EXPECT_EQ(c.certificate->date_of_issue, "2024-03-01");
}

TEST(CertificateTable, BadValuesAreRefusedOnTheirLine) {
  expect_appended_error("[certificate]\nnumbr = \"1\"", "certificate.numbr", {"unknown key", "did you mean 'number'?"});
  expect_appended_error("[certificate]\nserial_number = 815", "certificate.serial_number",
                        {"expected a string", "integer"});
  expect_appended_error("[certificate]\ncustomer = \"  \"", "certificate.customer", {"is empty", "no key at all"});
  expect_appended_error("[certificate]\ndate_of_issue = \"3.12.2026\"", "certificate.date_of_issue",
                        {"not written YYYY-MM-DD", "2026-12-03"});
  expect_appended_error("[certificate]\ndate_of_issue = \"2025-02-29\"", "certificate.date_of_issue",
                        {"month 2 of 2025 has no day 29"});
  expect_appended_error("[certificate]\ndate_of_issue = \"2026-13-01\"", "certificate.date_of_issue",
                        {"no month 13"});
  expect_appended_error("[certificate]\ndate_of_issue = 2026-12-03T10:00:00", "certificate.date_of_issue",
                        {"expected a date such as 2026-12-03"});
  expect_appended_error("[certificate]\nnumber = 2026-12-03", "certificate.number", {"expected a string"});
  expect_appended_error("[certificate]\ndate_of_calibration = 2026-12-03\ndate_of_issue = 2026-12-02",
                        "certificate.date_of_issue", {"before the date of calibration 2026-12-03"});
  expect_error("certificate = \"CAL-1\"\n" + kBase, 1, "certificate", {"expected a table"});
}

TEST(CertificateDates, OnlyRealDaysOfTheGregorianCalendar) {
  EXPECT_EQ(calendar_date_problem("2000-02-29"), "");  // divisible by 400: a leap year
  EXPECT_NE(calendar_date_problem("1900-02-29"), "");  // divisible by 100 only: not one
  EXPECT_EQ(calendar_date_problem("2026-12-31"), "");
  EXPECT_NE(calendar_date_problem("2026-04-31"), "");
  EXPECT_NE(calendar_date_problem("2026-00-10"), "");
  EXPECT_NE(calendar_date_problem("2026-1-10"), "");
  EXPECT_NE(calendar_date_problem("1899-12-31"), "");
  EXPECT_NE(calendar_date_problem("20x6-12-03"), "");
}

}  // namespace
}  // namespace ccal
