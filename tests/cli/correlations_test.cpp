// [[correlations]] through the program: `ccal budget` takes them (the JSON carries the input correlation
// matrix and the cross terms' share of u²), the Monte Carlo and the statement's check draw them, the
// allocation meets its targets with them; a pair the copula cannot draw is refused where it is.
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

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
  // The CSV: the matrix as r_<id> columns, each source's row of R in its line, and the cross terms' share.
  const Result csv = run("budget " + config + " --format csv");
  ASSERT_EQ(csv.code, 0) << csv.err;
  const auto cells = [](const std::string& line) {
    std::vector<std::string> out(1);
    bool quoted = false;
    for (const char c : line) {
      if (c == '"') quoted = !quoted;
      if (c == ',' && !quoted) {
        out.emplace_back();
      } else {
        out.back() += c;
      }
    }
    return out;
  };
  std::vector<std::vector<std::string>> rows;
  for (std::size_t at = 0, end; (end = csv.out.find('\n', at)) != std::string::npos; at = end + 1)
    rows.push_back(cells(csv.out.substr(at, end - at)));
  const auto column = [&](const std::string& name) {
    return std::size_t(std::find(rows[0].begin(), rows[0].end(), name) - rows[0].begin());
  };
  const auto row = [&](const std::string& source) {
    for (const auto& r : rows)
      if (r.size() > 1 && r[1] == source) return r;
    return std::vector<std::string>{};
  };
  for (const auto& r : rows) ASSERT_EQ(r.size(), rows[0].size());
  EXPECT_EQ(row("dthy4").at(column("r_dthy5")), "0.59999999999999998");
  EXPECT_EQ(row("ripple3_c1").at(column("r_ripple1_c1")), "-0.5");
  EXPECT_EQ(row("dthy4").at(column("r_dthy4")), "1");
  EXPECT_LT(std::stod(row("correlations_between_sources").at(column("share_K2"))), -0.9);
  const Result text = run("budget " + config);
  EXPECT_NE(text.out.find("correlations between sources -98.9 %"), std::string::npos) << text.out;
}

TEST_F(Cli, TheMonteCarloDrawsThemAndTheStatementChecksWithThem) {
  const std::string config = write("c.toml", read(CCAL_SOURCE_DIR + "/examples/wang_ren_2014.toml") + kPairs);
  // K2's two ripples with r = -0.5 take back 98.9 % of its u²: the Monte Carlo's spread must see it too. Its
  // u(K2) agrees with the LPU's within 5 standard errors, 5/sqrt(2M) = 2.5 % at M = 20000 (without the
  // correlation u(K2) would be 9.4 times larger).
  const Result mc = run("montecarlo " + config + " --trials 20000 --format json");
  ASSERT_EQ(mc.code, 0) << mc.err;
  const auto j = nlohmann::json::parse(mc.out);
  const auto& k2 = j["coefficients"]["K2"];
  const double lpu = k2["lpu"]["std_uncertainty"].get<double>();
  EXPECT_NEAR(k2["std_dev"].get<double>(), lpu, 0.025 * lpu);
  EXPECT_LT(j["input_correlation"]["share_of_variance"]["K2"].get<double>(), -0.9);
  EXPECT_NE(j["notes"].dump().find("Gaussian copula"), std::string::npos);
  // The allocation: its rows with the cross terms (a barrier method in the scales), its Monte Carlo
  // verification through the copula; the target holds and the verification passes.
  const Result alloc = run("allocate " + config + " --target K3=0.03 --format json");
  ASSERT_EQ(alloc.code, 0) << alloc.err;
  const auto a = nlohmann::json::parse(alloc.out);
  EXPECT_EQ(a["solver"]["method"], "barrier (partly correlated sources)");
  EXPECT_TRUE(a["solver"]["converged"].get<bool>());
  EXPECT_NEAR(a["coefficients"]["K3"]["allocated_expanded"].get<double>(), 0.03, 1e-12);
  EXPECT_TRUE(a["verification"]["passed"].get<bool>());
  // The statement: its Monte Carlo check draws them as the Monte Carlo does.
  ASSERT_EQ(run("simulate " + config + " -o /dev/null --observations-out obs.csv").code, 0);
  const Result st = run("identify obs.csv --statement --config " + config + " --format json");
  ASSERT_EQ(st.code, 0) << st.err;
  // A pair the Monte Carlo cannot draw with its inputs' distributions: refused where it is, with what would
  // do.
  const std::string far =
      write("far.toml", read(CCAL_SOURCE_DIR + "/examples/wang_ren_2014.toml") +
                            "\n[[correlations]]\nbetween = [\"dthy4\", \"ripple1_c1\"]\nr = 0.999\n");
  expect_bad_input(run("montecarlo " + far + " --trials 100"),
                   {"far.toml: [[correlations]] between = [\"dthy4\", \"ripple1_c1\"], r = 0.999: no joint "
                    "distribution of a",
                    "accepted: |r| ≤ 0.9484"});
  // A bad pair through the program: its place, exit code 2, nothing else.
  const std::string bad =
      write("bad.toml", read(CCAL_SOURCE_DIR + "/examples/wang_ren_2014.toml") +
                            "\n[[correlations]]\nbetween = [\"dthy4\", \"dthy5\"]\nr = 1.5\n");
  expect_bad_input(run("budget " + bad),
                   {"bad.toml:",
                    "correlations[1].r: 1.5 is not a correlation coefficient; accepted: a number from "
                    "-1 to 1"});
  const Result by_lpu =
      run("identify obs.csv --statement --statement-trials 0 --config " + config + " --format json");
  ASSERT_EQ(by_lpu.code, 0) << by_lpu.err;
}

}  // namespace
