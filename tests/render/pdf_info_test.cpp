// The printed page's document information: read from the page's <head>, written as an incremental update
// whose trailer points back to the browser's, every string as PDF text (literal or UTF-16BE).
#include "ccal/render/pdf_info.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "ccal/core/errors.hpp"

namespace ccal {
namespace {

// A minimal PDF as the browser writes one: objects, a classic xref table, a trailer with /Info.
const std::string kBrowserPdf =
    "%PDF-1.4\n1 0 obj\n<</Title (old)>>\nendobj\n2 0 obj\n<</Type /Catalog>>\nendobj\nxref\n0 3\n"
    "0000000000 65535 f \n0000000009 00000 n \n0000000042 00000 n \ntrailer\n<</Size 3\n/Root 2 0 R\n"
    "/Info 1 0 R>>\nstartxref\n75\n%%EOF";

TEST(PdfInfo, ThePageStatesItInItsHead) {
  const PdfInfo info = pdf_info_of_page(
      "<head><title>Certificate CAL-1 &amp; more</title><meta name=\"author\" content=\"Lab &quot;A&quot; "
      "&#956;\"><meta name=\"description\" content=\"Calibration\"><meta name=\"dcterms.created\" "
      "content=\"2026-12-03T10:00:00Z\"></head>");
  EXPECT_EQ(info.title, "Certificate CAL-1 & more");
  EXPECT_EQ(info.author, "Lab \"A\" \u03bc");
  EXPECT_EQ(info.subject, "Calibration");
  EXPECT_EQ(info.keywords, "");
  EXPECT_EQ(info.date_utc, "2026-12-03T10:00:00Z");
}

TEST(PdfInfo, StringsAreLiteralForAsciiElseUtf16) {
  EXPECT_EQ(pdf_text_string("a (b) \\c"), "(a \\(b\\) \\\\c)");
  EXPECT_EQ(pdf_text_string("\u00b0C"), "<FEFF00B00043>");     // ° is U+00B0
  EXPECT_EQ(pdf_text_string("\U0001D400"), "<FEFFD835DC00>");  // outside the BMP: a surrogate pair
}

TEST(PdfInfo, AnIncrementalUpdateKeepsTheBytesAndPointsBack) {
  PdfInfo info{"CAL-1", "Lab", "Calibration certificate", "", "ccal 0.1", "2026-12-03T10:00:00Z"};
  const std::string out = with_pdf_info(kBrowserPdf, info);
  ASSERT_EQ(out.substr(0, kBrowserPdf.size()), kBrowserPdf);  // the browser's bytes, unchanged
  const std::string added = out.substr(kBrowserPdf.size() + 1);
  // The new dictionary is object 3 (the old /Size), at the offset its xref entry names.
  const std::size_t object_at = out.find("3 0 obj\n");
  ASSERT_NE(object_at, std::string::npos);
  EXPECT_NE(added.find(fmt::format("xref\n3 1\n{:010} 00000 n \n", object_at)), std::string::npos) << added;
  EXPECT_NE(
      added.find("/Title (CAL-1)\n/Author (Lab)\n/Subject (Calibration certificate)\n/Creator (ccal 0.1)\n"
                 "/CreationDate (D:20261203100000Z)\n/ModDate (D:20261203100000Z)\n>>"),
      std::string::npos)
      << added;
  EXPECT_EQ(added.find("/Keywords"), std::string::npos);  // empty: left out
  EXPECT_NE(added.find("trailer\n<</Size 4\n/Root 2 0 R\n/Info 3 0 R\n/Prev 75>>"), std::string::npos)
      << added;
  const std::size_t xref_at = out.rfind("xref\n3 1");
  EXPECT_TRUE(out.ends_with(fmt::format("startxref\n{}\n%%EOF\n", xref_at)));
}

TEST(PdfInfo, NoClassicTrailerOrABadDateIsRefused) {
  EXPECT_THROW(with_pdf_info("%PDF-1.5\n1 0 obj\n<</Type /XRef>>\nendobj\nstartxref\n9\n%%EOF", {}),
               InputError);
  PdfInfo day_only;
  day_only.date_utc = "2026-12-03";
  EXPECT_THROW(with_pdf_info(kBrowserPdf, day_only), InputError);
}

}  // namespace
}  // namespace ccal
