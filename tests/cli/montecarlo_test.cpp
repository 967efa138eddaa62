// End-to-end tests of `ccal montecarlo`: a small run of the bundled example in every format, determinism of a
// seed across thread counts, and the rejection of bad options with exit code 2.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "ccal/io/config_file.hpp"
#include "cli_support.hpp"
#include "independent_lpu.hpp"

namespace ccal::test {
namespace {

using MonteCarloCli = Cli;

TEST_F(MonteCarloCli, SmallRunOfTheBundledExample) {
  const Result r = run("montecarlo --trials 400");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;  // no progress bar: standard error is not a terminal here
  for (const char* s :
       {"K0", "K2", "K3", "deg/s/g^3", "symmetric 95 % interval", "shortest 95 % interval", "LPU u_c",
        "validated", "correlation", "M = 400 trials", "seed 1", "Notes:", "JCGM 101"})
    EXPECT_NE(r.out.find(s), std::string::npos) << s << "\n" << r.out;

  // The bundled example without the drives' rate noise (its Type A part has no independent reference here;
  // tests/uncertainty/rate_noise_test.cpp checks it): the tolerances only.
  std::string text = read(kExample), kept;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (!line.starts_with("main_rate_noise") && !line.starts_with("platform_rate_noise")) kept += line + "\n";
  const std::string quiet = write("quiet.toml", kept);
  const Result j = run("montecarlo " + quiet + " --trials 20000 --format json");
  ASSERT_EQ(j.code, 0) << j.err;
  const nlohmann::json o = nlohmann::json::parse(j.out);
  EXPECT_EQ(o.at("command"), "montecarlo");
  EXPECT_EQ(o.at("trials"), 20000);
  // The reference u_c of the bundled example without the program's code paths: central differences of the
  // re-identified pipeline, σ from bound and distribution, groups by hand (independent_lpu.hpp), in °/s/gⁿ.
  const ccal::Config cfg = ccal::bundled_example();
  const Eigen::MatrixXd cov = ccal::test::independent_covariance(cfg, cfg.tolerances);
  EXPECT_EQ(o.at("seed"), 1);
  EXPECT_EQ(o.at("adaptive"), false);
  EXPECT_NEAR(o.at("coverage_factor").get<double>(), 1.959964, 1e-6);
  EXPECT_GT(o.at("wall_time_s").get<double>(), 0.0);
  EXPECT_GT(o.at("trials_per_s").get<double>(), 0.0);
  ASSERT_EQ(o.at("terms").size(), 3u);
  const char* ids[] = {"K0", "K2", "K3"};
  for (int k = 0; k < 3; ++k) {
    const char* id = ids[k];
    SCOPED_TRACE(id);
    const auto& c = o.at("coefficients").at(id);
    const double sd = c.at("std_dev").get<double>(), lpu = c.at("lpu").at("std_uncertainty").get<double>();
    const double u = std::sqrt(cov(k, k)) * 180 / std::numbers::pi;
    // The program's LPU against the reference: the central differences' accuracy, 1e-6 relative.
    EXPECT_NEAR(lpu, u, 1e-6 * u);
    // The LPU is nearly exact for ~1e-5 errors; the sample standard deviation of M = 20 000 values has a
    // relative standard error of about 1/√(2M) = 0.5 % for a normal output (less for the arcsine-dominated
    // ones, whose kurtosis is below 3): 5σ, 2.5 %.
    EXPECT_NEAR(sd / u, 1.0, 5 / std::sqrt(2 * 20000.0));
    const auto& sym = c.at("symmetric_interval");
    const auto& shortest = c.at("shortest_interval");
    EXPECT_LT(sym[0].get<double>(), c.at("mean").get<double>());
    EXPECT_GT(sym[1].get<double>(), c.at("mean").get<double>());
    EXPECT_LE(shortest[1].get<double>() - shortest[0].get<double>(),
              sym[1].get<double>() - sym[0].get<double>());
    EXPECT_NEAR(c.at("lpu").at("expanded_uncertainty").get<double>(), 1.959964 * lpu, 1e-6 * lpu);
    EXPECT_EQ(c.at("estimate").get<double>(), 0.0);  // the example's [errors] are zero
  }
  EXPECT_EQ(o.at("coefficients").at("K3").at("unit"), "deg/s/g^3");
  ASSERT_EQ(o.at("correlation").size(), 3u);
  EXPECT_DOUBLE_EQ(o["correlation"][1][1].get<double>(), 1.0);
  EXPECT_NEAR(o["covariance"][2][2].get<double>(),
              std::pow(o["coefficients"]["K3"]["std_dev"].get<double>(), 2),
              1e-12 * o["covariance"][2][2].get<double>());
  EXPECT_FALSE(o.at("notes").empty());

  const Result c = run("montecarlo --trials 400 --format csv -o mc.csv");
  ASSERT_EQ(c.code, 0) << c.err;
  const std::string csv = read(dir_ / "mc.csv");
  EXPECT_TRUE(csv.starts_with("coefficient,unit,mean,std_dev,")) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4) << csv;
}

TEST_F(MonteCarloCli, SameSeedSameResultsForAnyThreadCount) {
  // Everything but the timing (and the thread count itself, and the note that states both) is identical.
  auto strip = [](nlohmann::json j) {
    j.erase("wall_time_s");
    j.erase("trials_per_s");
    j.erase("threads");
    j["notes"].erase(0);
    return j;
  };
  const Result one = run("montecarlo --trials 400 --seed 7 --threads 1 --format json");
  const Result two = run("montecarlo --trials 400 --seed 7 --threads 2 --format json");
  ASSERT_EQ(one.code, 0) << one.err;
  ASSERT_EQ(two.code, 0) << two.err;
  const nlohmann::json a = nlohmann::json::parse(one.out), b = nlohmann::json::parse(two.out);
  EXPECT_EQ(a.at("threads"), 1);
  EXPECT_EQ(b.at("threads"), 2);
  EXPECT_EQ(strip(a), strip(b));
  // Another seed gives other draws.
  const Result other = run("montecarlo --trials 400 --seed 8 --threads 2 --format json");
  ASSERT_EQ(other.code, 0) << other.err;
  const nlohmann::json c = nlohmann::json::parse(other.out);
  EXPECT_NE(c["coefficients"]["K3"]["mean"], b["coefficients"]["K3"]["mean"]);
}

TEST_F(MonteCarloCli, PaperModeRuns) {
  const Result r = run("montecarlo --trials 200 --mode paper --format json --coverage-probability 0.9");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json o = nlohmann::json::parse(r.out);
  EXPECT_EQ(o.at("mode"), "paper");
  EXPECT_NEAR(o.at("coverage_factor").get<double>(), 1.644854, 1e-6);
}

TEST_F(MonteCarloCli, BadOptionsAreExitCodeTwo) {
  expect_bad_input(run("montecarlo --trials 1"), {"--trials"});
  expect_bad_input(run("montecarlo --trials -5"), {"--trials"});
  expect_bad_input(run("montecarlo --trials many"), {"--trials"});
  expect_bad_input(run("montecarlo --trials 2000000000"), {"--trials", "2 to 1000000000"});
  // Not a whole number: the option's range, not the type's 0 to 18446744073709551615.
  expect_bad_input(run("montecarlo --trials 2.5"),
                   {"--trials: 2.5 is not a whole number; accepted: a whole number from 2 to 1000000000"});
  expect_bad_input(run("montecarlo --trials nan"),
                   {"--trials: 'nan' is not a number; accepted: a whole number from 2 to 1000000000"});
  expect_bad_input(run("montecarlo --digits 2 --max-trials 1000"),
                   {"--max-trials: 1000 leaves fewer than the 2 stages"});
  expect_bad_input(run("montecarlo --threads -1"), {"--threads"});
  expect_bad_input(run("montecarlo --digits 7"), {"--digits", "0 (fixed M) or 1 to 6"});
  expect_bad_input(run("montecarlo --digits -1"), {"--digits"});
  expect_bad_input(run("montecarlo --coverage-probability 0"), {"--coverage-probability", "[0.5, 1)"});
  // Below ½ refused too: 1e-300 took q = 0 of the sorted values, a one-point "interval" said validated.
  expect_bad_input(run("montecarlo --coverage-probability 1e-300"), {"--coverage-probability", "[0.5, 1)"});
  expect_bad_input(run("montecarlo --coverage-probability 0.49"), {"--coverage-probability", "[0.5, 1)"});
  expect_bad_input(run("montecarlo --coverage-probability 1"), {"--coverage-probability"});
  expect_bad_input(run("montecarlo --coverage-probability 1.5"), {"--coverage-probability"});
  expect_bad_input(run("montecarlo --mode fast"), {"--mode"});
  expect_bad_input(run("montecarlo --format xml"), {"--format"});
  expect_bad_input(run("montecarlo missing.toml"), {"missing.toml"});
  // Nothing is written on failure.
  expect_bad_input(run("montecarlo --trials 1 -o x.json"), {"--trials"});
  EXPECT_FALSE(fs::exists(dir_ / "x.json"));
}

TEST_F(MonteCarloCli, HelpHasExamples) {
  const Result h = run("montecarlo --help");
  EXPECT_EQ(h.code, 0);
  EXPECT_NE(h.out.find("Examples:"), std::string::npos) << h.out;
  EXPECT_NE(h.out.find("--digits"), std::string::npos);
}

}  // namespace
}  // namespace ccal::test
