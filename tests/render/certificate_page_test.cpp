// The calibration certificate as a customer reads it (src/render/certificate_page.cpp, with the sections of
// certificate_result.cpp and certificate_annex.cpp), rendered in-process from examples/lab.toml's
// [certificate] and observations simulated from it: the parts ISO/IEC 17025 §7.8.2 requires, in order (title
// and number, the administrative fields, the result, the model, the method, the traceability, the signatures,
// annex A and annex B, the records and the end mark), the revision and the certificate it replaces when given,
// every text of the configuration escaped, and no command line, option or folder of this machine.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/render/report.hpp"
#include "ccal/verbs/report.hpp"
#include "ccal/verbs/simulate.hpp"
#include "test_paths.hpp"

namespace ccal {
namespace certificate_page_render_test {

Config lab() { return load_config(CCAL_SOURCE_DIR + "/examples/lab.toml"); }

std::string certificate_of(const Config& config) {
  verbs::ReportOptions o;
  o.input_points = 3;
  o.statement_trials = 0;
  o.observations = parse_csv(verbs::simulate(lab()).observations_csv, "obs.csv");
  const verbs::ReportResult r = verbs::report(config, o);
  EXPECT_TRUE(r.certificate);
  render::ReportProvenance p;
  p.config_text = "the configuration's bytes";
  p.date_utc = "2026-12-03T10:00:00Z";
  render::report_commands(r, o, p);
  return render::html(r, p, "/* the charting library */");
}

TEST(CertificatePage, EveryRequiredPartInItsOrder) {
  const std::string page = certificate_of(lab());
  const std::vector<std::string> parts = {
      "<title>Certificate CAL-2026-0142</title>",
      "<h1>Calibration certificate</h1>",
      "No. <span data-field=\"number\">CAL-2026-0142</span>",
      "<td data-field=\"laboratory\">Inertial Test Laboratory, 12 Centrifuge Road, Harbin</td>",
      "<td data-field=\"customer\">Example Navigation Systems Ltd.</td>",
      "<td data-field=\"serial_number\">SN 0815</td>",
      "<td data-field=\"date_of_calibration\">2026-11-30</td>",
      "<td data-field=\"date_of_issue\">2026-12-03</td>",
      "<section id=\"result\"",
      "<section id=\"model\"",
      "<section id=\"method\"",
      "<section id=\"traceability\"",
      "<section id=\"signatures\">",
      "Calibrated by: A. Engineer",
      "Approved by: B. Head of Laboratory",
      "This certificate may be reproduced only in full.",
      "<section id=\"annex-budget\"",
      "<section id=\"annex-runs\"",
      "Records of this calibration: observations obs.csv (SHA-256 ",
      "<p class=\"end\" id=\"end\">End of certificate</p>",
  };
  std::size_t at = 0;
  for (const std::string& part : parts) {
    const auto found = page.find(part, at);
    ASSERT_NE(found, std::string::npos) << "missing or out of order: " << part;
    at = found + part.size();
  }
  // The fields that have places of their own are not repeated among the administrative ones.
  EXPECT_EQ(page.find("data-field=\"operator\""), std::string::npos);
  EXPECT_EQ(page.find("data-field=\"revision\""), std::string::npos);  // none given
  // Page x of y at the foot of every printed page, with the number.
  EXPECT_NE(page.find("@bottom-left{content:\"Certificate CAL-2026-0142\""), std::string::npos);
  EXPECT_NE(page.find("counter(pages)"), std::string::npos);
  // The customer reads no command line, option or path.
  EXPECT_EQ(page.find("--"), std::string::npos);
  EXPECT_EQ(page.find(CCAL_SOURCE_DIR), std::string::npos);
}

TEST(CertificatePage, ARevisionNamesTheCertificateItReplacesAndTextIsEscaped) {
  Config config = lab();
  config.certificate->revision = "1";
  config.certificate->replaces = "CAL-2026-0142";
  config.certificate->number = "CAL-2026-0142A";
  config.certificate->remarks = "tested <after> repair & adjustment";
  const std::string page = certificate_of(config);
  EXPECT_NE(page.find("No. <span data-field=\"number\">CAL-2026-0142A</span>, revision <span "
                      "data-field=\"revision\">1</span>; replaces certificate <span "
                      "data-field=\"replaces\">CAL-2026-0142</span>"),
            std::string::npos);
  EXPECT_NE(page.find("content:\"Certificate CAL-2026-0142A, revision 1\""), std::string::npos);
  // The revision is part of the number, not a row of the administrative fields.
  const auto revision = page.find("data-field=\"revision\"");
  ASSERT_NE(revision, std::string::npos);
  EXPECT_EQ(page.find("data-field=\"revision\"", revision + 1), std::string::npos);
  EXPECT_NE(page.find("<h2>Remarks</h2>\n<p data-field=\"remarks\">tested &lt;after&gt; repair &amp; "
                      "adjustment</p>"),
            std::string::npos);
  // Without signatories the lines stay, blank, for a hand to sign.
  config.certificate->operator_name.clear();
  EXPECT_NE(certificate_of(config).find("Calibrated by: &nbsp;"), std::string::npos);
}

}  // namespace certificate_page_render_test
}  // namespace ccal
