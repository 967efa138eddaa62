// The drive keys of a configuration (docs/config.md): the rate ripple's ids, [centrifuge] platform_control,
// main_rate_noise and platform_rate_noise (with the per-root-hertz suffixes they share with [instrument]
// noise_density), accepted in every documented form and refused, located and explained, in every wrong one;
// and the command line's exit code 2 for them.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ccal/io/config_file.hpp"
#include "cli_support.hpp"
#include "config_test_support.hpp"

namespace ccal::test {
namespace {

// kBase (config_test_support.hpp) ends in [centrifuge], so an appended line lands there; a refused line's
// error names its line, its key and each hint, on one line.
using config_test::kBase;
const auto expect_refused = config_test::expect_appended_error;

TEST(DriveKeys, AcceptedForms) {
  // 0.2 ppm/rtHz is 2e-7 /√Hz; an Allan deviation of 0.1 ppm at 4 s is N = 1e-7·√4 = 2e-7 /√Hz (model.md
  // §3.2).
  Config c = parse_config(kBase +
                              "\nplatform_control = \"phase_locked\"\nmain_rate_noise = \"0.2 ppm/rtHz\"\n"
                              "platform_rate_noise = { allan_deviation = \"0.1 ppm\", tau = \"4 s\" }\n"
                              "[errors]\nripple1_s1 = \"10 ppm\"\n",
                          "ok.toml");
  EXPECT_EQ(c.centrifuge.geometry.platform_control, PlatformControl::phase_locked);
  EXPECT_NEAR(c.centrifuge.rate_noise.main, 2e-7, 1e-22);
  EXPECT_NEAR(c.centrifuge.rate_noise.platform, 2e-7, 1e-22);
  EXPECT_NEAR(c.centrifuge.error("ripple1_s1"), 1e-5, 1e-20);
  const Config d = parse_config(kBase, "default.toml");
  EXPECT_EQ(d.centrifuge.geometry.platform_control, PlatformControl::speed);
  EXPECT_FALSE(d.centrifuge.rate_noise.any());
}

TEST(DriveKeys, EveryPerRootHertzSuffix) {
  // A drive's density and the instrument's noise density read the same suffixes, trailing spaces allowed:
  // 0.2 ppm/√Hz = 2e-7 /√Hz, 10 ug/√Hz = 1e-5 g/√Hz.
  for (const std::string suffix : {"/rtHz", "/sqrt(Hz)", "/√Hz", "/rtHz  "}) {
    SCOPED_TRACE(suffix);
    const Config c = parse_config(kBase + "\nmain_rate_noise = \"0.2 ppm" + suffix +
                                      "\"\n[instrument]\nmodel = \"ieee\"\nnoise_density = \"10 ug" + suffix +
                                      "\"\n[instrument.terms]\nK1 = \"1 g/g\"\n",
                                  "suffix.toml");
    EXPECT_NEAR(c.centrifuge.rate_noise.main, 2e-7, 1e-22);
    EXPECT_NEAR(c.instrument.noise_density, 1e-5, 1e-20);
  }
  expect_refused("main_rate_noise = \"0.2 ppm/Hz\"", "centrifuge.main_rate_noise", {"must end in /rtHz"});
  expect_refused("[instrument]\nnoise_density = \"10 ug/rtHz/rtHz \"", "instrument.noise_density", {});
}

TEST(DriveKeys, WrongFormsAreRefusedWithTheirPlace) {
  expect_refused("platform_control = \"locked\"", "centrifuge.platform_control", {"speed", "phase_locked"});
  expect_refused("main_rate_noise = \"0.2 ppm\"", "centrifuge.main_rate_noise", {"/rtHz"});
  expect_refused("main_rate_noise = \"-1 ppm/rtHz\"", "centrifuge.main_rate_noise", {"negative"});
  expect_refused("main_rate_noise = \"1 deg/rtHz\"", "centrifuge.main_rate_noise", {});
  expect_refused("platform_rate_noise = 3", "centrifuge.platform_rate_noise", {"string or an inline table"});
  expect_refused("platform_rate_noise = { allan_deviation = \"0.1 ppm\" }", "centrifuge.platform_rate_noise",
                 {"tau"});
  expect_refused("platform_rate_noise = { allan_deviation = \"0.1 ppm\", tau = \"0 s\" }",
                 "centrifuge.platform_rate_noise.tau", {});
  expect_refused("platform_rate_noise = { allan = \"0.1 ppm\", tau = \"4 s\" }",
                 "centrifuge.platform_rate_noise.allan", {"allan_deviation"});
  expect_refused("[errors]\nripple1_c0 = \"10 ppm\"", "errors.ripple1_c0", {"no constant term", "domega"});
  expect_refused("[tolerances]\nripple3_c0 = \"10 ppm\"", "tolerances.ripple3_c0", {"dOmega"});
  expect_refused("[errors]\nripple1_c1 = \"10 urad\"", "errors.ripple1_c1", {});
  expect_refused("[errors]\nripple1_c2 = \"10 ppm\"", "errors.ripple1_c2", {"harmonic_order"});
}

TEST(DriveKeys, EncodersAreAListOfTheJointsLogged) {
  const Config both = parse_config(kBase + "\nencoders = [\"main\", \"platform\"]\n", "both.toml");
  EXPECT_TRUE(both.centrifuge.encoders.main);
  EXPECT_TRUE(both.centrifuge.encoders.platform);
  const Config main = parse_config(kBase + "\nencoders = [\"main\"]\n", "main.toml");
  EXPECT_TRUE(main.centrifuge.encoders.main);
  EXPECT_FALSE(main.centrifuge.encoders.platform);
  const Config none = parse_config(kBase, "none.toml");
  EXPECT_FALSE(none.centrifuge.encoders.main || none.centrifuge.encoders.platform);
  expect_refused("encoders = \"main\"", "centrifuge.encoders", {"expected a list", "\"platform\""});
  expect_refused("encoders = [\"theta1\"]", "centrifuge.encoders", {"'theta1' is not an encoder", "\"main\""});
  expect_refused("encoders = [1]", "centrifuge.encoders", {"is not an encoder"});
  expect_refused("encoders = [\"main\", \"main\"]", "centrifuge.encoders", {"listed twice"});
}

using DriveKeysCli = Cli;

TEST_F(DriveKeysCli, ExitCodeTwoWithTheKey) {
  std::string text = read(kExample);
  const auto at = text.find("platform_control = \"speed\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, std::string("platform_control = \"speed\"").size(), "platform_control = \"sped\"");
  const std::string bad = write("bad.toml", text);
  expect_bad_input(run("budget " + bad), {"centrifuge.platform_control", "speed"});
  text.replace(text.find("platform_control = \"sped\""), std::string("platform_control = \"sped\"").size(),
               "encoders = [\"main\", \"gamma\"]");
  expect_bad_input(run("design " + write("encoders.toml", text)),
                   {"centrifuge.encoders", "'gamma' is not an encoder", "\"platform\""});
}

}  // namespace
}  // namespace ccal::test
