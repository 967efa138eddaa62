// Hardening, round seven, through the program: what round six left open and what a fresh round of a careless
// user's wrong inputs found, each refused in words that say what is wrong, where, and what is accepted, and
// nothing left behind or lost.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

// A statement of one coefficient K0 [deg/s] with U and k = 2 (unique names: unity builds join the test files).
std::string seven_statement(const std::string& certificate = "") {
  return fmt::format(R"({{"coverage_probability": 0.95, {}"coefficients": {{"K0": {{"unit": "deg/s",
      "corrected_estimate": 1.5, "expanded_uncertainty": 0.2, "coverage_factor": 2}}}}}})",
                     certificate);
}

// A coverage probability given beside a stated coverage factor was taken when it was the default's value
// (0.95), which the options could not tell from none given: every command that takes both refuses both.
TEST_F(Cli, TwoCoveragesAreRefusedAlsoAtTheDefaultProbability) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --observations-out obs.csv --logs-out L -o /dev/null").code, 0);
  const std::string both = " --coverage-probability 0.95 --coverage-factor 2";
  for (const std::string& command :
       {"identify obs.csv --config " + quote(kLab) + " --statement" + both + " -o out.txt",
        "reduce " + quote(kLab) + " --logs L --statement" + both + " -o out.txt", "budget" + both + " -o out.txt",
        "design" + both + " -o out.txt", "report" + both + " -o out.html"}) {
    SCOPED_TRACE(command);
    expect_bad_input(run(command), {"--coverage-factor: 2 and --coverage-probability 0.95 are two coverages; "
                                    "accepted: one of them (a stated coverage factor, or a coverage "
                                    "probability)"});
    EXPECT_FALSE(fs::exists(dir_ / "out.txt") || fs::exists(dir_ / "out.html"));
  }
  // Either alone is taken; the help still states the default p.
  EXPECT_EQ(run("budget --coverage-probability 0.95 -o a.txt").code, 0);
  EXPECT_EQ(run("budget --coverage-factor 2 -o b.txt").code, 0);
  for (const char* verb : {"budget", "identify", "reduce", "design", "report", "montecarlo"}) {
    const Result help = run(std::string(verb) + " --help");
    EXPECT_NE(help.out.find("(default: 0.95)"), std::string::npos) << verb << "\n" << help.out;
  }
}

// `design --plan-out plan.json` wrote TOML under a name that says JSON; the plan is a configuration, which is
// read as TOML: another extension is refused before the design, and nothing is written.
TEST_F(Cli, ThePlanIsWrittenOnlyUnderATomlName) {
  for (const char* name : {"plan.json", "plan", "plan.toml.bak"}) {
    expect_bad_input(run(fmt::format("design --plan-out {} -o d.txt", name)),
                     {fmt::format("--plan-out: '{}' has no .toml extension, and the plan is written as a TOML "
                                  "configuration; accepted: FILE.toml, e.g. designed.toml",
                                  name)});
    EXPECT_FALSE(fs::exists(dir_ / name)) << name;
  }
  EXPECT_FALSE(fs::exists(dir_ / "d.txt"));
}

// `history add --date 9999-12-31` was recorded: a date after today (UTC) is refused, given or from the
// statement's certificate, and no store is left behind.
TEST_F(Cli, ACalibrationDatedAfterTodayIsNotRecorded) {
  write("st.json", seven_statement());
  expect_bad_input(run("history add st.json --db h.sqlite --serial S1 --date 9999-12-31"),
                   {"--date: 9999-12-31 is after today (", ", UTC), and a calibration is recorded once it is done; "
                                                           "accepted: its date, YYYY-MM-DD, up to "});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
  write("future.json",
        seven_statement(R"("certificate": {"serial_number": "S1", "date_of_calibration": "9999-12-31"}, )"));
  expect_bad_input(run("history add future.json --db h.sqlite"),
                   {"future.json: date of calibration '9999-12-31' ([certificate] date_of_calibration) is after "
                    "today (",
                    "accepted: a statement of a calibration done by "});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
  // An earlier date is recorded.
  EXPECT_EQ(run("history add st.json --db h.sqlite --serial S1 --date 2020-02-29").code, 0);
}

// A write that fails for want of space said only "No space left on device": it says what is accepted.
TEST_F(Cli, AFullDeviceSaysWhatIsAccepted) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  expect_bad_input(run("budget -o /dev/full"),
                   {"-o: cannot write '/dev/full': No space left on device; accepted: a path on a device with "
                    "space for the output (or free some space)"});
}

}  // namespace
