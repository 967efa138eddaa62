// `ccal budget` end to end: the bundled example's budget in each format, its consistency with the library,
// and bad input.
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace ccal::test {
namespace {

using Budget = Cli;

TEST_F(Budget, DefaultRunsTheBundledExample) {
  const Result r = run("budget");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("52 sources"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("combined standard uncertainty"), std::string::npos);
  EXPECT_NE(r.out.find("K3 [deg/s/g^3]: u = "), std::string::npos);
  EXPECT_NE(r.out.find("u(x_i)"), std::string::npos);
  // The two largest contributors to K3 are the rate ripple of the main axis and of the platform (model.md
  // §2.3: the heading wobble of a speed-controlled platform), shown in ppm as the configuration writes them.
  const auto table = r.out.find("K3 [deg/s/g^3]: u = ");
  ASSERT_NE(table, std::string::npos);
  const auto first = r.out.find("\n  ripple", table);
  ASSERT_NE(first, std::string::npos) << r.out.substr(table);
  EXPECT_NE(r.out.substr(first, 100).find("10 ppm"), std::string::npos) << r.out.substr(first, 100);
  EXPECT_NE(r.out.find("  main_rate_noise "), std::string::npos);
  // --wide: every source, the compensation choices and the exact-vs-paper flags.
  const Result w = run("budget --wide");
  ASSERT_EQ(w.code, 0) << w.err;
  EXPECT_NE(w.out.find("coriolis left out"), std::string::npos);
  EXPECT_NE(w.out.find("no paper rule"), std::string::npos);
  EXPECT_NE(w.out.find("  platform_rate_noise "), std::string::npos);
}

TEST_F(Budget, DeclaredEncodersAreSaidToReplaceTheirInputsTolerances) {
  // Before a test the budget keeps every tolerance, and says which inputs a test with the lab's declared
  // encoders measures; the bundled example declares none and says nothing of them.
  const Result lab = run("budget " + kLab);
  ASSERT_EQ(lab.code, 0) << lab.err;
  EXPECT_NE(lab.out.find("A test with the declared encoders"), std::string::npos) << lab.out;
  for (const std::string id : {"domega,", "dOmega,", "ripple1_c1,", "ripple3_s1:"})
    EXPECT_NE(lab.out.find(id), std::string::npos) << id << "\n" << lab.out;
  const Result bundled = run("budget");
  ASSERT_EQ(bundled.code, 0) << bundled.err;
  EXPECT_EQ(bundled.out.find("declared encoders"), std::string::npos) << bundled.out;
}

TEST_F(Budget, JsonCarriesUnitsAndMatchesTheText) {
  const Result r = run("budget --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["mode"], "exact");
  ASSERT_EQ(j["coefficients"].size(), 3u);
  EXPECT_EQ(j["coefficients"][2]["id"], "K3");
  EXPECT_EQ(j["coefficients"][2]["unit"], "deg/s/g^3");
  ASSERT_EQ(j["sources"].size(), 52u);
  // Root-sum-square of the per-source effects and the rate noise's u equals the total (no correlation groups
  // in the example): relative 1e-12 (sums of 54 squares).
  double sum = 0;
  for (const auto& s : j["sources"]) sum += std::pow(s["effect"]["K3"].get<double>(), 2);
  ASSERT_EQ(j["rate_noise"].size(), 2u);
  for (const auto& n : j["rate_noise"]) sum += std::pow(n["u"]["K3"].get<double>(), 2);
  const double total = j["coefficients"][2]["standard_uncertainty"];
  EXPECT_NEAR(std::sqrt(sum), total, 1e-12 * total);
  // U = k u at the default p = 95 %: k = Φ⁻¹(0.975) of the normal LPU total, and the JSON says so.
  EXPECT_NEAR(j["coefficients"][2]["expanded_uncertainty"].get<double>(), 1.959963984540054 * total,
              1e-12 * total);
  EXPECT_EQ(j["coverage_probability"], 0.95);
  EXPECT_EQ(j["coverage_method"], "normal");
  EXPECT_EQ(j["sources"][0]["id"], "ripple1_c1");  // ranked first: a rate ripple, dimensionless
  EXPECT_EQ(j["sources"][0]["unit_si"], "1");
  for (const auto& s : j["sources"])
    if (s["id"] == "dthx1t") {
      EXPECT_EQ(s["unit_si"], "rad");
    }
  EXPECT_TRUE(j["sources"][0].contains("exact_paper_disagree"));
  EXPECT_EQ(j["compensation_choices"].size(), 2u);
}

TEST_F(Budget, PaperModeReproducesTable4ForTheAzimuthError) {
  // model.md §5.1: Δθz5 = 1e-5 rad → ΔK3 = +9.1287e-6 °/s/g³ in paper mode (normal tolerance 1e-5 → the 1σ
  // effect is that number): 5 digits, relative 2e-4.
  const Result r = run("budget --mode paper --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  bool found = false;
  for (const auto& s : j["sources"])
    if (s["id"] == "dthz5") {
      found = true;
      EXPECT_NEAR(s["effect"]["K3"].get<double>(), 9.1287e-6, 2e-4 * 9.1287e-6);
    }
  EXPECT_TRUE(found);
}

TEST_F(Budget, CsvHasOneRowPerSource) {
  const Result r = run("budget --format csv");
  ASSERT_EQ(r.code, 0) << r.err;
  // The header, 52 tolerances, the two drives' rate noise, u, U and the round-off floor.
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 58);
  EXPECT_TRUE(r.out.starts_with("rank,source,group,distribution,bound_si,unit_si,standard_uncertainty_si"));
}

TEST_F(Budget, WritesTheFileAtomically) {
  ASSERT_EQ(run("budget -o budget.txt").code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "budget.txt"));
  const Result bad = run("budget --coverage-factor -1 -o bad.txt");
  EXPECT_EQ(bad.code, 2);
  EXPECT_FALSE(fs::exists(dir_ / "bad.txt"));
}

TEST_F(Budget, BadInputIsDiagnosed) {
  const std::string text = read(kExample);
  const int line = line_of(text, "dthz5 = \"1e-5 rad\"");
  ASSERT_GT(line, 0);
  const std::string cfg = write("bad.toml", example_with_line(line, "dthz5 = \"1e-5 mm\""));
  expect_bad_input(run("budget " + cfg), {"bad.toml:" + std::to_string(line), "dthz5", "angle"});
  expect_bad_input(run("budget --mode sideways"), {"--mode"});
  expect_bad_input(run("budget --derivatives numerical"), {"--derivatives"});
  expect_bad_input(run("budget --coverage-factor 0"), {"--coverage-factor"});
  const std::string empty =
      write("empty.toml", example_with_line(line_of(text, "[tolerances]"), "[tolerances_x]"));
  EXPECT_EQ(run("budget " + empty).code, 2);
}

}  // namespace
}  // namespace ccal::test

namespace ccal::test {
namespace {

TEST_F(Budget, BothDerivativeMethodsGiveTheSameTable) {
  // Linearised (default) and automatic differentiation: the same effects to 1e-9 of each coefficient's total
  // (the JSON prints 17 digits; the methods differ by round-off and quadrature exactness only).
  const Result a = run("budget --format json");
  const Result b = run("budget --derivatives automatic --format json");
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  const auto ja = nlohmann::json::parse(a.out), jb = nlohmann::json::parse(b.out);
  EXPECT_EQ(ja["derivatives"], "linearised");
  EXPECT_EQ(jb["derivatives"], "automatic");
  for (const char* k : {"K0", "K2", "K3"}) {
    double total = 0;
    for (const auto& c : ja["coefficients"])
      if (c["id"] == k) total = c["standard_uncertainty"];
    for (const auto& sa : ja["sources"]) {
      for (const auto& sb : jb["sources"]) {
        if (sa["id"] == sb["id"]) {
          EXPECT_NEAR(sa["effect"][k].get<double>(), sb["effect"][k].get<double>(), 1e-9 * total)
              << sa["id"] << " " << k;
        }
      }
    }
  }
}

// A test of two instruments (examples/two_instruments.toml) through the program: the JSON holds each instrument's
// budget as `ccal budget` of it alone would (checked field by field in tests/verbs/budget_instruments_test.cpp)
// and the covariance, whose correlation matrix is symmetric with a unit diagonal (to 1e-15: a quotient of two
// products of the same doubles); the text a section per instrument and the correlation table; the CSV a leading
// instrument column.
TEST_F(Budget, ATestOfTwoInstrumentsGivesEachBudgetAndTheirCorrelation) {
  const std::string two = CCAL_SOURCE_DIR + "/examples/two_instruments.toml";
  const Result j = run("budget " + two + " --format json");
  ASSERT_EQ(j.code, 0) << j.err;
  const auto doc = nlohmann::json::parse(j.out);
  ASSERT_EQ(doc["instruments"].size(), 2u);
  EXPECT_EQ(doc["instruments"][1]["id"], "B");
  EXPECT_EQ(doc["instruments"][1]["coefficients"][2]["id"], "K3");
  const auto& rho = doc["covariance"]["lpu_correlation"];
  ASSERT_EQ(rho.size(), 6u);
  EXPECT_EQ(doc["covariance"]["coefficients"][3], "B K0");
  for (std::size_t a = 0; a < 6; ++a) {
    EXPECT_NEAR(rho[a][a].get<double>(), 1.0, 1e-15);
    for (std::size_t b = 0; b < 6; ++b) EXPECT_NEAR(rho[a][b].get<double>(), rho[b][a].get<double>(), 1e-15);
  }
  const Result t = run("budget " + two);
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("ccal budget: a test of 2 instruments"), std::string::npos) << t.out.substr(0, 200);
  EXPECT_NE(t.out.find("=== instrument B ==="), std::string::npos);
  EXPECT_NE(t.out.find("correlation of the instruments' coefficients"), std::string::npos);
  const Result c = run("budget " + two + " --format csv");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_EQ(c.out.rfind("instrument,rank,source,", 0), 0u);
}

}  // namespace
}  // namespace ccal::test
