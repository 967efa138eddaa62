// The notes of a result as lines (the text's indented lines and the JSON's "notes" array): the non-empty
// lines, without their line ends.
#include <gtest/gtest.h>

#include "../src/render/text_lines.hpp"

namespace ccal::render::detail {
namespace {

TEST(LinesOf, NonEmptyLinesWithoutTheirEnds) {
  EXPECT_TRUE(lines_of("").empty());
  EXPECT_TRUE(lines_of("\n\n").empty());
  EXPECT_EQ(lines_of("one"), (std::vector<std::string>{"one"}));
  EXPECT_EQ(lines_of("one\ntwo\n"), (std::vector<std::string>{"one", "two"}));
  EXPECT_EQ(lines_of("\none\n\n  two \n"), (std::vector<std::string>{"one", "  two "}));
}

}  // namespace
}  // namespace ccal::render::detail
