// End-to-end tests of `ccal design`: the configuration written by --plan-out budgets (`ccal budget`) exactly as
// the design reports, and bad design spaces and options are refused with exit code 2 and one line.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace ccal::test {
namespace {

using DesignCli = Cli;

// A small space (192 candidates) so that a design takes seconds.
const std::string kSmallSpace =
    "\n[design]\ng_step = \"5 g\"\nturn_fractions = 4\nphase_step = \"90 deg\"\nazimuth_step = \"180 deg\"\n"
    "starts = 2\n";

// --plan-out writes the whole file with the designed [plan]; `ccal budget` of it gives the designed U of the
// report (relative 1e-12: both are the full budget of the same numbers, read back exactly from 17 digits).
TEST_F(DesignCli, PlanOutBudgetsAsReported) {
  const std::string config = write("small.toml", read(kExample) + kSmallSpace);
  const Result d = run("design " + config + " --format json --plan-out designed.toml");
  ASSERT_EQ(d.code, 0) << d.err;
  const nlohmann::json j = nlohmann::json::parse(d.out);
  EXPECT_EQ(j.at("command"), "design");
  const Result b = run("budget designed.toml --format json");
  ASSERT_EQ(b.code, 0) << b.err;
  const nlohmann::json budget = nlohmann::json::parse(b.out);
  for (const auto& c : budget.at("coefficients")) {
    const std::string id = c.at("id");
    SCOPED_TRACE(id);
    const double designed = j.at("coefficients").at(id).at("designed_expanded").get<double>();
    const double written = c.at("expanded_uncertainty").get<double>();
    EXPECT_NEAR(written, designed, 1e-12 * designed);
    // Never worse than the configured plan on the coefficients the objective counts (all three here).
    EXPECT_LE(designed, j.at("coefficients").at(id).at("configured_expanded").get<double>() * (1 + 1e-12));
  }
  // The rest of the configuration is kept, the [design] table included.
  const std::string text = read(dir_ / "designed.toml");
  EXPECT_NE(text.find("[tolerances]"), std::string::npos);
  EXPECT_NE(text.find("turn_fractions = 4"), std::string::npos);
  EXPECT_EQ(text.find("name = \"10g\""), std::string::npos);  // the configured runs are gone (10 g: not designed)
  // The designed runs are named after their g-levels, rounded as the operator sets them (docs/config.md).
  EXPECT_NE(text.find("name = \"5g-2\"\ng_level = \"5 g\""), std::string::npos) << text;
}

TEST_F(DesignCli, BadDesignSpacesAreRefused) {
  const std::string base = read(kExample);
  const std::string key = write("key.toml", base + "\n[design]\nrunz = 6\n");
  expect_bad_input(run("design " + key), {"key.toml:", "design.runz: unknown key; did you mean 'runs'?"});
  const std::string high = write("high.toml", base + "\n[design]\ng_levels = [\"5 g\", \"45 g\"]\n");
  expect_bad_input(run("design " + high), {"design.g_levels: 45 g exceeds max_g = 30 g"});
  const std::string few = write("few.toml", base + "\n[design]\nruns = 2\n");
  expect_bad_input(run("design " + few), {"design.runs: 2 runs cannot identify 3 free terms"});
  const std::string long_runs = write("long.toml", base + "\n[design]\ndurations = [\"1000 s\"]\n");
  expect_bad_input(run("design " + long_runs), {"cannot fit total_time"});
  // Two g-levels cannot give the default four distinct ones (free terms + 1), nor 7 the six runs.
  const std::string two =
      "\n[design]\ng_levels = [\"10 g\", \"20 g\"]\nturn_fractions = 1\n"
      "phases = [\"180 deg\"]\narm_azimuths = [\"0 deg\"]\n";
  expect_bad_input(
      run("design " + write("two.toml", base + two)),
      {"two.toml: design: 6 runs over 2 allowed g-levels give at most 2 distinct g-levels, but a test "
       "of the fit of 3 free terms (K0, K2, K3) for a missing term needs 4 (the default of "
       "design.min_g_levels: free terms + 1); accepted: design.runs and the allowed g-levels at least "
       "4, or design.min_g_levels = 2 to design without that test"});
  expect_bad_input(run("design " + write("seven.toml", base + "\n[design]\nmin_g_levels = 7\n")),
                   {"seven.toml: design.min_g_levels: 7 but 6 runs over 26 allowed g-levels give at most 6 "
                    "distinct g-levels; accepted: at most 6, or more runs or g-levels"});
  expect_bad_input(run("design " + write("zero.toml", base + "\n[design]\nmin_g_levels = 0\n")),
                   {"zero.toml:", "design.min_g_levels", "a number of distinct g-levels from 1 to 1000"});
  // A machine that sets nothing finer than zero: the resolutions must be positive, named with their line.
  expect_bad_input(run("design " + write("res.toml", base + "\n[design]\ng_resolution = \"0 g\"\n")),
                   {"res.toml:", "design.g_resolution: must be positive, got 0 g"});
  expect_bad_input(run("design " + write("dur.toml", base + "\n[design]\nduration_resolution = \"-1 ms\"\n")),
                   {"dur.toml:", "design.duration_resolution: must be positive, got -1 ms"});
  // Two g-levels and whole turns cannot separate K0, K2 and K3: no plan is well posed.
  const std::string blind = write("blind.toml", base + two + "min_g_levels = 2\n");
  expect_bad_input(run("design " + blind), {"identifies every free term"});
}

TEST_F(DesignCli, BadOptionsAreRefused) {
  const std::string config = write("small.toml", read(kExample) + kSmallSpace);
  expect_bad_input(run("design " + config + " --plan-out small.toml"), {"small.toml"});
  expect_bad_input(run("design " + config + " --target K9=1"), {"--target", "K9"});
  expect_bad_input(run("design " + config + " --tradeoff 0,1"), {"--tradeoff"});
  // An empty item is a typing error, not nothing (CLI11's own splitting dropped it).
  expect_bad_input(run("design " + config + " --tradeoff 1,,2"), {"--tradeoff: 1,,2 has an empty item"});
  // A factor whose scaled space holds no plan is said of the factor, not of [design] keys the user never wrote.
  expect_bad_input(run("design " + config + " --tradeoff 1e-300"),
                   {"--tradeoff: 1e-300 scales the total time to", "for which the design fails ("});
  expect_bad_input(run("design " + config + " --objective best"), {"--objective"});
}

// A test of two instruments (examples/two_instruments.toml, its set-up named by its path) through the program:
// one designed plan, each instrument's U against the target (met: the joint objective keeps every instrument
// within it, tests/verbs/design_instruments_test.cpp); --plan-out writes the configuration of both instruments
// with the designed runs, which `ccal budget` takes.
TEST_F(DesignCli, ATestOfTwoInstrumentsGetsOnePlanForBoth) {
  std::string two = read(CCAL_SOURCE_DIR + "/examples/two_instruments.toml");
  const std::string setup = "setup = \"lab.toml\"";
  two.replace(two.find(setup), setup.size(), "setup = \"" + CCAL_SOURCE_DIR + "/examples/lab.toml\"");
  const std::string config = write("two.toml", two + kSmallSpace);
  const Result d = run("design " + config + " --target K3=1e-3 --format json --plan-out designed.toml");
  ASSERT_EQ(d.code, 0) << d.err;
  const nlohmann::json j = nlohmann::json::parse(d.out);
  ASSERT_EQ(j.at("instruments").size(), 2u);
  EXPECT_FALSE(j.contains("coefficients"));
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& designed = j.at("instruments")[i].at("coefficients").at("K3");
    EXPECT_LE(designed.at("designed_expanded").get<double>(), 1e-3);
    EXPECT_TRUE(designed.at("is_target").get<bool>());
  }
  const std::string written = read(dir_ / "designed.toml");
  EXPECT_EQ(written.find("name = \"10g\""), std::string::npos);  // the configured runs are gone
  for (const auto& run : j.at("designed_plan"))
    EXPECT_NE(written.find("name = \"" + run.at("name").get<std::string>() + "\""), std::string::npos) << run;
  const Result b = run("budget designed.toml --format json");
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_EQ(nlohmann::json::parse(b.out).at("instruments").size(), 2u);
  // --tradeoff answers for one instrument.
  const Result t = run("design " + config + " --tradeoff 0.5,1");
  EXPECT_EQ(t.code, 2);
  EXPECT_NE(t.err.find("--tradeoff"), std::string::npos) << t.err;
}

}  // namespace
}  // namespace ccal::test
