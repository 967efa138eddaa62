// The readers' trimming: blanks (spaces, tabs) around a text; for CSV fields and lines also the carriage
// returns among the trailing blanks (a CRLF line end), never other characters or inner blanks.
#include "../src/core/text_trim.hpp"

#include <gtest/gtest.h>

namespace ccal::detail {
namespace {

TEST(TextTrim, BlanksAround) {
  EXPECT_TRUE(blank(' '));
  EXPECT_TRUE(blank('\t'));
  EXPECT_FALSE(blank('\r'));
  EXPECT_FALSE(blank('\n'));
  EXPECT_EQ(trim_blanks(" \t 5 deg/s \t"), "5 deg/s");
  EXPECT_EQ(trim_blanks("5\r"), "5\r");
  EXPECT_EQ(trim_blanks(" \t "), "");
  EXPECT_EQ(trim_blanks(""), "");
}

TEST(TextTrim, CsvAlsoDropsTrailingCarriageReturns) {
  EXPECT_EQ(trim_csv(" \ta, b \r"), "a, b");
  EXPECT_EQ(trim_csv("x \r \r"), "x");
  EXPECT_EQ(trim_csv("\rx"), "\rx");
  EXPECT_EQ(trim_csv(" \r\t"), "");
}

}  // namespace
}  // namespace ccal::detail
