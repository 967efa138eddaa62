// The run sheet as text (render/run_sheet.hpp): each value to the decimals of the step the machine sets it
// by, the phase the plan sets marked, and the notes an operator needs.
#include "ccal/render/run_sheet.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <string_view>

namespace ccal::render {
namespace {

TEST(RunSheetText, DecimalsShowEveryMultipleOfTheStep) {
  EXPECT_EQ(decimals_of(0.01), 2);
  EXPECT_EQ(decimals_of(0.001), 3);
  EXPECT_EQ(decimals_of(0.5), 1);
  EXPECT_EQ(decimals_of(0.25), 2);
  EXPECT_EQ(decimals_of(2.0), 0);
  EXPECT_EQ(decimals_of(0.1 * std::numbers::pi / 180 * (180 / std::numbers::pi)), 1);  // 0.1° through rad
  EXPECT_EQ(decimals_of(1e-12), 9);                                                    // capped
}

RunSheetLine line(int order, std::string run, PlatformMode mode, bool terminal) {
  RunSheetLine l;
  l.order = order;
  l.run = std::move(run);
  l.g_level = 29.47;
  l.main_rate = 10.0;  // 95.4929658551372 rpm
  l.platform_rate = mode == PlatformMode::fixed ? 0.0 : -10.0;
  l.duration = 449.269;
  l.turns = 714.98;
  l.arm_azimuth = std::numbers::pi;         // 180°
  l.start_phase = std::numbers::pi / 2;     // 90°
  l.stop_phase = 3 * std::numbers::pi / 2;  // 270°
  l.terminal_phase = terminal;
  l.mode = mode;
  return l;
}

TEST(RunSheetText, ValuesToTheirStepsAndTheSetPhaseMarked) {
  RunSheet sheet;
  sheet.lines = {line(1, "29.47g", PlatformMode::counter_rotating, true),
                 line(2, "29.47g-2", PlatformMode::fixed, false)};
  sheet.lines[1].mounting = Mounting::pa_vertical;
  sheet.total_duration = 898.538;
  const std::string t = text(sheet, SettingResolution{});
  // 0.01 g → 2 decimals, 1 ms → 3, 0.1° → 1; the speed in rpm to a tenth of its change per g step
  // (95.49 rpm × 0.01/(2·29.47) = 0.016 rpm → 3 decimals).
  EXPECT_NE(t.find("29.47        95.493    counter        449.269   714.980"), std::string::npos) << t;
  EXPECT_NE(t.find("180.0               90.0              270.0*   ia_horizontal"), std::string::npos) << t;
  EXPECT_NE(t.find("fixed"), std::string::npos) << t;
  EXPECT_NE(t.find("180.0               90.0*             270.0      pa_vertical"), std::string::npos) << t;
  EXPECT_NE(t.find("  total 898.538 s\n"), std::string::npos) << t;
  // The notes are wrapped at 110 columns: read as one paragraph.
  std::string notes;
  for (char c : std::string_view(t).substr(t.find("  Each run")))
    if (c == '\n')
      notes += ' ';
    else if (c != ' ' || notes.empty() || notes.back() != ' ')
      notes += c;
  EXPECT_NE(notes.find("* the phase the plan sets; the other follows from it."), std::string::npos) << notes;
  EXPECT_NE(notes.find("Mounting: ia_horizontal (IA = x5, PA = y5, OA = z5); pa_vertical (IA = x5, PA = z5, OA = "
                       "-y5)."),
            std::string::npos)
      << notes;
  // A coarser machine: 0.5 g, 0.1 s, 1°.
  const std::string coarse = text(sheet, SettingResolution{0.5, 0.1, std::numbers::pi / 180});
  EXPECT_NE(coarse.find("  total 898.5 s\n"), std::string::npos) << coarse;
  EXPECT_NE(coarse.find("29.5 "), std::string::npos) << coarse;
  EXPECT_NE(coarse.find("180   "), std::string::npos) << coarse;
}

}  // namespace
}  // namespace ccal::render
