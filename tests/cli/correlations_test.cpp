// [[correlations]] through the program: `ccal budget` takes them (the JSON carries the input correlation
// matrix and the cross terms' share of u²); what does not take them yet refuses them clearly instead of
// ignoring them: the Monte Carlo, the allocation and the statement's Monte Carlo check.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

const std::string kPairs =
    "\n[[correlations]]\nbetween = [\"ripple1_c1\", \"ripple3_c1\"]\nr = -0.5\n\n[[correlations]]\n"
    "between = [\"dthy4\", \"dthy5\"]\nr = 0.6\n";

TEST_F(Cli, TheBudgetCarriesTheInputCorrelations) {
  const std::string config = write("c.toml", read(CCAL_SOURCE_DIR + "/examples/wang_ren_2014.toml") + kPairs);
  const Result r = run("budget " + config + " --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out)["input_correlation"];
  const auto& ids = j["sources"];
  std::size_t a = 0, b = 0;
  for (std::size_t s = 0; s < ids.size(); ++s) {
    if (ids[s] == "ripple1_c1") a = s;
    if (ids[s] == "ripple3_c1") b = s;
  }
  EXPECT_EQ(j["matrix"][a][b], -0.5);
  EXPECT_EQ(j["matrix"][b][a], -0.5);
  EXPECT_EQ(j["matrix"][a][a], 1.0);
  // K2's two ripples cancel: their cross term takes back nearly all of what each adds (-98.9 %).
  EXPECT_LT(j["share_of_variance"]["K2"].get<double>(), -0.9);
  const Result text = run("budget " + config);
  EXPECT_NE(text.out.find("correlations between sources -98.9 %"), std::string::npos) << text.out;
}

TEST_F(Cli, WhatDoesNotTakeThemYetRefusesThem) {
  const std::string config = write("c.toml", read(CCAL_SOURCE_DIR + "/examples/wang_ren_2014.toml") + kPairs);
  expect_bad_input(run("montecarlo " + config + " --trials 100"),
                   {"c.toml: [[correlations]]: the Monte Carlo does not take partly correlated inputs yet"});
  expect_bad_input(run("allocate " + config + " --target K3=1e-3"),
                   {"c.toml: [[correlations]]: the allocation does not take partly correlated inputs yet"});
  // The statement: its Monte Carlo check refuses them and says how to go without it; its LPU takes them.
  ASSERT_EQ(run("simulate " + config + " -o /dev/null --observations-out obs.csv").code, 0);
  expect_bad_input(run("identify obs.csv --statement --config " + config),
                   {"--statement-trials: ",
                    "has [[correlations]], which the statement's Monte Carlo check does "
                    "not take yet; accepted: 0 (the statement by the LPU alone)"});
  // A bad pair through the program: its place, exit code 2, nothing else.
  const std::string bad =
      write("bad.toml", read(CCAL_SOURCE_DIR + "/examples/wang_ren_2014.toml") +
                            "\n[[correlations]]\nbetween = [\"dthy4\", \"dthy5\"]\nr = 1.5\n");
  expect_bad_input(run("budget " + bad),
                   {"bad.toml:",
                    "correlations[1].r: 1.5 is not a correlation coefficient; accepted: a number from "
                    "-1 to 1"});
  const Result lpu = run("identify obs.csv --statement --statement-trials 0 --config " + config + " --format json");
  ASSERT_EQ(lpu.code, 0) << lpu.err;
}

}  // namespace
