// Pinned behaviour: every verb's JSON output on the bundled example and on a second configuration
// (tests/data/golden/second.toml: lever arms, latitude 30°, known errors, a phase-locked platform with ripple
// and rate noise, instrument noise, a fixed-platform run, a reversed mounting) equals the saved output in
// tests/data/golden/, number for number (exact equality: the outputs print 17 significant digits where it
// matters, and any change of the arithmetic shows). Only the version, the timing and the thread count are
// left out. A key the saved output lacks is allowed (a new result field is a feature, not a change of
// behaviour); a missing key or a different value fails.
//
// After a deliberate change of behaviour, regenerate with CCAL_UPDATE_GOLDEN=1 (docs/testing.md) and say
// why in the commit message.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <ostream>
#include <regex>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "test_paths.hpp"

namespace {

using namespace ccal::test;
using nlohmann::json;

const fs::path kGolden = fs::path(CCAL_SOURCE_DIR) / "tests/data/golden";

// Fields that depend on the machine or the build, not on the computation.
bool volatile_key(const std::string& key) {
  return key == "ccal_version" || key == "wall_time_s" || key == "threads" || key == "trials_per_s" ||
         key == "cache_seconds" || key == "search_seconds" || key == "candidates_from_cache";
}

// The Monte Carlo note names its thread count and run time: "…, seed 1, 2 threads, 0.262 s."
std::string without_timing(const std::string& s) {
  static const std::regex timing(R"(, \d+ threads?, [0-9.]+ s)");
  return std::regex_replace(s, timing, "");
}

json normalised(const json& j) {
  if (j.is_object()) {
    json out = json::object();
    for (const auto& [key, value] : j.items())
      if (!volatile_key(key)) out[key] = normalised(value);
    return out;
  }
  if (j.is_array()) {
    json out = json::array();
    for (const auto& v : j) out.push_back(normalised(v));
    return out;
  }
  if (j.is_string()) return without_timing(j.get<std::string>());
  return j;
}

// Every value of `saved` is in `now` and equal; reports the first differing path.
void expect_contains(const json& saved, const json& now, const std::string& path) {
  if (saved.is_object()) {
    ASSERT_TRUE(now.is_object()) << path << ": was an object";
    for (const auto& [key, value] : saved.items()) {
      ASSERT_TRUE(now.contains(key)) << path << "/" << key << ": missing";
      expect_contains(value, now[key], path + "/" + key);
    }
    return;
  }
  if (saved.is_array()) {
    ASSERT_TRUE(now.is_array()) << path << ": was an array";
    ASSERT_EQ(saved.size(), now.size()) << path << ": array length";
    for (std::size_t k = 0; k < saved.size(); ++k)
      expect_contains(saved[k], now[k], path + "/" + std::to_string(k));
    return;
  }
  ASSERT_EQ(saved, now) << path;
}

struct Case {
  std::string name;     // golden file stem
  std::string command;  // arguments of ccal, run in the test's folder
};

// The configurations: the bundled example (no file argument) and the second one, copied into the folder.
std::vector<Case> cases() {
  std::vector<Case> all;
  for (const auto& [stem, config] :
       {std::pair<std::string, std::string>{"bundled", ""}, {"second", "second.toml"}}) {
    const std::string c = config.empty() ? "" : " " + config;
    const std::string targets =
        stem == "bundled" ? " --target K2=2e-5 --target K3=2e-3" : " --target K2=1e-5 --target K3=1e-3";
    all.push_back({stem + ".budget", "budget" + c + " --format json"});
    all.push_back({stem + ".budget_automatic", "budget" + c + " --derivatives automatic --format json"});
    all.push_back({stem + ".simulate", "simulate" + c + " --format json"});
    // Paper mode needs every run on the paper's mounting: the bundled plan only.
    if (stem == "bundled") all.push_back({stem + ".simulate_paper", "simulate --mode paper --format json"});
    all.push_back({stem + ".force", "force" + c + " --format json"});
    all.push_back({stem + ".force_run3", "force" + c + " --run 3 --time '123.4 s' --format json"});
    all.push_back({stem + ".montecarlo", "montecarlo" + c + " --trials 3000 --seed 7 --format json"});
    all.push_back({stem + ".allocate", "allocate" + c + targets + " --format json"});
    all.push_back({stem + ".identify",
                   "simulate" + c + " --observations-out obs.csv -o /dev/null && ccal_identify obs.csv"});
    all.push_back({stem + ".reduce", "reduce" + c});
    // The design of the bundled plan with the [design] defaults (9990 candidates, a few seconds).
    if (stem == "bundled") all.push_back({stem + ".design", "design --format json"});
  }
  return all;
}

// Synthetic logs of the first three runs of the plan: pulses of 1e-3 deg at a made-up mean rate, encoders
// turning at the planned rate of a 2.5 m arm (within the reduction's 5 % plausibility window) every 0.1 s.
// Pure test data: no library code computes them, so they cannot drift with the code under test.
std::string write_logs(const fs::path& dir) {
  const double g_levels[] = {5, 10, 15};
  const double means_deg_s[] = {2526.171, 5052.236, 7578.517};
  std::string args;
  for (int r = 0; r < 3; ++r) {
    const double rate = std::sqrt(g_levels[r] * 9.8 / 2.5), T = 120;
    std::string text = "time,pulses,theta1,gamma\n";
    for (int k = 0; k <= 1200; ++k) {
      const double t = T * k / 1200;
      const double theta1 = std::fmod(0.3 + rate * (1 + 1e-6) * t, 2 * std::numbers::pi);
      const double gamma =
          std::fmod(4 * 2 * std::numbers::pi + 1.1 - rate * (1 - 2e-6) * t, 2 * std::numbers::pi);
      text += std::to_string(t) + "," + std::to_string(std::floor(means_deg_s[r] * t / 1e-3)) + "," +
              std::to_string(theta1) + "," + std::to_string(gamma) + "\n";
    }
    const std::string name = "run" + std::to_string(r + 1) + ".csv";
    std::ofstream(dir / name) << text;
    args += " --log " + std::to_string(r + 1) + "=" + name;
  }
  return args + " --pulse-weight 1e-3 --format json";
}

void PrintTo(const Case& c, std::ostream* os) { *os << "ccal " << c.command; }

class Golden : public Cli, public ::testing::WithParamInterface<Case> {};

TEST_P(Golden, OutputEqualsTheSavedOne) {
  const Case& c = GetParam();
  fs::copy_file(kGolden / "second.toml", dir_ / "second.toml");
  std::string command = c.command;
  if (command.rfind("reduce", 0) == 0) command += write_logs(dir_);
  // The identify case chains two commands: the second runs the same program.
  const auto at = command.find("ccal_identify");
  if (at != std::string::npos) command.replace(at, 13, quote(kProgram) + " identify --format json");
  const Result r = run(command);
  ASSERT_EQ(r.code, 0) << c.command << "\n" << r.err;
  const json now = normalised(json::parse(r.out));
  const fs::path file = kGolden / (c.name + ".json");
  if (std::getenv("CCAL_UPDATE_GOLDEN")) {
    std::ofstream(file) << now.dump(1) << "\n";
    GTEST_SKIP() << "wrote " << file;
  }
  ASSERT_TRUE(fs::exists(file)) << file << " missing: run with CCAL_UPDATE_GOLDEN=1";
  std::ifstream in(file);
  expect_contains(json::parse(in), now, c.name);
}

INSTANTIATE_TEST_SUITE_P(EveryVerb, Golden, ::testing::ValuesIn(cases()), [](const auto& info) {
  std::string n = info.param.name;
  for (char& ch : n)
    if (ch == '.') ch = '_';
  return n;
});

}  // namespace
