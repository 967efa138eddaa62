// Hardening, round nine, through the program: what round eight left and what a fresh round of a careless user's
// wrong inputs found, each refused in words that say what is wrong, where, and what is accepted.
#include <gtest/gtest.h>

#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

// An option that needs another was refused at any value but its default: `--max-trials 1000000` without
// --digits, `--statement-trials 100000`, `--seed 1` or `--threads 0` without --statement ran with exit 0. The
// options are told given from left out now, not by their value.
TEST_F(Cli, AnOptionGivenAtItsDefaultWithoutTheOptionItNeedsIsRefused) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --logs-out L --observations-out obs.csv -o /dev/null").code, 0);
  const std::string max_trials = "--max-trials: 1000000 bounds the adaptive procedure, which --digits 0 does not "
                                 "run (M is then --trials); accepted: --max-trials with --digits 1 to 6, or "
                                 "--max-trials left out";
  expect_bad_input(run("montecarlo --max-trials 1000000 -o m.txt"), {max_trials});
  expect_bad_input(run("report --trials 200 --max-trials 1000000 -o r.html"), {max_trials});
  expect_bad_input(run("report --trials 200 --statement-trials 100000 -o r.html"),
                   {"--statement-trials: 100000 checks the statement of observations, and none are given; "
                    "accepted: --statement-trials with --observations, or --statement-trials left out"});
  expect_bad_input(run("reduce " + quote(kLab) + " --logs L --statement-trials 100000 -o r.txt"),
                   {"--statement-trials: 100000 is an option of the calibration statement, which is not asked "
                    "for; accepted: --statement-trials with --statement, or --statement-trials left out"});
  expect_bad_input(run("reduce " + quote(kLab) + " --logs L --seed 1 -o r.txt"),
                   {"--seed: 1 is an option of the calibration statement, which is not asked for"});
  expect_bad_input(run("identify obs.csv --threads 0 -o r.txt"),
                   {"--threads: 0 is an option of the calibration statement, which is not asked for"});
  EXPECT_FALSE(fs::exists(dir_ / "m.txt") || fs::exists(dir_ / "r.html") || fs::exists(dir_ / "r.txt"));
  // With the option they serve, the same values are taken; the help still states the defaults.
  EXPECT_EQ(run("montecarlo --digits 1 --max-trials 1000000 -o m.txt").code, 0);
  EXPECT_EQ(run("reduce " + quote(kLab) + " --logs L --statement --statement-trials 0 --seed 1 --threads 0 -o "
                                          "r.txt")
                .code,
            0);
  const Result help = run("reduce --help");
  EXPECT_NE(help.out.find("--seed S                    Seed of the statement's Monte Carlo check (default: 1)"),
            std::string::npos)
      << help.out;
  EXPECT_NE(run("montecarlo --help").out.find("no stage beyond this many trials (default: 1000000)"),
            std::string::npos);
}

// `identify --terms K0,,K2` fitted K0 and K2 with exit 0: the empty item, a typing error, was dropped.
TEST_F(Cli, AnEmptyItemOfAListOfTermsIsRefused) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --observations-out obs.csv -o /dev/null").code, 0);
  expect_bad_input(run("identify obs.csv --terms K0,,K2 -o i.txt"),
                   {"--terms: 'K0,,K2' has an empty item; accepted: items separated by single commas, e.g. "
                    "K0,K2,K3"});
  expect_bad_input(run("identify obs.csv --terms K0,K2, -o i.txt"), {"--terms: 'K0,K2,' has an empty item"});
  expect_bad_input(run("identify obs.csv --known , -o i.txt"), {"--known: ',' has an empty item"});
  EXPECT_FALSE(fs::exists(dir_ / "i.txt"));
  EXPECT_EQ(run("identify obs.csv --terms K0,K2 --terms K3 -o i.txt").code, 0);
}

}  // namespace
