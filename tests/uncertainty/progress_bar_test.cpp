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

TEST(ProgressLine, NamesWhatItCounts) {
  // The design counts candidate runs, starts and halvings, not trials.
  const std::string runs = progress_line("design: candidate runs ", 0.25, 2500, 10000, 4e3, "0:00:02", 200, "runs");
  EXPECT_NE(runs.find(" 2500/10000 runs  4e+03 runs/s  ETA 0:00:02"), std::string::npos) << runs;
  EXPECT_EQ(runs.find("trials"), std::string::npos) << runs;
}

TEST(Progress, ARestartCountsTheNewStageFromZero) {
  // Not drawn (stderr is not wanted): the count and the callback are the stage's own after a restart.
  std::uint64_t last_done = 99, last_total = 0;
  Progress p(false, [&](std::uint64_t done, std::uint64_t total) {
    last_done = done;
    last_total = total;
  });
  p.restart(10, "a ", "runs");
  for (int i = 0; i < 7; ++i) p.tick();
  p.poll();
  EXPECT_EQ(last_done, 7u);
  EXPECT_EQ(last_total, 10u);
  p.restart(3, "b ", "starts");
  p.set_done(2);
  p.poll();
  EXPECT_EQ(last_done, 2u);
  EXPECT_EQ(last_total, 3u);
}

}  // namespace
}  // namespace ccal::progress_bar
