// The [certificate] table (docs/config.md): every field read as written, the dates as TOML dates or strings of
// a real day, and every bad value refused on its line, naming the key and what is accepted.
#include <fmt/format.h>

#include <map>
#include <tuple>

#include "ccal/setup/input_description.hpp"
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
  // A control character went into the certificate (and a serial so made was refused only by the history):
  // none in a serial or a number, line breaks and tabs alone in free text.
  expect_appended_error("[certificate]\nserial_number = \"SN\\u0000X\"", "certificate.serial_number",
                        {"'SN\\x00X' holds a control character; accepted: printable text on one line"});
  expect_appended_error("[certificate]\nnumber = \"CAL\\n1\"", "certificate.number",
                        {"'CAL\\n1' holds a control character"});
  expect_appended_error("[certificate]\nremarks = \"a\\u001bb\"", "certificate.remarks",
                        {"holds a control character; accepted: printable text (line breaks and tabs allowed)"});
  const Config free_text = parse_config(kBase + "\n[certificate]\nremarks = \"line 1\\nline 2\"", "case.toml");
  EXPECT_EQ(free_text.certificate->remarks, "line 1\nline 2");
}

TEST(CertificateTable, RevisionIsANumberOrAText) {
  const Config n = parse_config(kBase + "\n[certificate]\nnumber = \"C-2\"\nrevision = 1\nreplaces = \"C-1\"", "case.toml");
  EXPECT_EQ(n.certificate->revision, "1");
  EXPECT_EQ(n.certificate->replaces, "C-1");
  EXPECT_EQ(parse_config(kBase + "\n[certificate]\nrevision = \"A\"", "case.toml").certificate->revision, "A");
}

TEST(CertificateTable, AnAmendmentNamesItsRevisionAndAnotherCertificate) {
  expect_appended_error("[certificate]\nreplaces = \"C-1\"", "certificate.replaces",
                        {"without certificate.revision", "revision = 1"});
  expect_appended_error("[certificate]\nnumber = \"C-1\"\nrevision = 1\nreplaces = \"C-1\"", "certificate.replaces",
                        {"this certificate's own number"});
  expect_appended_error("[certificate]\nrevision = -1", "certificate.revision", {"a revision number such as 1"});
  expect_appended_error("[certificate]\ndate_of_calibration = 2026-12-03\ndate_of_receipt = 2026-12-04",
                        "certificate.date_of_receipt", {"after the date of calibration 2026-12-03"});
}

TEST(CertificateTable, TraceabilityByKindOrInputIdInTheOrderWritten) {
  const Config c = parse_config(kBase + "\n[tolerances]\ndR_s = \"25 um\"\n[certificate]\nradius_standard = \"LT-1\"\n"
                                        "[certificate.traceability]\ntemperature = \"PT100, T-9\"\ng = \"gravimeter, "
                                        "G-3\"\ndR_s = \"laser tracker, LT-1\"",
                                "case.toml");
  const std::vector<std::pair<std::string, std::string>> expected{
      {"temperature", "PT100, T-9"}, {"g", "gravimeter, G-3"}, {"dR_s", "laser tracker, LT-1"}};
  EXPECT_EQ(c.certificate->traceability, expected);
  EXPECT_EQ(traceability_label("g"), "local gravity g");
  EXPECT_EQ(traceability_label("dR_s"), "dR_s");  // an input: the budget names it
  expect_appended_error("[certificate.traceability]\nradious = \"LT-1\"", "certificate.traceability.radious",
                        {"names no quantity of the budget",
                         "radius, length, angle, rate, time_base, g, output, fixed_terms, temperature"});
  expect_appended_error("[certificate.traceability]\ng = 9.8", "certificate.traceability.g", {"expected a string"});
  expect_appended_error("[certificate.traceability]\ng = \" \"", "certificate.traceability.g", {"is empty"});
  expect_appended_error("[certificate]\nrate_standard = \"TB-1\"\n[certificate.traceability]\nrate = \"TB-2\"",
                        "certificate.traceability.rate", {"certificate.rate_standard states it already"});
  expect_appended_error("[certificate]\nfixed_terms_source = \"CAL-1\"\n[certificate.traceability]\nfixed_terms = "
                        "\"CAL-2\"",
                        "certificate.traceability.fixed_terms", {"certificate.fixed_terms_source states it already"});
}

TEST(CertificateTraceability, EveryInputRestsOnItsOwnLineOrItsKindsOrOnANotStatedOne) {
  Certificate c;
  c.radius_standard = "laser tracker, LT-1";
  c.fixed_terms_source = "dividing head, CAL-7";
  c.traceability = {{"g", "gravimeter, G-3"}, {"dthz5", "autocollimator, AC-2"}, {"temperature", "PT100, T-9"}};
  const std::vector<TracedInput> inputs{{"dR_s", "radius"},  {"dthz5", "angle"},       {"dthx4", "angle"},
                                        {"dx5", "length"},   {"g", "g"},              {"K1", "fixed_terms"},
                                        {"dthy5", "angle"},  {"time_base", "time_base"}};
  const std::vector<TraceabilityLine> lines = traceability_lines(c, inputs);
  // The stated lines in the order written (radius_standard first, fixed_terms_source after the table), then
  // the kinds nobody stated, in the order the inputs first need them; dthz5 rests on its own line.
  const std::vector<std::tuple<std::string, std::string, std::vector<std::string>>> expected{
      {"radius", "laser tracker, LT-1", {"dR_s"}},
      {"g", "gravimeter, G-3", {"g"}},
      {"dthz5", "autocollimator, AC-2", {"dthz5"}},
      {"temperature", "PT100, T-9", {}},
      {"fixed_terms", "dividing head, CAL-7", {"K1"}},
      {"angle", "", {"dthx4", "dthy5"}},
      {"length", "", {"dx5"}},
      {"time_base", "", {"time_base"}}};
  ASSERT_EQ(lines.size(), expected.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].key, std::get<0>(expected[i])) << i;
    EXPECT_EQ(lines[i].standard, std::get<1>(expected[i])) << i;
    EXPECT_EQ(lines[i].inputs, std::get<2>(expected[i])) << i;
  }
  EXPECT_EQ(traceability_gaps_text(lines),
            "the certificate states no traceability for angles of the axes and of the mounting (dthx4, dthy5); "
            "lengths of the machine (runouts, floats, offsets) (dx5); time base (time_base); it shows them as "
            "not stated (state them in [certificate.traceability]: angle, length, time_base)");
  c.traceability.emplace_back("angle", "electronic level, EL-1");
  c.traceability.emplace_back("length", "probes, DP-4");
  c.traceability.emplace_back("time_base", "rubidium, TB-1");
  EXPECT_EQ(traceability_gaps_text(traceability_lines(c, inputs)), "");
}

TEST(CertificateTraceability, EachInputHasTheKindOfItsStandard) {
  // The kind of every input comes from what it is (setup/input_description.cpp): the radius's error and the
  // arm's stretch rest on the radius, runouts on lengths, tilts on angles, rates, ripples and encoders on the
  // rate, and the measuring chain's inputs on their own standards.
  const Config cfg = bundled_example();  // the paper's layout: every kind of error, ripples and stretch too
  const ErrorLayout& layout = cfg.centrifuge.layout;
  std::map<std::string, std::string> kinds;
  for (int p = 0; p < layout.size(); ++p) kinds[layout.parameter_id(p)] = describe_layout_parameter(layout, p).traceability;
  EXPECT_EQ(kinds.at("dR_s"), "radius");
  EXPECT_EQ(kinds.at("arm_stretch"), "radius");
  EXPECT_EQ(kinds.at("dx5"), "length");
  EXPECT_EQ(kinds.at("dthz5"), "angle");
  EXPECT_EQ(kinds.at("domega"), "rate");
  EXPECT_EQ(kinds.at("ripple1_c1"), "rate");
  for (const auto& [id, kind] : kinds) EXPECT_FALSE(kind.empty()) << id;
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
