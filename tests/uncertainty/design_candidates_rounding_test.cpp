// A designed run as the operator sets it (uncertainty/design_candidates.hpp, rounded_run): the g-level to the
// nearest step (the step below above max_g), the duration down to its step, the angles to the nearest step in
// [0°, 360°), each value the one its shortest decimal reads back as; the [design] keys that set the steps.
#include <gtest/gtest.h>

#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/design_candidates.hpp"
#include "test_constants.hpp"

namespace ccal {
namespace {

using ccal::test::kDeg;

TEST(DesignRounding, EachSettingGoesToTheMachinesStep) {
  ccal::Run run;
  run.g_level = 29.4751;
  run.duration = 449.26903039399861;
  run.terminal_phase = 125.6049 * kDeg;
  run.arm_azimuth = 359.97 * kDeg;  // rounds to 360°: written as 0°
  const ccal::Run r = rounded_run(run, SettingResolution{}, 30);
  EXPECT_EQ(r.g_level, 29.48);
  EXPECT_EQ(r.duration, 449.269);  // down: never longer
  EXPECT_EQ(*r.terminal_phase, parse_quantity("125.6 deg").value_si);
  EXPECT_EQ(r.arm_azimuth, 0.0);
  // Above max_g the step below; a coarse duration step never gives 0.
  run.g_level = 29.996;
  SettingResolution coarse;
  coarse.duration = 1000;
  const ccal::Run top = rounded_run(run, coarse, 29.995);
  EXPECT_EQ(top.g_level, 29.99);
  EXPECT_EQ(top.duration, 1000.0);
}

TEST(DesignRounding, TheStepsAreDesignKeysRefusedWhenNotPositive) {
  const std::string base(bundled_example_text());
  const Config c = parse_config(base +
                                    "\n[design]\ng_resolution = \"0.1 g\"\nduration_resolution = \"10 ms\"\n"
                                    "angle_resolution = \"1 deg\"\n",
                                "steps.toml");
  const SettingResolution s = setting_resolution(c.design);
  EXPECT_DOUBLE_EQ(s.g, 0.1);
  EXPECT_DOUBLE_EQ(s.duration, 0.01);
  EXPECT_DOUBLE_EQ(s.angle, kDeg);
  try {
    parse_config(base + "\n[design]\nangle_resolution = \"0 deg\"\n", "zero.toml");
    FAIL() << "a zero step was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("design.angle_resolution: must be positive"), std::string::npos)
        << e.what();
  }
}

// Steps finer than any machine sets (a unit error; 1e-300 g overflowed the 64-bit step counts) are refused
// where they are read, as written; steps coarser than the space refused before the search: a duration step
// of 1000 s raised every run to 1000 s, past the total time, and the plan was written with exit 0.
TEST(DesignRounding, StepsFinerThanAMachineOrCoarserThanTheSpaceAreRefused) {
  const std::string base(bundled_example_text());
  for (const auto& [line, key] : {std::pair{"g_resolution = \"1e-300 g\"", "design.g_resolution"},
                                  {"duration_resolution = \"1 ns\"", "design.duration_resolution"},
                                  {"angle_resolution = \"1e-9 deg\"", "design.angle_resolution"}}) {
    try {
      parse_config(base + "\n[design]\n" + line + "\n", "fine.toml");
      ADD_FAILURE() << line << " was accepted";
    } catch (const ConfigError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(std::string(key) + ": "), std::string::npos) << what;
      EXPECT_NE(what.find("is finer than any machine sets; accepted: at least 1e-6"), std::string::npos)
          << what;
    }
  }
  const auto refused = [&](const std::string& design, const std::vector<std::string>& hints) {
    SCOPED_TRACE(design);
    try {
      resolve_design_space(parse_config(base + "\n[design]\n" + design, "coarse.toml"));
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      for (const std::string& hint : hints)
        EXPECT_NE(std::string(e.what()).find(hint), std::string::npos) << "'" << hint << "' in " << e.what();
    }
  };
  refused("duration_resolution = \"1e3 s\"\n",
          {"coarse.toml: design.duration_resolution: 1000 s is coarser than the shortest run the design may "
           "choose (",
           "accepted: at most"});
  refused("g_resolution = \"100 g\"\n", {"coarse.toml: design.g_resolution: 100 g is coarser than the lowest "
                                         "g-level the design may choose (5 g)"});
  // As fine as the space: accepted.
  EXPECT_NO_THROW(
      resolve_design_space(parse_config(base + "\n[design]\ng_resolution = \"5 g\"\n", "ok.toml")));
}

}  // namespace
}  // namespace ccal
