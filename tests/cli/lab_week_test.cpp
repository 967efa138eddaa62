// A lab's week end to end: `ccal simulate --truth FILE` gives the simulated machine the truth file's errors, the
// lab's configuration only what it measured; its logs, written in a data acquisition system's layout into a
// folder with its manifest, are reduced by `ccal reduce --logs DIR` as ccal's own are; the statement corrects for
// the measured error alone; a bad truth file or manifest is refused with its place and nothing is written.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <string>

#include "ccal/core/sha256.hpp"
#include "cli_support.hpp"

namespace {

using namespace ccal::test;
namespace fs = std::filesystem;

const std::string kLab = CCAL_SOURCE_DIR + "/examples/lab.toml";
const std::string kLabTruth = CCAL_SOURCE_DIR + "/examples/lab_truth.toml";

TEST_F(Cli, TheMachineHasTheTruthAndTheStatementCorrectsOnlyWhatTheLabMeasured) {
  const Result sim = run("simulate " + kLab + " --truth " + kLabTruth + " --observations-out obs.csv --format json");
  ASSERT_EQ(sim.code, 0) << sim.err;
  const auto js = nlohmann::json::parse(sim.out);
  EXPECT_EQ(js["errors_nonzero"], 5);
  EXPECT_EQ(js["truth"]["file"], kLabTruth);
  EXPECT_EQ(js["truth"]["sha256"], ccal::sha256_hex(read(kLabTruth)));
  // The observations are the lab's: they name its configuration, not the truth.
  const std::string obs = read(dir_ / "obs.csv");
  EXPECT_EQ(obs.find("lab_truth"), std::string::npos);
  const Result text = run("simulate " + kLab + " --truth " + kLabTruth + " -o /dev/null");
  ASSERT_EQ(text.code, 0) << text.err;

  // The statement knows dthz5, the one [errors] entry of lab.toml: its correction is minus that error's bias row
  // in `ccal budget` (the budget of the configuration's own [errors]), for every coefficient.
  const Result st = run("identify obs.csv --statement --statement-trials 0 --config " + kLab + " --format json");
  ASSERT_EQ(st.code, 0) << st.err;
  const Result budget = run("budget " + kLab + " --format json");
  ASSERT_EQ(budget.code, 0) << budget.err;
  const auto s = nlohmann::json::parse(st.out)["statement"];
  const auto b = nlohmann::json::parse(budget.out);
  EXPECT_EQ(s["known_errors"], 1);
  for (const auto& c : b["coefficients"]) {
    const std::string id = c["id"];
    const double bias = b["known_error_bias"][id];
    // 1e-12 relative: the same shift, scaled to the fit's unit.
    EXPECT_NEAR(s["coefficients"][id]["correction"].get<double>(), -bias, 1e-12 * std::abs(bias) + 1e-300) << id;
  }
}

TEST_F(Cli, ADaqFolderIsReducedByItsManifestAsCcalsOwnLogsAre) {
  {
    std::ofstream f(dir_ / "daq.toml");
    f << "[columns]\ntime = \"t_ms\"\ntime_unit = \"ms\"\npulses = \"piga_count\"\ntheta1 = \"enc_main\"\n"
         "gamma = \"enc_platform\"\nangle_unit = \"counts\"\ncounts_per_revolution = 16777216\n";
  }
  const std::string simulate = "simulate " + kLab + " --truth " + kLabTruth + " -o /dev/null --logs-out ";
  ASSERT_EQ(run(simulate + "own").code, 0);
  const Result daq = run(simulate + "daq --log-layout daq.toml");
  ASSERT_EQ(daq.code, 0) << daq.err;
  const std::string log = read(dir_ / "daq" / "20g.csv");
  EXPECT_EQ(log.substr(0, log.find('\n')), "t_ms,piga_count,enc_main,enc_platform");
  EXPECT_NE(read(dir_ / "daq" / "manifest.toml").find("counts_per_revolution = 16777216"), std::string::npos);
  const Result own = run("reduce " + kLab + " --logs own --statement --statement-trials 0 --format json");
  const Result theirs = run("reduce " + kLab + " --logs daq --statement --statement-trials 0 --format json");
  ASSERT_EQ(own.code, 0) << own.err;
  ASSERT_EQ(theirs.code, 0) << theirs.err;
  const auto a = nlohmann::json::parse(own.out)["statement"]["coefficients"];
  const auto b = nlohmann::json::parse(theirs.out)["statement"]["coefficients"];
  // The same pulse counts; encoder readings quantised to 2π/2^24 = 3.7e-7 rad move the measured rates by ~1e-9
  // rad/s and the regressors with them: the estimates agree to 1e-3 of their U.
  for (const auto& [id, c] : a.items()) {
    const double U = c["expanded_uncertainty"];
    EXPECT_NEAR(b[id]["corrected_estimate"].get<double>(), c["corrected_estimate"].get<double>(), 1e-3 * U) << id;
  }
  // The --log form of the same folder gives the same numbers as its manifest.
  std::string logs;
  for (const char* r : {"5g", "10g", "15g", "20g", "25g", "30g"}) logs += fmt::format(" --log {0}=own/{0}.csv", r);
  const Result listed = run("reduce " + kLab + logs + " --statement --statement-trials 0 --format json");
  ASSERT_EQ(listed.code, 0) << listed.err;
  EXPECT_EQ(nlohmann::json::parse(listed.out)["statement"]["coefficients"], a);
  // A folder without a manifest, and --log with --logs.
  fs::create_directories(dir_ / "empty");
  const Result none = run("reduce " + kLab + " --logs empty");
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("empty/manifest.toml: no manifest in the folder; accepted: "), std::string::npos)
      << none.err;
  const Result both = run("reduce " + kLab + " --logs own --log 5g=own/5g.csv");
  EXPECT_EQ(both.code, 2);
  EXPECT_NE(both.err.find("--log and --logs: give one of them"), std::string::npos) << both.err;
}

TEST_F(Cli, ABadTruthFileIsRefusedWithItsPlaceAndNothingWritten) {
  {
    std::ofstream f(dir_ / "truth.toml");
    f << "[errors]\ndthz5 = \"1 arcsec\"\n[centrifuge]\nradius = \"2 m\"\n";
  }
  const Result r = run("simulate " + kLab + " --truth truth.toml --observations-out obs.csv -o out.txt");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(r.err.starts_with("ccal: error: truth.toml:3:2: centrifuge: a configuration's table, not a truth's; "
                                "accepted: [errors] only"))
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "obs.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "out.txt"));
  const Result layout = run("simulate " + kLab + " --log-layout daq.toml");
  EXPECT_EQ(layout.code, 2);
  EXPECT_NE(layout.err.find("--log-layout: is read only for the logs; accepted: with --logs-out DIR"),
            std::string::npos)
      << layout.err;
  const Result missing = run("simulate " + kLab + " --truth none.toml");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("none.toml: cannot read the file"), std::string::npos) << missing.err;
}

}  // namespace
