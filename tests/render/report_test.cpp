// The HTML report's pieces: the page's escaping of everything a
// configuration brings (its text, its file name) so that no input can add markup or end a script, and the
// allocation section's numbers and command line, and the statement section's.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/core/sha256.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/render/budget.hpp"
#include "ccal/render/report.hpp"
#include "ccal/verbs/report.hpp"

namespace ccal::test {
namespace {

TEST(ReportHtml, EverythingFromTheConfigurationIsEscaped) {
  Config cfg = bundled_example();
  cfg.source = "/home/lab/evil<img src=x onerror=alert(1)>.toml";  // shown by its name, without its folder
  verbs::ReportOptions o;
  o.monte_carlo.trials = 500;
  o.input_points = 5;
  const verbs::ReportResult r = verbs::report(cfg, o);
  render::ReportProvenance p;
  p.config_text = std::string(bundled_example_text()) + "\n# </pre><script>alert(2)</script> & \"q\" 'a'\n";
  p.command_line = "ccal report '<b>x</b>'";
  p.date_utc = "2026-12-01T07:00:00Z";
  const std::string page = render::html(r, p, "/* the charting library */");
  EXPECT_EQ(page.find("<img"), std::string::npos);
  EXPECT_EQ(page.find("<script>alert"), std::string::npos);
  EXPECT_EQ(page.find("<b>x"), std::string::npos);
  EXPECT_NE(page.find("# &lt;/pre&gt;&lt;script&gt;alert(2)&lt;/script&gt; &amp; &quot;q&quot; &#39;a&#39;"),
            std::string::npos);
  EXPECT_NE(page.find("evil&lt;img src=x onerror=alert(1)&gt;.toml"), std::string::npos);
  EXPECT_EQ(page.find("/home/lab"), std::string::npos);
  // Exactly the page's own script elements: the sources, the charts' specifications, the library, the draw.
  std::size_t scripts = 0, ends = 0;
  for (std::size_t at = 0; (at = page.find("<script", at)) != std::string::npos; ++at) ++scripts;
  for (std::size_t at = 0; (at = page.find("</script", at)) != std::string::npos; ++at) ++ends;
  EXPECT_EQ(scripts, ends);
  EXPECT_EQ(scripts, 1u + 8u + 2u);
  EXPECT_NE(page.find(sha256_hex(p.config_text)), std::string::npos);
}

TEST(ReportHtml, TheLibraryCannotEndItsScriptEarly) {
  const verbs::ReportResult r = [] {
    verbs::ReportOptions o;
    o.monte_carlo.trials = 200;
    o.input_points = 3;
    return verbs::report(bundled_example(), o);
  }();
  const std::string page = render::html(r, {}, "var s = '</script><p>';");
  EXPECT_NE(page.find("var s = '<\\/script><p>';"), std::string::npos);
  EXPECT_EQ(page.find("'</script><p>'"), std::string::npos);
}

// The budget's table has EA-4/02's columns, each number naming its place in the budget's JSON; a contribution
// below the round-off floor (dthx4 and dx5 turn or shift the instrument without moving its input: 1e-18 u and
// 0) is 0 in c_i, u_i(y) and share, the cell naming its flag, while the JSON keeps the number.
TEST(ReportSections, TheBudgetTableShowsRoundOffAsZeroAndNamesEveryNumber) {
  Config cfg = bundled_example();
  std::vector<Tolerance> few;
  for (const Tolerance& t : cfg.tolerances)
    if (t.id == "dthy1t" || t.id == "dthx4" || t.id == "dx5" || t.id == "ripple1_c1") few.push_back(t);
  ASSERT_EQ(few.size(), 4u);
  cfg.tolerances = few;
  verbs::ReportOptions o;
  o.monte_carlo.trials = 200;
  o.input_points = 3;
  const verbs::ReportResult r = verbs::report(cfg, o);
  const std::string page = render::html(r, {}, "");
  const auto json = nlohmann::json::parse(render::json(r.budget));
  const std::string table = page.substr(page.find("<table class=\"budget\" data-coefficient=\"K0\""));
  const std::string k0 = table.substr(0, table.find("</table>"));
  for (const char* column : {"quantity X<sub>i</sub>", "<th>x<sub>i</sub></th>", "u(x<sub>i</sub>)", "<th>unit</th>",
                             "distribution", "divisor", "<th>type</th>", "ν<sub>i</sub>", "c<sub>i</sub> [deg/s per unit]"})
    EXPECT_NE(k0.find(column), std::string::npos) << column;
  int floored = 0;
  for (std::size_t s = 0; s < json["sources"].size(); ++s) {
    const auto& source = json["sources"][s];
    const std::string at = "budget:/sources/" + std::to_string(s);
    const std::string row = k0.substr(k0.find("<code>" + source["id"].get<std::string>() + "</code>"));
    const std::string line = row.substr(0, row.find("</tr>"));
    EXPECT_NE(line.find(source["name"].get<std::string>()), std::string::npos) << line;  // its description
    for (const char* field : {"/estimate\"", "/standard_uncertainty\"", "/divisor\""})
      EXPECT_NE(line.find(at + field), std::string::npos) << field << "\n" << line;
    EXPECT_NE(line.find("<td>B</td><td>∞</td>"), std::string::npos) << line;
    const bool zero = source["below_round_off_floor"]["K0"];
    const std::string flag = "data-round-off=\"" + at + "/below_round_off_floor/K0\"";
    for (const char* field : {"/sensitivity/K0\"", "/effect/K0\"", "/share/K0\""}) {
      const std::string cell = line.substr(line.find(at + field));
      EXPECT_EQ(cell.substr(0, cell.find("</td>")).find(flag), cell.find(flag)) << cell;
      EXPECT_EQ(cell.substr(cell.find('>') + 1, cell.find("</td>") - cell.find('>') - 1) == "0", zero)
          << source["id"] << field << "\n" << cell.substr(0, cell.find("</td>"));
    }
    floored += zero;
  }
  EXPECT_EQ(floored, 2);  // dthx4 and dx5
  // The rate noise's line: Type A.
  EXPECT_NE(k0.find("<td>A</td><td>∞</td>"), std::string::npos);
}

TEST(ReportSections, TheAllocationIsTheVerbsWithTheReportsModeAndItsCommandLine) {
  // The section's numbers are those of verbs::allocate with the same options (the report's mode filled in):
  // the same deterministic computation and the same seeded Monte Carlo, so equal to the last bit.
  const Config cfg = bundled_example();
  verbs::ReportOptions o;
  o.mode = ModelMode::paper;
  o.monte_carlo.trials = 200;
  o.input_points = 3;
  AllocateOptions a;
  a.targets = {"K3=2e-3 deg/s/g^3"};
  a.verify_trials = 200;
  o.allocate = a;
  const verbs::ReportResult r = verbs::report(cfg, o);
  ASSERT_TRUE(r.allocation.has_value());
  EXPECT_FALSE(r.design.has_value());
  a.mode = ModelMode::paper;
  const verbs::AllocateResult direct = verbs::allocate(cfg, a);
  const AllocationDetail &x = r.allocation->allocation, &y = direct.allocation;
  EXPECT_EQ(x.mode, ModelMode::paper);
  ASSERT_EQ(x.sources.size(), y.sources.size());
  for (std::size_t s = 0; s < x.sources.size(); ++s) {
    EXPECT_EQ(x.sources[s].id, y.sources[s].id);
    EXPECT_EQ(x.sources[s].scale, y.sources[s].scale);
  }
  for (std::size_t k = 0; k < x.coefficients.size(); ++k) {
    EXPECT_EQ(x.coefficients[k].allocated_expanded, y.coefficients[k].allocated_expanded);
    EXPECT_EQ(x.coefficients[k].mc_half_width, y.coefficients[k].mc_half_width);
  }
  // The command line that gives the same numbers, and the page's section with cells naming that output.
  render::ReportProvenance p;
  render::report_commands(r, o, p);
  EXPECT_EQ(p.allocate_command, (std::vector<std::string>{"allocate", "--target", "K3=2e-3 deg/s/g^3",
                                                          "--mode", "paper", "--verify-trials", "200"}));
  EXPECT_TRUE(p.design_command.empty());
  const std::string page = render::html(r, p, "/* the charting library */");
  EXPECT_NE(page.find("<section id=\"allocation\">"), std::string::npos);
  EXPECT_EQ(page.find("<section id=\"design\">"), std::string::npos);
  EXPECT_NE(page.find("data-src=\"allocate:/coefficients/K3/allocated_expanded\""), std::string::npos);
  // The target with a space is quoted for the shell.
  EXPECT_NE(page.find("ccal allocate --target &#39;K3=2e-3 deg/s/g^3&#39; --mode paper --verify-trials 200 "
                      "--format json"),
            std::string::npos);
  // Without report_commands the page cannot name the allocation's command: refused, not left out.
  EXPECT_THROW(render::html(r, {}, ""), std::logic_error);
}

// Each "same as" command line names every option the report gave its verb that is not the verb's default,
// written from the verb's own table (core/options.hpp option_arguments): the seed and threads of the Monte
// Carlo reach the allocation, and a switch such as let_others_grow its command.
TEST(ReportSections, EachCommandNamesEveryOptionThatIsNotTheDefault) {
  verbs::ReportOptions o;
  o.monte_carlo.trials = 300;
  o.monte_carlo.seed = 9;
  o.monte_carlo.threads = 2;
  o.coverage_factor = 2;
  o.allocate = verbs::report_allocation({"K3=2e-3"}, o);
  o.allocate->let_others_grow = true;
  o.design = verbs::report_design({"K3=1e-3"}, o);
  const verbs::ReportResult not_run;  // the commands come from the options alone
  render::ReportProvenance p;
  render::report_commands(not_run, o, p);
  using Words = std::vector<std::string>;
  EXPECT_EQ(p.budget_command, (Words{"budget", "--coverage-factor", "2"}));
  EXPECT_EQ(p.montecarlo_command, (Words{"montecarlo", "--trials", "300", "--seed", "9", "--threads", "2"}));
  EXPECT_EQ(p.allocate_command, (Words{"allocate", "--target", "K3=2e-3", "--let-others-grow", "--seed", "9",
                                       "--threads", "2"}));
  EXPECT_EQ(p.design_command, (Words{"design", "--target", "K3=1e-3", "--coverage-factor", "2", "--threads", "2"}));
  EXPECT_TRUE(p.identify_command.empty());  // no observations
}

// The bundled example's run means as `ccal simulate --observations-out` writes them, with the 10g and 20g
// outputs moved by +2e-4 and -3e-4 deg/s so that the fit has a scatter (a Type A part well above round-off).
std::string observations_text() {
  return
      "# ccal observations v1; terms=K0:K0,K2:K2,K3:K3; fixed=K1:K1=505.2097 deg/s/g; known=rate; "
      "output_unit=deg/s\n"
      "run,a_i,output,rate,K0,K1,K2,K3\n"
      "5g,0.0011258647673581118,0.87960387298876774,-0.0013078191577280609,1,0.0011258647673581118,"
      "12.503105558100096,0.026259875629783602\n"
      "10g,0.001894267171119568,2.0180067347005011,-0.0015559323219851468,1,0.001894267171119568,"
      "49.993658702524705,0.17144791027889283\n"
      "15g,0.004024892939033603,4.3449185147206109,-0.0026993518875195925,1,0.004024892939033603,"
      "112.51446997604825,0.64683760857359807\n"
      "20g,0.0040248706513405647,6.0971092168112426,-0.0023376986301180238,1,0.0040248706513405647,"
      "200.02876985513265,1.2649413451187916\n"
      "25g,-3.1771231287280877e-05,6.2960027667124328,1.6505024563838392e-05,1,-3.1771231287280877e-05,"
      "312.50619837971044,-0.019857226505450853\n"
      "30g,-0.0053797588949902643,6.3367545720364937,0.0025512599853871726,1,-0.0053797588949902643,"
      "450.04772400165359,-3.6059301907758177\n";
}
CsvTable observations() { return parse_csv(observations_text(), "obs.csv"); }

TEST(ReportSections, TheStatementIsIdentifysWithTheReportsModeAndCoverage) {
  const Config cfg = bundled_example();
  verbs::ReportOptions o;
  o.mode = ModelMode::paper;
  o.monte_carlo.trials = 200;
  o.monte_carlo.coverage_probability = 0.9;
  o.input_points = 3;
  o.observations = observations();
  const verbs::ReportResult r = verbs::report(cfg, o);
  ASSERT_TRUE(r.observed.has_value());
  ASSERT_TRUE(r.observed->statement.has_value());
  // The same as `ccal identify obs.csv --statement --config CONFIG --mode paper --coverage-probability 0.9`:
  // the same deterministic computation, so equal to the last bit.
  verbs::IdentifyOptions io;
  io.statement = true;
  io.config = cfg;
  io.statement_options.mode = ModelMode::paper;
  io.statement_options.coverage_probability = 0.9;
  const verbs::IdentifyResult direct = verbs::identify(observations(), io);
  const verbs::CalibrationStatement &x = *r.observed->statement, &y = *direct.statement;
  EXPECT_EQ(x.mode, ModelMode::paper);
  EXPECT_EQ(x.coverage_probability, 0.9);
  ASSERT_EQ(x.coefficients.size(), 3u);
  ASSERT_EQ(y.coefficients.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const CoefficientStatement &a = x.coefficients[k], &b = y.coefficients[k];
    EXPECT_EQ(a.input.coefficient, b.input.coefficient);
    EXPECT_EQ(a.corrected, b.corrected);
    EXPECT_EQ(a.input.type_a.u, b.input.type_a.u);
    EXPECT_EQ(a.input.type_b.u, b.input.type_b.u);
    EXPECT_EQ(a.expanded, b.expanded);
    // The statement's own relations (JCGM 100 §7, G.2b): Type A from the noise model (the example's drives'
    // rate noise), ν_A = ∞, its residual check with 6 runs − 3 free terms = 3 degrees of freedom; u_c² = u_A² +
    // u_B² and U = k u_c (to round-off, 1e-14 relative); k at least the normal quantile z_0.95 =
    // 1.6448536269514722 (Student's t is wider for a finite ν_eff).
    EXPECT_TRUE(x.type_a.from_noise_model);
    EXPECT_EQ(x.type_a.dof, 3);
    EXPECT_TRUE(std::isinf(a.input.type_a.dof));
    EXPECT_GT(a.input.type_a.u, 0.0);
    EXPECT_NEAR(a.combined, std::hypot(a.input.type_a.u, a.input.type_b.u), 1e-14 * a.combined);
    EXPECT_NEAR(a.expanded, a.coverage_factor * a.combined, 1e-14 * a.expanded);
    EXPECT_GE(a.coverage_factor, 1.6448536269514722 - 1e-12);
  }
  // The command line that gives the same numbers, and the page's section with cells naming that output.
  render::ReportProvenance p;
  render::report_commands(r, o, p);
  // Every option the report gave the statement that is not identify's default, in identify's table's order.
  EXPECT_EQ(p.identify_command, (std::vector<std::string>{"identify", "obs.csv", "--statement",
                                                          "--coverage-probability", "0.9", "--mode", "paper"}));
  const std::string page = render::html(r, p, "/* the charting library */");
  EXPECT_NE(page.find("<section id=\"statement\">"), std::string::npos);
  // The observations are named and fingerprinted in the provenance, as the configuration is.
  EXPECT_EQ(p.observations_sha256, sha256_hex(observations_text()));
  EXPECT_NE(page.find("<code id=\"observations-sha256\">" + sha256_hex(observations_text()) + "</code>"),
            std::string::npos);
  EXPECT_NE(page.find("data-src=\"identify:/statement/coefficients/K3/expanded_uncertainty\""),
            std::string::npos);
  EXPECT_NE(page.find("ccal identify obs.csv --statement --config examples/wang_ren_2014.toml "
                      "--coverage-probability 0.9 --mode paper --format json"),
            std::string::npos);
  EXPECT_THROW(render::html(r, {}, ""), std::logic_error);
}

TEST(ReportSections, ACertificateComputesNoMonteCarloOfTheTolerances) {
  // The certificate shows the statement and its budget; the tolerance budget's Monte Carlo and the sensed input
  // belong to the engineering report only, so the certificate does not spend their time.
  Config cfg = bundled_example();
  cfg.certificate = Certificate{};
  cfg.certificate->number = "CAL-1";
  verbs::ReportOptions o;
  o.monte_carlo.trials = 200;
  o.input_points = 3;
  o.statement_trials = 0;
  o.observations = observations();
  ASSERT_TRUE(verbs::gives_certificate(cfg, o));
  const verbs::ReportResult certificate = verbs::report(cfg, o);
  EXPECT_TRUE(certificate.certificate);
  EXPECT_EQ(certificate.monte_carlo.monte_carlo.trials, 0u);
  EXPECT_TRUE(certificate.sensed_input.time.empty());
  ASSERT_TRUE(certificate.observed.has_value());
  o.engineering = true;
  EXPECT_FALSE(verbs::gives_certificate(cfg, o));
  const verbs::ReportResult engineering = verbs::report(cfg, o);
  EXPECT_FALSE(engineering.certificate);
  EXPECT_EQ(engineering.monte_carlo.monte_carlo.trials, 200u);
  EXPECT_EQ(engineering.sensed_input.time.size(), 3u);
  // Without observations or without a [certificate] table there is no certificate.
  o.engineering = false;
  o.observations.reset();
  EXPECT_FALSE(verbs::gives_certificate(cfg, o));
  o.observations = observations();
  EXPECT_FALSE(verbs::gives_certificate(bundled_example(), o));
}

TEST(ReportSections, ObservationsOfOtherTermsAreRefusedNamingTheOption) {
  verbs::ReportOptions o;
  o.monte_carlo.trials = 200;
  o.observations = parse_csv(
      "# ccal observations v1; terms=K0:K0,K1:K1; fixed=; known=; output_unit=deg/s\n"
      "run,a_i,output,K0,K1\n1g,1,1.1,1,1\n2g,2,2.0,1,2\n3g,3,2.9,1,3\n4g,4,4.2,1,4\n",
      "obs.csv");
  try {
    verbs::report(bundled_example(), o);
    FAIL() << "observations of K0, K1 accepted for a configuration of K0, K2, K3";
  } catch (const OptionError& e) {
    // Named as the report's own option (not identify's statement or config, which the report has not).
    const std::string message = e.what();
    EXPECT_EQ(e.field(), "observations");
    EXPECT_EQ(message.rfind("observations: the fit's free terms (K0, K1) are not those of ", 0), 0u) << message;
  }
}

}  // namespace
}  // namespace ccal::test
