// Annex A of the calibration certificate (src/render/certificate_annex.cpp), the uncertainty budget as a GUM
// table, on the certificate of examples/lab.toml's [certificate] and observations simulated from it: one row
// per input that acts on a coefficient (the others counted in a sentence), each with its type and distribution,
// u(x_i), c_i and u_i per coefficient; then the Type A row and the totals (u_c, nu_eff, k to two decimals, U as
// the statement rounds it, or the Monte Carlo's interval and no k), and how each interval is obtained.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/render/report.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/statement.hpp"
#include "ccal/verbs/report.hpp"
#include "ccal/verbs/simulate.hpp"
#include "test_paths.hpp"

namespace ccal {
namespace certificate_annex_render_test {

struct Certified {
  verbs::ReportResult result;
  std::string annex;  // the page's Annex A section
};

Certified certified(std::int64_t statement_trials) {
  const Config lab = load_config(CCAL_SOURCE_DIR + "/examples/lab.toml");
  verbs::ReportOptions o;
  o.input_points = 3;
  o.statement_trials = statement_trials;
  o.observations = parse_csv(verbs::simulate(lab).observations_csv, "obs.csv");
  Certified c{verbs::report(lab, o), ""};
  render::ReportProvenance p;
  render::report_commands(c.result, o, p);
  const std::string page = render::html(c.result, p, "");
  const auto from = page.find("<section id=\"annex-budget\"");
  const auto to = page.find("</section>", from);
  EXPECT_NE(from, std::string::npos);
  c.annex = page.substr(from, to - from);
  return c;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(CertificateAnnex, OneRowPerActingInputTheRestCounted) {
  const Certified c = certified(0);
  const verbs::CalibrationStatement& st = *c.result.observed->statement;
  int acting = 0, silent = 0;
  for (const verbs::StatementSource& s : st.inputs) {
    bool acts = false;  // beyond the derivatives' round-off on some coefficient (kRoundOffFloor of its u_c)
    for (std::size_t k = 0; k < s.effect.size(); ++k)
      acts = acts || std::abs(s.effect[k]) >= kRoundOffFloor * st.coefficients[k].combined;
    (acts ? acting : silent) += 1;
  }
  ASSERT_GT(acting, 0);
  // Rows: the two header rows, one per acting input, Type A, u_c, nu_eff, k, U, the method.
  EXPECT_EQ(count(c.annex, "<tr"), std::size_t(2 + acting + 6)) << c.annex;
  if (silent > 0) {
    EXPECT_NE(c.annex.find(fmt::format(" {} further inputs contribute nothing to any coefficient and are not listed.",
                                       silent)),
              std::string::npos);
  }
  // One pair of columns (c_i, u_i) per coefficient, each headed by the term and its unit.
  EXPECT_EQ(count(c.annex, "<th>c<sub>i</sub></th><th>u<sub>i</sub></th>"), st.coefficients.size());
  EXPECT_NE(c.annex.find("<th colspan=\"2\">K<sub>2</sub> [°/s/g²]</th>"), std::string::npos) << c.annex;
  EXPECT_NE(c.annex.find("<tr><td>noise of the run means (instrument and drives)</td><td>A, this test</td>"),
            std::string::npos);
  EXPECT_NE(c.annex.find("<td>B, tolerance, arcsine</td>"), std::string::npos) << c.annex;
}

TEST(CertificateAnnex, TheTotalsAreTheStatementsRounded) {
  const Certified c = certified(0);
  const verbs::CalibrationStatement& st = *c.result.observed->statement;
  std::string k_row = "<tr><td colspan=\"3\">coverage factor k</td>",
              u_row = "<tr class=\"total\"><td colspan=\"3\">expanded uncertainty U</td>";
  for (const CoefficientStatement& s : st.coefficients) {
    k_row += fmt::format("<td colspan=\"2\" class=\"num\">{:.2f}</td>", s.coverage_factor);
    u_row += fmt::format("<td colspan=\"2\" class=\"num\">{}</td>", round_figures(s).expanded);
  }
  EXPECT_NE(c.annex.find(k_row + "</tr>"), std::string::npos) << k_row << "\n" << c.annex;
  EXPECT_NE(c.annex.find(u_row + "</tr>"), std::string::npos) << u_row << "\n" << c.annex;
  for (const CoefficientStatement& s : st.coefficients)
    EXPECT_NE(c.annex.find(fmt::format("data-method=\"{}\">", s.input.coefficient)), std::string::npos);
}

}  // namespace certificate_annex_render_test
}  // namespace ccal
