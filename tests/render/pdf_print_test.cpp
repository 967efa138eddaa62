// Printing a page to PDF through headless Chromium (render/pdf_print.hpp): a missing or failing browser is refused
// with what to install; a page prints to a PDF (skipped where no Chromium is installed).
#include "ccal/render/pdf_print.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "ccal/core/errors.hpp"

namespace ccal {
namespace {

std::string message_of(const PdfPrintOptions& o) {
  try {
    print_pdf("<p>x</p>", o);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "printed with " << o.browser;
  return {};
}

TEST(PdfPrint, AMissingBrowserIsRefusedSayingWhatToInstall) {
  PdfPrintOptions o;
  o.browser = "/nonexistent/chromium";
  EXPECT_EQ(find_pdf_browser(o), "");
  const std::string m = message_of(o);
  EXPECT_NE(m.find("'/nonexistent/chromium' is not an executable file"), std::string::npos) << m;
  EXPECT_NE(m.find("apt-get install chromium"), std::string::npos) << m;
  EXPECT_NE(m.find("CCAL_CHROMIUM"), std::string::npos) << m;
}

TEST(PdfPrint, ABrowserThatWritesNoPdfIsRefusedWithWhatItSaid) {
  PdfPrintOptions o;
  o.browser = "false";  // runs, exits 1, writes nothing
  const std::string m = message_of(o);
  EXPECT_NE(m.find("wrote no PDF (exit status 1)"), std::string::npos) << m;
}

TEST(PdfPrint, ABrowserThatHangsIsStoppedAtTheTimeout) {
  const std::filesystem::path script = std::filesystem::temp_directory_path() / "ccal-pdf-test-hang.sh";
  {
    std::ofstream out(script);
    out << "#!/bin/sh\nsleep 60\n";
  }
  std::filesystem::permissions(script, std::filesystem::perms::owner_all);
  PdfPrintOptions o;
  o.browser = script.string();
  o.timeout_s = 0.3;
  const auto start = std::chrono::steady_clock::now();
  const std::string m = message_of(o);
  // Stopped at the timeout, not after the script's minute (generous: a loaded machine starts /bin/sh slowly).
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  EXPECT_NE(m.find("did not finish printing within 0.3 s"), std::string::npos) << m;
  std::filesystem::remove(script);
}

TEST(PdfPrint, APagePrintsToAnA4Pdf) {
  if (find_pdf_browser().empty()) GTEST_SKIP() << "no Chromium installed";
  const std::string pdf = print_pdf(
      "<!DOCTYPE html><html><head><style>@page{size:A4}</style></head><body><p>ccal</p>"
      "<script>document.body.append('drawn')</script></body></html>");
  ASSERT_TRUE(pdf.starts_with("%PDF-"));
  // A4 is 595.28 × 841.89 pt; Chromium writes the page box on its own grid of 1/96 in (594.96 × 841.92 pt):
  // within 1 pt.
  const std::size_t box = pdf.find("/MediaBox [0 0 ");
  ASSERT_NE(box, std::string::npos);
  double width = 0, height = 0;
  std::istringstream(pdf.substr(box + 15, 40)) >> width >> height;
  EXPECT_NEAR(width, 595.28, 1.0);
  EXPECT_NEAR(height, 841.89, 1.0);
}

}  // namespace
}  // namespace ccal
