// The HTML report's pieces: SHA-256 against the FIPS 180-2 examples, the page's escaping of everything a
// configuration brings (its text, its file name) so that no input can add markup or end a script, and the
// allocation section's numbers and command line.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "ccal/io/config_file.hpp"
#include "ccal/render/report.hpp"
#include "ccal/render/report_sha256.hpp"
#include "ccal/verbs/report.hpp"

namespace ccal::test {
namespace {

TEST(ReportSha256, FipsExamples) {
  // FIPS 180-2, Appendix B (one block, two blocks: 56 bytes fill the first block's length field, a million
  // 'a'), and the empty message.
  EXPECT_EQ(render::sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(render::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(render::sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  EXPECT_EQ(render::sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(ReportHtml, EverythingFromTheConfigurationIsEscaped) {
  Config cfg = bundled_example();
  cfg.source = "evil</script><img src=x onerror=alert(1)>.toml";
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
  EXPECT_NE(page.find("evil&lt;/script&gt;&lt;img src=x onerror=alert(1)&gt;.toml"), std::string::npos);
  // Exactly the page's own script elements: the sources, the charts' specifications, the library, the draw.
  std::size_t scripts = 0, ends = 0;
  for (std::size_t at = 0; (at = page.find("<script", at)) != std::string::npos; ++at) ++scripts;
  for (std::size_t at = 0; (at = page.find("</script", at)) != std::string::npos; ++at) ++ends;
  EXPECT_EQ(scripts, ends);
  EXPECT_EQ(scripts, 1u + 8u + 2u);
  EXPECT_NE(page.find(render::sha256_hex(p.config_text)), std::string::npos);
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

TEST(ReportSections, TheAllocationIsTheVerbsWithTheReportsModeAndItsCommandLine) {
  // The section's numbers are those of verbs::allocate with the same options (the report's mode filled in):
  // the same deterministic computation and the same seeded Monte Carlo, so equal to the last bit.
  const Config cfg = bundled_example();
  verbs::ReportOptions o;
  o.mode = ModelMode::paper;
  o.monte_carlo.trials = 200;
  o.input_points = 3;
  verbs::AllocateOptions a;
  a.targets = {"K3=2e-3 deg/s/g^3"};
  a.verify_trials = 200;
  o.allocate = a;
  const verbs::ReportResult r = verbs::report(cfg, o);
  ASSERT_TRUE(r.allocation.has_value());
  EXPECT_FALSE(r.design.has_value());
  a.mode = ModelMode::paper;
  const verbs::AllocateResult direct = verbs::allocate(cfg, a);
  const AllocationResult &x = r.allocation->allocation, &y = direct.allocation;
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

}  // namespace
}  // namespace ccal::test
