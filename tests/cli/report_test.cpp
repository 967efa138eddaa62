// `ccal report --pdf`: refused before any computation when there is no browser to print with or when the PDF
// would replace the page, and with no file written; printed (skipped without Chromium) as an A4 PDF, alone
// without -o, beside the page with it.
#include <cstdlib>

#include "cli_support.hpp"

namespace ccal::test {
namespace {

class Report : public Cli {
 protected:
  // The environment's CCAL_CHROMIUM for one command.
  Result run_with_browser(const std::string& browser, const std::string& args) const {
    ::setenv("CCAL_CHROMIUM", browser.c_str(), 1);
    const Result r = run(args);
    ::unsetenv("CCAL_CHROMIUM");
    return r;
  }
};

TEST_F(Report, APdfWithoutABrowserIsRefusedBeforeTheWork) {
  // 10⁹ trials would take hours: the refusal comes first.
  const Result r = run_with_browser("/nonexistent/chromium", "report --trials 1000000000 -o r.html --pdf r.pdf");
  expect_bad_input(r, {"--pdf: ", "'/nonexistent/chromium' is not an executable file", "apt-get install chromium",
                       "CCAL_CHROMIUM"});
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
  EXPECT_FALSE(fs::exists(dir_ / "r.pdf"));
}

TEST_F(Report, APdfThatIsThePageIsRefused) {
  expect_bad_input(run("report --trials 1000000000 -o r.html --pdf ./r.html"),
                   {"--pdf: './r.html' is also the -o file"});
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
}

TEST_F(Report, ABrowserThatFailsWritesNoFile) {
  std::ofstream(dir_ / "r.pdf") << "the old file";
  const Result r = run_with_browser("false", "report --trials 20000 -o r.html --pdf r.pdf");
  expect_bad_input(r, {"--pdf: the browser", "wrote no PDF (exit status 1)"});
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
  EXPECT_EQ(read(dir_ / "r.pdf"), "the old file");
}

TEST_F(Report, ThePdfAloneOrBesideThePage) {
  if (std::system("command -v chromium >/dev/null 2>&1") != 0) GTEST_SKIP() << "no Chromium installed";
  const Result alone = run("report --trials 20000 --pdf r.pdf");
  ASSERT_EQ(alone.code, 0) << alone.err;
  EXPECT_TRUE(alone.out.empty());  // no page on standard output
  EXPECT_TRUE(read(dir_ / "r.pdf").starts_with("%PDF-"));
  const Result both = run("report --trials 20000 --pdf s.pdf -o s.html");
  ASSERT_EQ(both.code, 0) << both.err;
  EXPECT_TRUE(read(dir_ / "s.pdf").starts_with("%PDF-"));
  EXPECT_TRUE(read(dir_ / "s.html").starts_with("<!DOCTYPE html>"));
}

}  // namespace
}  // namespace ccal::test
