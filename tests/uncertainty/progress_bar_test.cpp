// The Monte Carlo's progress bar fits its terminal: the line is never wider than the terminal less one
// column (a wrapped line would scroll at every redraw), the bar gives way first, then the rate and counts.
#include <gtest/gtest.h>

#include "../src/uncertainty/progress_bar.hpp"

namespace ccal::progress_bar {
namespace {

TEST(ProgressLine, FitsEveryTerminalWidth) {
  for (std::size_t columns = 10; columns <= 300; ++columns)
    for (const std::string label : {"", "stage 3 (M = 40000): "}) {
      const std::string line = progress_line(label, 0.4237, 4237, 10000, 12345.6, "0:00:05", columns);
      EXPECT_LE(line.size(), columns - 1) << columns << ": " << line;
    }
  // A normal terminal shows everything, the bar at most 50 wide; a narrow one keeps the percentage and ETA.
  const std::string wide = progress_line("", 0.5, 5000, 10000, 1e4, "0:00:01", 200);
  EXPECT_NE(wide.find("trials/s"), std::string::npos) << wide;
  EXPECT_NE(wide.find(std::string(25, '#') + std::string(25, ' ') + "]"), std::string::npos) << wide;
  const std::string narrow = progress_line("", 0.5, 5000, 10000, 1e4, "0:00:01", 40);
  EXPECT_EQ(narrow.find("trials/s"), std::string::npos) << narrow;
  EXPECT_NE(narrow.find("50.0 %"), std::string::npos) << narrow;
  EXPECT_NE(narrow.find("ETA 0:00:01"), std::string::npos) << narrow;
}

}  // namespace
}  // namespace ccal::progress_bar
