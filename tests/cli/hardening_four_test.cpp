// Hardening, round four, through the program: the allocation's line of the correlated sources' cross terms
// (the budget's line, at the allocated tolerances; with the shares it makes 100 % of u²), and the history's
// words for a calibration id that is no number and a mistyped subcommand (the top-level command's did-you-mean).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

// The bundled example without rate noise (so the sources' shares and the cross terms make all of u²) and
// with two pairs of partly correlated inputs.
std::string correlated_example() {
  std::string text = read(kExample);
  for (const char* key : {"main_rate_noise = \"1 ppm/rtHz\"", "platform_rate_noise = \"1 ppm/rtHz\""}) {
    const auto at = text.find(key);
    EXPECT_NE(at, std::string::npos) << key;
    text.replace(at, std::string(key).size(), "");
  }
  return text + "\n[[correlations]]\nbetween = [\"ripple1_c1\", \"ripple3_c1\"]\nr = -0.5\n\n"
                "[[correlations]]\nbetween = [\"dthy4\", \"dthy5\"]\nr = 0.6\n";
}

TEST_F(Cli, TheAllocationShowsTheCrossTermsOfCorrelatedSources) {
  write("c.toml", correlated_example());
  const std::string args = "allocate c.toml --target K3=0.01 --target K2=1e-4 --verify-trials 0";
  const Result json = run(args + " --format json");
  ASSERT_EQ(json.code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  for (const char* k : {"K3", "K2"}) {
    // Σ_s share_s + the cross terms' share = 1 at the allocated tolerances (no rate noise); the sum of ~50
    // shares of order 1 to round-off, 1e-12.
    double sum = j["coefficients"][k]["correlation_share"].get<double>();
    EXPECT_LT(std::abs(sum), 1.0) << k;
    EXPECT_GT(std::abs(sum), 0.01) << k;  // the cancelling ripples make a visible part
    for (const auto& s : j["sources"]) sum += s["share"][k].get<double>();
    EXPECT_NEAR(sum, 1.0, 1e-12) << k;
  }
  const Result text = run(args);
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find(fmt::format("correlations between sources (their cross terms at the allocated "
                                      "tolerances): share K3 {:.1f} % share K2 {:.1f} %",
                                      100 * j["coefficients"]["K3"]["correlation_share"].get<double>(),
                                      100 * j["coefficients"]["K2"]["correlation_share"].get<double>())),
            std::string::npos)
      << text.out;
  // Without [[correlations]] or groups there are no cross terms, and no line.
  const Result plain = run("allocate --target K3=0.01 --verify-trials 0");
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_EQ(plain.out.find("correlations between sources"), std::string::npos) << plain.out;
}

TEST_F(Cli, HistoryWordsForAnIdAndAMistypedSubcommand) {
  expect_bad_input(run("history supersede abc --reason x --db h.sqlite"),
                   {"ID: 'abc' is not a calibration id; accepted: a whole number from 1, as `ccal history show "
                    "SERIAL` lists them"});
  expect_bad_input(run("history supersede 0 --reason x --db h.sqlite"), {"ID: '0' is not a calibration id"});
  expect_bad_input(run("history shwo S1"),
                   {"unknown command 'ccal history shwo'; did you mean 'ccal history show'? accepted: add, show"});
  expect_bad_input(run("history"), {"'ccal history …' needs a command; accepted: add, show"});
  expect_bad_input(run("history --db h.sqlite show S1"), {"needs a command"});
  EXPECT_EQ(run("history --help").code, 0);
  // The top-level command's did-you-mean, which the subcommand's shares: a swap of two letters is one step.
  expect_bad_input(run("bugdet"), {"unknown command 'bugdet'; did you mean 'budget'?"});
}

TEST_F(Cli, AManifestNamingTooFewRunsIsBlamedOnTheManifest) {
  // Found by the careless round: the count of a manifest's runs was refused as "--log: 1 logged run(s) …",
  // an option the user did not give.
  ASSERT_EQ(run("simulate " + quote(kLab) + " --logs-out L -o /dev/null").code, 0);
  write("L/manifest.toml", "[runs]\n5g = '5g.csv'\n");
  expect_bad_input(run("reduce " + quote(kLab) + " --logs L"),
                   {"L/manifest.toml: [runs]: 1 logged run(s) cannot determine 3 free terms"});
  const Result r = run("reduce " + quote(kLab) + " --logs L");
  EXPECT_EQ(r.err.find("--log"), std::string::npos) << r.err;
}

// An option given twice is said so, in the program's words (the parser's read "At Most 1 required but received
// 2"), for a path as for a number.
TEST_F(Cli, AnOptionGivenTwiceIsSaidSo) {
  expect_bad_input(run("reduce " + quote(kLab) + " --log 5g=a.csv --log-layout a.toml --log-layout b.toml"),
                   {"--log-layout: given 2 times; accepted: once (the last of several is not taken silently)"});
  expect_bad_input(run("montecarlo --trials 300 --trials 400"), {"--trials: given 2 times; accepted: once"});
  const Result r = run("budget -o a.txt -o b.txt");
  EXPECT_EQ(r.err.find("At Most"), std::string::npos) << r.err;
}

}  // namespace
