// A lab's week end to end: `ccal design` writes the plan as its operator runs it (the run sheet, rounded to the
// machine's steps, runs named after their g-levels); `ccal simulate --truth FILE` gives the simulated machine the
// truth file's errors, the lab's configuration only what it measured; its logs, written in a data acquisition
// system's layout into a folder with its manifest, are reduced by `ccal reduce --logs DIR` as ccal's own are; the
// statement corrects for the measured error alone; an allocation for one target leaves the others no worse; a
// bad truth file or manifest is refused with its place and nothing is written.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <string>

#include "ccal/core/sha256.hpp"
#include "cli_support.hpp"

namespace {

using namespace ccal::test;
namespace fs = std::filesystem;

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
  // A run the manifest names wrongly is refused at the manifest's line (its [runs] key), not as an option the
  // user did not give: an unknown run, and one file for two runs.
  std::string manifest = read(dir_ / "own" / "manifest.toml");
  const std::size_t at = manifest.find("10g = '10g.csv'");
  ASSERT_NE(at, std::string::npos) << manifest;
  const int line = int(std::count(manifest.begin(), manifest.begin() + std::ptrdiff_t(at), '\n')) + 1;
  auto refused = [&](const std::string& entry) {
    std::ofstream(dir_ / "own" / "manifest.toml") << std::string(manifest).replace(at, 15, entry);
    const Result r = run("reduce " + kLab + " --logs own -o /dev/null");
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(r.err.find("--log"), std::string::npos) << r.err;
    return r.err;
  };
  EXPECT_NE(refused("10G = '10g.csv'").find(fmt::format("own/manifest.toml:{}:1: runs.10G: '10G' is no run; ", line)),
            std::string::npos);
  EXPECT_NE(refused("10g = '5g.csv'")
                .find(fmt::format("own/manifest.toml:{}:1: runs.10g: run '10g' has the same log as run '5g'", line)),
            std::string::npos);
}

// The whole week: the designed plan's run sheet, its logs simulated from the separate truth into a DAQ-layout
// folder, the folder reduced by its manifest, and a statement corrected for the stated error alone; and an
// allocation for one target that leaves the other coefficients no worse.
TEST_F(Cli, TheWholeWeekFromTheDesignedRunSheetToTheStatement) {
  {
    std::ofstream f(dir_ / "daq.toml");
    f << "[columns]\ntime = \"t_ms\"\ntime_unit = \"ms\"\npulses = \"piga_count\"\ntheta1 = \"enc_main\"\n"
         "gamma = \"enc_platform\"\nangle_unit = \"counts\"\ncounts_per_revolution = 16777216\n";
  }
  // Monday: the plan, as the operator sets it.
  const Result design = run("design " + kLab + " --plan-out designed.toml --format json");
  ASSERT_EQ(design.code, 0) << design.err;
  const auto sheet = nlohmann::json::parse(design.out)["run_sheet"];
  ASSERT_EQ(sheet["runs"].size(), 6u);
  std::set<std::string> levels;
  // Each value a whole number of the machine's steps (0.01 g, 1 ms, 0.1 deg): 1e-9 of a step is round-off of
  // the unit conversion.
  auto on_step = [](double value, double step) {
    return std::abs(value / step - std::round(value / step)) < 1e-6;
  };
  for (const auto& line : sheet["runs"]) {
    const double g = line["g_level_g"];
    EXPECT_TRUE(on_step(g, 0.01)) << line;
    EXPECT_TRUE(on_step(line["duration_s"].get<double>(), 0.001)) << line;
    EXPECT_TRUE(
        on_step(line[line["sets"] == "stop_phase" ? "stop_phase_deg" : "start_phase_deg"].get<double>(), 0.1))
        << line;
    EXPECT_TRUE(on_step(line["arm_azimuth_deg"].get<double>(), 0.1)) << line;
    const std::string level = fmt::format("{:.12g}g", g);
    EXPECT_TRUE(line["run"].get<std::string>().starts_with(level))
        << line;  // the log's name says its g-level
    levels.insert(level);
  }
  EXPECT_GE(levels.size(), 4u);  // three free terms + 1: the residuals can show a term the model lacks
  const std::string written = read(dir_ / "designed.toml");
  const std::string plan = written.substr(written.find("\n[plan]"));
  EXPECT_EQ(plan.find(" rad\""), std::string::npos)
      << plan;  // degrees, seconds and g, as the operator sets them
  EXPECT_NE(plan.find("terminal_phase = \""), std::string::npos) << plan;

  // Tuesday: the machine, which has the truth's errors, runs the sheet; the DAQ writes its own layout.
  const Result sim = run("simulate designed.toml --truth " + kLabTruth +
                         " -o /dev/null --logs-out daq --log-layout daq.toml");
  ASSERT_EQ(sim.code, 0) << sim.err;
  for (const auto& line : sheet["runs"])
    EXPECT_TRUE(fs::exists(dir_ / "daq" / (line["run"].get<std::string>() + ".csv"))) << line;

  // Wednesday: the folder reduced by its manifest, against the lab's configuration with the designed plan.
  const Result reduced =
      run("reduce designed.toml --logs daq --statement --statement-trials 0 --format json");
  ASSERT_EQ(reduced.code, 0) << reduced.err;
  const auto red = nlohmann::json::parse(reduced.out);
  ASSERT_EQ(red["runs"].size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    const auto& logged = red["runs"][k];
    EXPECT_EQ(logged["name"], sheet["runs"][k]["run"]);
    EXPECT_EQ(logged["log_sha256"],
              ccal::sha256_hex(read(dir_ / "daq" / (logged["name"].get<std::string>() + ".csv"))));
    // The platform's start as the encoder saw it is the sheet's: the truth's errors move it by arcseconds,
    // the encoder's counts by 2π/2^24; 0.01 deg is far above both and far below the sheet's 0.1 deg step.
    const double measured =
        logged["platform_encoder"]["initial_phase_rad"].get<double>() * 180 / std::numbers::pi;
    EXPECT_NEAR(std::remainder(measured - sheet["runs"][k]["start_phase_deg"].get<double>(), 360.0), 0, 0.01)
        << logged["name"];
  }
  // The statement corrects for dthz5, the one error lab.toml states, and nothing else: its correction is
  // minus that error's bias row in `ccal budget` of the same configuration (1e-12 relative: the same shift).
  const auto st = red["statement"];
  EXPECT_EQ(st["known_errors"], 1);
  const Result budget = run("budget designed.toml --format json");
  ASSERT_EQ(budget.code, 0) << budget.err;
  const auto b = nlohmann::json::parse(budget.out);
  for (const auto& c : b["coefficients"]) {
    const std::string id = c["id"];
    const double bias = b["known_error_bias"][id];
    EXPECT_NEAR(st["coefficients"][id]["correction"].get<double>(), -bias, 1e-12 * std::abs(bias) + 1e-300)
        << id;
  }

  // Thursday: what the centrifuge must be for U(K3) at half the configured; K0 and K2 are held.
  const Result configured = run("allocate " + kLab + " --target K3=1 --format json");
  ASSERT_EQ(configured.code, 0) << configured.err;
  const double U3 = nlohmann::json::parse(configured.out)["coefficients"]["K3"]["configured_expanded"];
  const Result allocated = run(fmt::format("allocate {} --target K3={:.6g} --format json", kLab, U3 / 2));
  ASSERT_EQ(allocated.code, 0) << allocated.err;
  const auto a = nlohmann::json::parse(allocated.out);
  EXPECT_TRUE(a["grown"].empty()) << a["grown"];
  for (const auto& [id, c] : a["coefficients"].items()) {
    if (id == "K3") continue;
    // No worse: 1e-9 relative is the solver's tolerance on a held constraint.
    EXPECT_LE(c["allocated_expanded"].get<double>(), c["configured_expanded"].get<double>() * (1 + 1e-9))
        << id;
    EXPECT_TRUE(c["held"].get<bool>()) << id;
  }
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
