// One meaning per option name across the verbs: --coverage-factor is a stated factor k (budget, design,
// report; k < 1 refused), --coverage-probability is a probability p (every verb that states a U); the old
// --coverage is refused with a message naming its successor; allocate follows the configuration's mode. Each of these failed before.
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace ccal::test {
namespace {

using OptionTraps = Cli;

TEST_F(OptionTraps, BudgetCoverageFactorBelowOneIsRefused) {
  // `--coverage 0.95` used to print an "expanded" uncertainty smaller than u with exit code 0.
  expect_bad_input(run("budget --coverage 0.95"), {"--coverage", "--coverage-factor"});
  expect_bad_input(run("budget --coverage-factor 0.95"), {"--coverage-factor", "accepted: 1 to 10", "--coverage-probability"});
  const Result r = run("budget --coverage-factor 3 --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["coverage_factor"], 3.0);
  for (const auto& c : j["coefficients"])  // U = 3 u: one product, relative 1e-15
    EXPECT_NEAR(c["expanded_uncertainty"].get<double>(), 3 * c["standard_uncertainty"].get<double>(),
                1e-15 * c["expanded_uncertainty"].get<double>());
  EXPECT_EQ(j["coverage_method"], "stated k");
  EXPECT_NEAR(j["coverage_probability"].get<double>(), 0.9973002039367398, 1e-15);  // erf(3/√2)
  // One coverage convention: p as in every verb, k = Φ⁻¹((1 + p)/2); both at once are refused.
  const Result p = run("budget --coverage-probability 0.99 --format json");
  ASSERT_EQ(p.code, 0) << p.err;
  EXPECT_NEAR(nlohmann::json::parse(p.out)["coverage_factor"].get<double>(), 2.5758293035489004, 1e-15);
  expect_bad_input(run("budget --coverage-probability 0.9 --coverage-factor 2"),
                   {"--coverage-factor: 2 and --coverage-probability 0.9 are two coverages"});
}

TEST_F(OptionTraps, BudgetTopAndWidthOutOfRangeAreRefusedWithTheRange) {
  // Exit 2, one line naming the option and the accepted range (not the largest double).
  expect_bad_input(run("budget --top 0"), {"--top", "1 to 100000"});
  expect_bad_input(run("budget --top -3"), {"--top", "1 to 100000"});
  expect_bad_input(run("budget --width 10"), {"--width", "40 to 10000"});
}

TEST_F(OptionTraps, AllocateCoverageIsAProbabilityByName) {
  expect_bad_input(run("allocate --target K3=2e-3 --coverage 0.9"), {"--coverage", "--coverage-probability"});
  expect_bad_input(run("allocate --target K3=2e-3 --coverage-probability 2"), {"--coverage-probability"});
  const Result r =
      run("allocate --target K3=2e-3 --coverage-probability 0.9 --verify-trials 0 --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["coverage_probability"], 0.9);
  // k_p = Φ⁻¹(0.95) = 1.6448536269514722 (16-digit normal quantile), relative 1e-12.
  EXPECT_NEAR(j["coverage_factor"].get<double>(), 1.6448536269514722, 1e-12 * 1.65);
}

TEST_F(OptionTraps, AllocateFollowsTheConfigurationsMode) {
  // A paper-mode configuration: allocate's U at the configured tolerances is k_p u of `budget` in paper mode
  // (it used to be the exact-mode u, three times larger for K3, without a word).
  const std::string text = read(kPaperExample);
  const auto at = text.find("mode = \"exact\"");
  ASSERT_NE(at, std::string::npos);
  const std::string cfg = write("paper.toml", text.substr(0, at) + "mode = \"paper\"" + text.substr(at + 14));
  const Result b = run("budget " + cfg + " --coverage-factor 1.959963984540054 --format json");
  const Result a = run("allocate " + cfg + " --target K3=1e-6 --verify-trials 0 --format json");
  ASSERT_EQ(b.code, 0) << b.err;
  ASSERT_EQ(a.code, 0) << a.err;
  const auto jb = nlohmann::json::parse(b.out), ja = nlohmann::json::parse(a.out);
  EXPECT_EQ(jb["mode"], "paper");
  EXPECT_EQ(ja["mode"], "paper");
  const double budget_U = jb["coefficients"][2]["expanded_uncertainty"];
  // The same LPU on both sides, k_p = Φ⁻¹(0.975) to 16 digits: relative 1e-9 (the allocation's sums).
  EXPECT_NEAR(ja["coefficients"]["K3"]["configured_expanded"].get<double>(), budget_U, 1e-9 * budget_U);
  // --mode exact overrides it.
  const Result e = run("allocate " + cfg + " --mode exact --target K3=1e-6 --verify-trials 0 --format json");
  ASSERT_EQ(e.code, 0) << e.err;
  EXPECT_EQ(nlohmann::json::parse(e.out)["mode"], "exact");
}

TEST_F(OptionTraps, AllocateTextFitsOneHundredColumns) {
  // It used to be 247 columns wide.
  const Result r = run("allocate --target K2=2e-5 --target K3=2e-3 --verify-trials 200");
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  for (std::string line; std::getline(lines, line);) {
    std::size_t columns = 0;  // UTF-8: count the bytes that start a character
    for (unsigned char c : line) columns += (c & 0xC0) != 0x80;
    EXPECT_LE(columns, 100u) << line;
  }
}

}  // namespace
}  // namespace ccal::test
