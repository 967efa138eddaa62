// The calibration statement end to end: `ccal identify --statement --config CONFIG` and `ccal reduce --statement` (JCGM 100
// §7, docs/model.md §10.5), checked against the fit and the budget printed by the other verbs.
#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "ccal/core/sha256.hpp"
#include "cli_support.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

class Statement : public Cli {
 protected:
  // Logs of the first n runs of the bundled plan (5, 10, 15, … g): pulses of 1e-3 deg at K1 × g-level
  // deg/s, encoders at the planned rate of a 2.5 m arm, every 0.1 s over 120 s. Pure test data. Returns the
  // --log options.
  std::string write_logs(int n) const {
    std::string logs;
    for (int r = 0; r < n; ++r) {
      const double g_level = 5.0 * (r + 1), rate = std::sqrt(g_level * 9.8 / 2.5), T = 120;
      std::string csv = "time,pulses,theta1,gamma\n";
      for (int k = 0; k <= 1200; ++k) {
        const double t = T * k / 1200;
        csv += std::to_string(t) + "," + std::to_string(std::floor(505.2097 * g_level * t / 1e-3)) + "," +
               std::to_string(std::fmod(rate * t, 2 * std::numbers::pi)) + "," +
               std::to_string(std::fmod(8 * std::numbers::pi - rate * t, 2 * std::numbers::pi)) + "\n";
      }
      write("run" + std::to_string(r) + ".csv", csv);
      logs += " --log " + std::to_string(r + 1) + "=run" + std::to_string(r) + ".csv";
    }
    return logs + " --pulse-weight 1e-3";
  }
};

// Φ⁻¹(0.975) to 16 digits.
using ccal::test::kZ975;

TEST_F(Statement, ObservationsOfAnotherConfigurationAreRefusedNamingBothFingerprints) {
  // The observations file carries the fingerprint of what changes the numbers of the configuration it was
  // simulated with; a statement with another configuration's budget would be silently wrong. Before, it was
  // made with exit code 0.
  ASSERT_EQ(run("simulate --observations-out obs.csv -o /dev/null").code, 0);
  const std::string sha_bundled = "config_sha256=";
  std::ifstream in(dir_ / "obs.csv");
  std::string header;
  std::getline(in, header);
  const std::size_t at = header.find(sha_bundled);
  ASSERT_NE(at, std::string::npos) << header;
  const std::string fingerprint = header.substr(at + sha_bundled.size(), 64);
  ASSERT_EQ(run("identify obs.csv --statement --config " + kExample).code, 0);  // the same text: accepted
  // A comment and a [certificate] change the file, not its numbers: the observations stay valid.
  write("worded.toml", read(kExample) + "\n# a comment\n[certificate]\noperator = \"A. Engineer\"\n");
  ASSERT_EQ(run("identify obs.csv --statement --statement-trials 0 --config worded.toml").code, 0);
  // A tolerance changes them.
  std::string other = read(kExample);
  other.replace(other.find("dR_s = \"25 um\""), 14, "dR_s = \"26 um\"");
  write("other.toml", other);
  const Result r = run("identify obs.csv --statement --config other.toml");
  expect_bad_input(r, {"--config: obs.csv was made with another configuration than other.toml", fingerprint,
                       "(line 1)"});
  const Result report = run("report other.toml --observations obs.csv --trials 1000 -o page.html");
  expect_bad_input(report, {"--observations", fingerprint});
  EXPECT_FALSE(fs::exists(dir_ / "page.html"));
}

TEST_F(Statement, ObservationsWrittenWithTheTextsFingerprintAreStillAccepted) {
  // Files written before the fingerprint of the numbers hold the SHA-256 of the configuration's text: that
  // matches still; once the text changes, neither does, and the file is refused.
  ASSERT_EQ(run("simulate --observations-out obs.csv -o /dev/null").code, 0);
  std::string obs = read((dir_ / "obs.csv").string());
  const std::string key = "config_sha256=";
  const std::size_t at = obs.find(key);
  ASSERT_NE(at, std::string::npos);
  const std::string text_sha = sha256_hex(read(kExample));
  ASSERT_NE(obs.substr(at + key.size(), 64), text_sha);  // a new file holds the numbers' fingerprint
  obs.replace(at + key.size(), 64, text_sha);
  write("old.csv", obs);
  EXPECT_EQ(run("identify old.csv --statement --statement-trials 0 --config " + kExample).code, 0);
  write("commented.toml", read(kExample) + "\n# another text\n");
  expect_bad_input(run("identify old.csv --statement --statement-trials 0 --config commented.toml"),
                   {"--config: old.csv was made with another configuration than commented.toml", text_sha});
}

TEST_F(Statement, TheLabExamplesMethodsDoNotFlipWithTheTrials) {
  // The same logs of examples/lab.toml at 2·10⁴ and 10⁵ requested trials: each coefficient and run output is
  // stated by the same method. At a fixed M the 30 g run's output had the Student-t interval at 2·10⁴ (its
  // check within the sampling error) and the Monte Carlo's at 10⁵; the check now goes on until it can tell.
  ASSERT_EQ(run("simulate " + kLab + " --truth " + kLabTruth + " --logs-out logs -o /dev/null").code, 0);
  std::map<std::string, std::string> methods[2];
  const std::uint64_t requested[2] = {20000, 100000};
  for (int i = 0; i < 2; ++i) {
    const Result r = run(fmt::format("reduce {} --logs logs --statement --statement-trials {} --format json", kLab,
                                     requested[i]));
    ASSERT_EQ(r.code, 0) << r.err;
    const auto s = nlohmann::json::parse(r.out).at("statement");
    EXPECT_EQ(s["monte_carlo"]["requested_trials"], requested[i]);
    EXPECT_GE(s["monte_carlo"]["trials"].get<std::uint64_t>(), requested[i]);
    EXPECT_LE(s["monte_carlo"]["trials"].get<std::uint64_t>(), 10 * requested[i]);
    for (const auto& [id, c] : s["coefficients"].items()) methods[i][id] = c["interval_method"];
    for (const auto& o : s["modelled_output"]) methods[i][o["run"]] = o["interval_method"];
  }
  EXPECT_EQ(methods[0].size(), 9u);  // K0, K2, K3 and six runs
  EXPECT_EQ(methods[0], methods[1]);
}

TEST_F(Statement, AStatedCoverageFactorGivesUEqualToKTimesUcForEveryQuantity) {
  ASSERT_EQ(run("simulate --observations-out obs.csv -o /dev/null").code, 0);
  const Result r = run("identify obs.csv --statement --statement-trials 2000 --coverage-factor 2 --config " +
                       kExample + " --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto s = nlohmann::json::parse(r.out).at("statement");
  EXPECT_EQ(s["coverage_factor"], 2.0);
  // 2Φ(2) − 1 = 0.9544997361036416 (erf(√2)); to 1e-15, the last digits of a double near 1.
  EXPECT_NEAR(s["coverage_probability"].get<double>(), 0.9544997361036416, 1e-15);
  int quantities = 0;
  auto check = [&](const nlohmann::json& c) {
    ++quantities;
    EXPECT_EQ(c["interval_method"], "coverage_factor");
    EXPECT_EQ(c["coverage_factor"], 2.0);
    // U = k u_c exactly: one multiplication by 2 is exact in binary.
    const double uc = c["combined_standard_uncertainty"], y = c["corrected_estimate"];
    EXPECT_EQ(c["expanded_uncertainty"].get<double>(), 2 * uc);
    EXPECT_EQ(c["interval"][0].get<double>(), y - 2 * uc);
    EXPECT_EQ(c["interval"][1].get<double>(), y + 2 * uc);
    EXPECT_NEAR(c["stated_coverage_probability"]["normal"].get<double>(), 0.9544997361036416, 1e-15);
    EXPECT_FALSE(c["monte_carlo"].is_null());  // the check still runs and reports
  };
  for (const auto& [id, c] : s["coefficients"].items()) check(c);
  for (const auto& o : s["modelled_output"]) check(o);
  EXPECT_GE(quantities, 4);
  // With a coverage probability too: two coverages, refused naming both.
  expect_bad_input(run("identify obs.csv --statement --coverage-factor 2 --coverage-probability 0.99 --config " +
                       kExample),
                   {"--coverage-factor", "--coverage-probability", "two coverages"});
  expect_bad_input(run("identify obs.csv --statement --coverage-factor 0.5 --config " + kExample),
                   {"--coverage-factor"});
}

TEST_F(Statement, IdentifyWithTheBudgetOfItsConfiguration) {
  ASSERT_EQ(run("simulate --observations-out obs.csv -o /dev/null").code, 0);
  const Result fit = run("identify obs.csv --format json");
  // The Student-t statement as it is (the Monte Carlo check: TheMonteCarloCheckStatesTheIntervalItGives).
  const Result st = run("identify obs.csv --statement --statement-trials 0 --config " + kExample + " --format json");
  const Result budget = run("budget --format json");
  ASSERT_EQ(fit.code, 0) << fit.err;
  ASSERT_EQ(st.code, 0) << st.err;
  ASSERT_EQ(budget.code, 0) << budget.err;
  const auto jf = nlohmann::json::parse(fit.out), js = nlohmann::json::parse(st.out),
             jb = nlohmann::json::parse(budget.out);
  const auto& s = js.at("statement");
  EXPECT_EQ(s["mode"], "exact");
  EXPECT_EQ(s["known_errors"], 0);
  for (std::size_t k = 0; k < jb["coefficients"].size(); ++k) {
    const std::string id = jb["coefficients"][k]["id"];
    const auto& c = s["coefficients"][id];
    // Type A: the noise model, here the drives' rate noise alone (the instrument states none), propagated
    // through the fit with ν = ∞: the budget's rate-noise lines, u_A² = Σ u_noise² (relative 1e-9: H⁺ from the
    // observations file's 17-digit regressors rather than the budget's own).
    double noise = 0;
    for (const auto& n : jb["rate_noise"]) noise += std::pow(n["u"][id].get<double>(), 2);
    EXPECT_NEAR(c["type_a"]["u"].get<double>(), std::sqrt(noise), 1e-9 * std::sqrt(noise)) << id;
    EXPECT_TRUE(c["type_a"]["dof"].is_null());  // infinite
    EXPECT_EQ(c["estimate"], jf["coefficients"][id]["value"]);
    EXPECT_EQ(c["correction"], 0.0);  // no known errors
    // Type B: the budget's u without the drives' rate noise: u_B² = u² − Σ u_noise², relative 1e-9 (a
    // difference of sums of squares); nothing was measured (no logs), so every input is its tolerance.
    const double u = jb["coefficients"][k]["standard_uncertainty"];
    const double u_b = std::sqrt(u * u - noise);
    EXPECT_NEAR(c["type_b"]["u"].get<double>(), u_b, 1e-9 * u_b) << id;
    EXPECT_TRUE(c["type_b"]["dof"].is_null());  // infinite
    // So u_c is the budget's u: the statement of a test that measured nothing is the budget (1e-9).
    EXPECT_NEAR(c["combined_standard_uncertainty"].get<double>(), u, 1e-9 * u);
    EXPECT_TRUE(c["effective_dof"].is_null());
    const double u_c = u;
    // Every part with ν = ∞: k is the normal quantile.
    EXPECT_NEAR(c["coverage_factor"].get<double>(), kZ975, 1e-12);
    const double U = c["expanded_uncertainty"];
    EXPECT_NEAR(U, c["coverage_factor"].get<double>() * u_c, 1e-9 * U);
    EXPECT_NEAR(c["interval"][0].get<double>(), c["corrected_estimate"].get<double>() - U, 1e-12 * U + 1e-15);
  }
  EXPECT_TRUE(s["type_a"]["from_noise_model"]);
  EXPECT_FALSE(s["type_a"]["residual_check"]["excess"]);  // noise-free observations: nothing to charge
  ASSERT_FALSE(s["inputs"].empty());
  for (const auto& input : s["inputs"]) EXPECT_FALSE(input["measured"]) << input["id"];
  const Result text = run("identify obs.csv --statement --statement-trials 0 --config " + kExample);
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("Calibration statement (JCGM 100 §7)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("  K3 = ("), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("No Monte Carlo check of the intervals"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("Type A: the noise model"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("nothing more is charged"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("Type B inputs (u_i: signed effect c u in each coefficient's unit; 0 measured"),
            std::string::npos)
      << text.out;
  EXPECT_NE(text.out.find("  dthz5  "), std::string::npos) << text.out;
  EXPECT_TRUE(s["monte_carlo"].is_null());
}

TEST_F(Statement, TheMonteCarloCheckStatesTheIntervalItGives) {
  // On by default (here 2·10⁴ trials requested, which the check extends while a verdict is within its sampling
  // error, to at most 10 times that): every coefficient has its check; where the check refused the Student-t interval,
  // the JSON's interval is the Monte Carlo's symmetric one, U half its width, and the text's line gives the
  // ends (`K = value unit, p = 95 %: [low, high] (the Monte Carlo's interval, JCGM 101)`); the same seed on 1
  // and 2 threads gives the same file.
  ASSERT_EQ(run("simulate --observations-out obs.csv -o /dev/null").code, 0);
  const std::string command = "identify obs.csv --statement --statement-trials 20000 --config " + kExample;
  const Result one = run(command + " --threads 1 --format json");
  const Result two = run(command + " --threads 2 --format json");
  const Result text = run(command);
  ASSERT_EQ(one.code, 0) << one.err;
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_EQ(one.out, two.out);
  const auto s = nlohmann::json::parse(one.out).at("statement");
  EXPECT_EQ(s["monte_carlo"]["requested_trials"], 20000);
  const std::uint64_t trials = s["monte_carlo"]["trials"];
  EXPECT_GE(trials, 20000u);
  EXPECT_LE(trials, 200000u);
  EXPECT_EQ(s["monte_carlo"]["seed"], 1);
  int replaced = 0;
  for (const auto& [id, c] : s["coefficients"].items()) {
    const auto& m = c["monte_carlo"];
    ASSERT_FALSE(m.is_null()) << id;
    const bool mc = c["interval_method"] == "monte_carlo";
    EXPECT_EQ(mc, !m["validated"].get<bool>() && !m["explained_by_sampling"].get<bool>()) << id;
    const auto& r = c["rounded"];
    if (mc) {
      ++replaced;
      EXPECT_EQ(c["interval"], m["interval_symmetric"]) << id;
      EXPECT_DOUBLE_EQ(c["expanded_uncertainty"].get<double>(),
                       (c["interval"][1].get<double>() - c["interval"][0].get<double>()) / 2);
      const std::string line =
          fmt::format("  {} = {} {}, p = 95 %: [{}, {}] (the Monte Carlo's interval, JCGM 101)", id,
                      r["estimate"].get<std::string>(), c["unit"].get<std::string>(),
                      r["interval"][0].get<std::string>(), r["interval"][1].get<std::string>());
      EXPECT_NE(text.out.find(line), std::string::npos) << line << "\n" << text.out;
    } else {
      EXPECT_NE(text.out.find(fmt::format("  {} = ({} ± {}) ", id, r["estimate"].get<std::string>(),
                                          r["expanded_uncertainty"].get<std::string>())),
                std::string::npos)
          << id << "\n" << text.out;
    }
  }
  // The bundled example's tolerances are no normal sum: its K2 and K3 take the Monte Carlo's interval.
  EXPECT_GE(replaced, 1) << one.out;
  EXPECT_NE(text.out.find(fmt::format("Monte Carlo check (JCGM 101 §8; M = {}", trials)), std::string::npos)
      << text.out;
}

TEST_F(Statement, KnownErrorsAreCorrected) {
  // The example with two known errors, not compensated: simulate identifies shifted coefficients; the
  // statement's correction takes the shift off, so the corrected estimate is the instrument's value (the
  // [instrument.terms]) to round-off of the fit.
  std::string text = read(kExample);
  for (const std::string line : {"# dthz5 = \"2 arcsec\"", "# dx3_c1 = \"5 um\""})
    text.replace(text.find(line), 2, "");
  const std::string cfg = write("errors.toml", text);
  ASSERT_EQ(run("simulate " + cfg + " --observations-out obs.csv -o /dev/null").code, 0);
  const Result st = run("identify obs.csv --statement --config " + cfg + " --format json");
  ASSERT_EQ(st.code, 0) << st.err;
  const auto s = nlohmann::json::parse(st.out).at("statement");
  EXPECT_EQ(s["known_errors"], 2);
  EXPECT_FALSE(s["compensated"].get<bool>());
  // [instrument.terms] of the example, in deg/s/g^n; tolerance 1e-10 of the value (fit round-off).
  const std::map<std::string, double> truth{{"K0", 0.061973}, {"K2", 0.02}, {"K3", 0.003}};
  for (const auto& [id, value] : truth) {
    const auto& c = s["coefficients"][id];
    EXPECT_NE(c["correction"].get<double>(), 0.0) << id;
    EXPECT_NEAR(c["corrected_estimate"].get<double>(), value, 1e-10 * value) << id;
  }
}

TEST_F(Statement, IdentifyModeSetsTheBudgetsKinematics) {
  // `--mode paper`: Type B from the paper-mode budget (`ccal budget --mode paper`) without the rate noise,
  // as in exact mode above; relative 1e-9 (a difference of sums of squares).
  ASSERT_EQ(run("simulate --observations-out obs.csv -o /dev/null").code, 0);
  const Result st = run("identify obs.csv --statement --config " + kExample + " --mode paper --format json");
  const Result budget = run("budget --mode paper --format json");
  ASSERT_EQ(st.code, 0) << st.err;
  ASSERT_EQ(budget.code, 0) << budget.err;
  const auto s = nlohmann::json::parse(st.out).at("statement");
  const auto jb = nlohmann::json::parse(budget.out);
  EXPECT_EQ(s["mode"], "paper");
  for (const auto& b : jb["coefficients"]) {
    const std::string id = b["id"];
    double noise = 0;
    for (const auto& n : jb["rate_noise"]) noise += std::pow(n["u"][id].get<double>(), 2);
    const double u = b["standard_uncertainty"], u_b = std::sqrt(u * u - noise);
    EXPECT_NEAR(s["coefficients"][id]["type_b"]["u"].get<double>(), u_b, 1e-9 * u_b) << id;
  }
  expect_bad_input(run("identify obs.csv --statement --config " + kExample + " --mode first"), {"--mode", "first"});
}

TEST_F(Statement, ReduceWithOneDegreeOfFreedom) {
  // Four logged runs for three free terms. These logs hold only K1's share of the output, sampled as no run of
  // the bundled set-up would give it, so their residuals are far beyond what its noise model (the drives' rate
  // noise) predicts: the excess is charged as Type A with the fit's n − p = 1 degree of freedom, ν_A follows by
  // Welch–Satterthwaite (at least 1), and k lies between the normal quantile and t_{0.975}(1) = 12.706.
  const Result r = run("reduce" + write_logs(4) + " --statement --coverage-probability 0.95 --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& s = j.at("statement");
  EXPECT_EQ(s["coverage_probability"], 0.95);
  EXPECT_TRUE(s["type_a"]["from_noise_model"]);
  EXPECT_EQ(s["type_a"]["dof"], 1);
  EXPECT_TRUE(s["type_a"]["residual_check"]["excess"]);
  EXPECT_LT(s["type_a"]["residual_check"]["p_value"].get<double>(), 0.01);
  for (const std::string id : {"K0", "K2", "K3"}) {
    const auto& c = s["coefficients"][id];
    ASSERT_TRUE(c["type_a"]["dof"].is_number()) << id;
    EXPECT_GE(c["type_a"]["dof"].get<double>(), 1.0 - 1e-12) << id;
    const double u_a = c["type_a"]["u"], u_b = c["type_b"]["u"], u_c = std::hypot(u_a, u_b);
    EXPECT_NEAR(c["combined_standard_uncertainty"].get<double>(), u_c, 1e-12 * u_c);
    EXPECT_GE(c["coverage_factor"].get<double>(), kZ975 - 1e-12);
    EXPECT_LE(c["coverage_factor"].get<double>(), 12.7062 + 5e-5);
  }
  const Result text = run("reduce" + write_logs(4) + " --statement");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("Calibration statement"), std::string::npos);
}

TEST_F(Statement, TheStatementAloneAsJsonAndCsvWithTheRoundedFiguresOfTheText) {
  // --statement-out: the JSON file is the report's "statement" object; the CSV's rounded figures are the text's
  // "K = (value ± U)" line and the JSON's, character for character; its covariance columns are the JSON's
  // combined covariance (shortest round-trip digits: equal doubles).
  const std::string logs = write_logs(5);
  const Result json = run("reduce" + logs + " --statement --statement-out st.json --format json");
  ASSERT_EQ(json.code, 0) << json.err;
  const Result text = run("reduce" + logs + " --statement --statement-out st.csv");
  ASSERT_EQ(text.code, 0) << text.err;
  const auto report = nlohmann::json::parse(json.out);
  const auto alone = nlohmann::json::parse(read(dir_ / "st.json"));
  EXPECT_EQ(alone, report["statement"]);
  std::istringstream csv(read(dir_ / "st.csv"));
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("coefficient,unit,corrected_estimate,expanded_uncertainty,coverage_factor,", 0), 0u);
  EXPECT_NE(header.find(",rounded_estimate,rounded_expanded_uncertainty,rounded_low,rounded_high,interval_method,"
                        "mc_trials,mc_standard_uncertainty,mc_low,mc_high,mc_d_low,mc_d_high,mc_delta,mc_validated,"
                        "cov_K0,cov_K2,cov_K3"),
            std::string::npos)
      << header;
  const auto& order = alone["covariance"]["order"];
  ASSERT_EQ(order.size(), 3u);
  for (std::size_t i = 0; i < order.size(); ++i) {
    ASSERT_TRUE(std::getline(csv, line));
    std::vector<std::string> cells;
    std::istringstream cells_in(line);
    for (std::string cell; std::getline(cells_in, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 30u) << line;
    const std::string id = order[i];
    EXPECT_EQ(cells[0], id);
    const auto& rounded = alone["coefficients"][id]["rounded"];
    // The rounded figures as text, quoted, so that their trailing zeros are kept.
    EXPECT_EQ(cells[14], fmt::format("\"{}\"", rounded["estimate"].get<std::string>()));
    EXPECT_EQ(cells[15], fmt::format("\"{}\"", rounded["expanded_uncertainty"].get<std::string>()));
    const bool mc = alone["coefficients"][id]["interval_method"] == "monte_carlo";
    EXPECT_EQ(cells[18], mc ? "monte_carlo" : "student_t");
    const std::string expected_line =
        mc ? fmt::format("{} = {} ", id, rounded["estimate"].get<std::string>())
           : fmt::format("{} = ({} ± {}) ", id, rounded["estimate"].get<std::string>(),
                         rounded["expanded_uncertainty"].get<std::string>());
    EXPECT_NE(text.out.find(expected_line), std::string::npos) << expected_line << "\n" << text.out;
    EXPECT_EQ(std::stod(cells[21]), alone["coefficients"][id]["monte_carlo"]["interval_symmetric"][0].get<double>());
    for (std::size_t k = 0; k < 3; ++k)
      EXPECT_EQ(std::stod(cells[27 + k]), alone["covariance"]["combined"][i][k].get<double>()) << id << k;
  }
}

TEST_F(Statement, TheStatementFileIsRefusedWithoutTheStatementOrAKnownExtension) {
  const std::string logs = write_logs(4);
  expect_bad_input(run("reduce" + logs + " --statement-out st.json"), {"--statement-out", "without --statement"});
  expect_bad_input(run("reduce" + logs + " --statement --statement-out st.txt"), {"--statement-out", ".json or .csv"});
  expect_bad_input(run("reduce" + logs + " --statement --statement-out st.csv -o st.csv"),
                   {"--statement-out", "also the -o file"});
  EXPECT_FALSE(fs::exists(dir_ / "st.json"));
  EXPECT_FALSE(fs::exists(dir_ / "st.txt"));
  EXPECT_FALSE(fs::exists(dir_ / "st.csv"));
}

TEST_F(Statement, BadUsesAreExitCodeTwo) {
  ASSERT_EQ(run("simulate --observations-out obs.csv -o /dev/null").code, 0);
  expect_bad_input(run("identify obs.csv --statement --config " + kExample + " --coverage-probability 1.5"),
                   {"--coverage-probability"});
  expect_bad_input(run("identify obs.csv --statement --config missing.toml"), {"missing.toml"});
  // A fit of other free terms than the configuration's: its budget does not apply.
  expect_bad_input(run("identify obs.csv --terms K0,K2 --fix K1=505.2097,K3=0.003 --statement --config " + kExample),
                   {"--statement", "K0, K2", "K0, K2, K3"});
  // reduce with as many logs as free terms: no degrees of freedom, no Type A.
  const std::string logs = write_logs(3);
  expect_bad_input(run("reduce" + logs + " --statement"), {"--statement", "degrees of freedom"});
}

TEST_F(Statement, RetiredSpellingsAreRefusedWithTheirSuccessors) {
  // --budget took a file in identify and was a flag in reduce; --input/--weight/--output named identify's
  // columns before -o/--output named the file written. Each is refused saying what replaced it, and nothing
  // is written.
  ASSERT_EQ(run("simulate --observations-out obs.csv -o /dev/null").code, 0);
  expect_bad_input(run("identify obs.csv --budget " + kExample), {"--budget", "--statement --config " + kExample});
  expect_bad_input(run("reduce" + write_logs(4) + " --budget"), {"--budget", "--statement"});
  expect_bad_input(run("identify obs.csv --input a_i"), {"--input", "--input-column"});
  expect_bad_input(run("identify obs.csv --weight s"), {"--weight", "--weight-column"});
  expect_bad_input(run("identify obs.csv --output output"),
                   {"-o/--output: 'output' is a column of obs.csv", "--output-column output"});
  EXPECT_FALSE(fs::exists(dir_ / "output"));
  // The statement and its configuration go together.
  expect_bad_input(run("identify obs.csv --statement"), {"--statement: needs the configuration", "--config"});
  expect_bad_input(run("identify obs.csv --config " + kExample), {"--config", "only for the calibration statement",
                                                                  "--statement"});
}

TEST_F(Statement, IdentifyWritesCsvOfTheCoefficientsAndTheStatement) {
  // One row per free term with the JSON's numbers to 17 digits: the CSV reads back to the same doubles.
  ASSERT_EQ(run("simulate --observations-out obs.csv -o /dev/null").code, 0);
  const Result csv = run("identify obs.csv --statement --config " + kExample + " --format csv -o st.csv");
  ASSERT_EQ(csv.code, 0) << csv.err;
  const Result json = run("identify obs.csv --statement --config " + kExample + " --format json");
  ASSERT_EQ(json.code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  std::ifstream in(dir_ / "st.csv");
  std::string header, line;
  std::getline(in, header);
  EXPECT_EQ(header, "coefficient,unit,value,std_error,correction,corrected,u_a,dof_a,u_b,u_c,nu_eff,"
                    "coverage_probability,k,expanded,low,high");
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    std::vector<std::string> cells;
    for (std::size_t at = 0;;) {
      const std::size_t comma = line.find(',', at);
      cells.push_back(line.substr(at, comma - at));
      if (comma == std::string::npos) break;
      at = comma + 1;
    }
    ASSERT_EQ(cells.size(), 16u) << line;
    const std::string& id = cells[0];
    const auto& c = j["statement"]["coefficients"][id];
    EXPECT_EQ(std::stod(cells[2]), j["coefficients"][id]["value"].get<double>()) << id;
    EXPECT_EQ(std::stod(cells[13]), c["expanded_uncertainty"].get<double>()) << id;
    EXPECT_EQ(std::stod(cells[12]), c["coverage_factor"].get<double>()) << id;
  }
  EXPECT_EQ(rows, 3);
}

}  // namespace
}  // namespace ccal::test
