// What calibrations on one machine share, through the program: the lab example's machine, its errors drawn
// once from the tolerances and kept, calibrated three years running while the instrument's K2 drifts by 2e-4
// deg/s/g² a year (the noise drawn anew each year); each year reduced with the lab's one configuration, so
// that the three statements name one set-up. E_n of two calibrations equals a hand computation with the
// covariance they share (from the statements' effects), and the drift line, with the shared Type B taken out,
// has u(b) below the machine's u_B(K2) and finds the drift within its expanded uncertainty, significantly.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

constexpr double kSharedDrift = 2e-4;  // deg/s/g² per year

// The machine's errors of one draw from examples/lab.toml's tolerances, as a truth file: each SI value with
// its SI unit (a ripple and the time base are ratios, written bare). K1 is left out: the instrument's scale
// factor from another calibration, not the machine's.
std::string drawn_truth(const nlohmann::json& drawn) {
  std::string toml = "[errors]\n";
  for (const auto& [id, v] : drawn.items()) {
    const std::string si = id.starts_with("dth") || id.starts_with("encoder") ? "rad"
                           : id == "arm_stretch"                              ? "m/(rad/s)^2"
                           : id == "domega" || id == "dOmega"                 ? "rad/s"
                           : id == "g"                                        ? "m/s^2"
                           : id.starts_with("ripple") || id == "time_base"    ? ""
                                                                              : "m";
    if (id == "K1") continue;
    toml += si.empty() ? fmt::format("{} = {:.17g}\n", id, v.get<double>())
                       : fmt::format("{} = \"{:.17g} {}\"\n", id, v.get<double>(), si);
  }
  return toml;
}

// R_αβ between two inputs of a statement: 1 for one input or one group, its input_correlations' ρ, else 0.
double rho(const nlohmann::json& st, const nlohmann::json& a, const nlohmann::json& b) {
  if (a["id"] == b["id"]) return 1;
  if (!a["group"].get<std::string>().empty() && a["group"] == b["group"]) return 1;
  for (const auto& c : st["input_correlations"])
    if ((c[0] == a["id"] && c[1] == b["id"]) || (c[0] == b["id"] && c[1] == a["id"]))
      return c[2].get<double>();
  return 0;
}

TEST_F(Cli, CalibrationsOnOneMachineShareItsTypeBAndShowASmallDrift) {
  // One draw of the machine's errors (the lab's tolerances, seed 7), kept for the three years.
  const Result drawn = run("simulate " + quote(kLab) + " --draw-truth --seed 7 --format json -o drawn.json");
  ASSERT_EQ(drawn.code, 0) << drawn.err;
  const auto draw = nlohmann::json::parse(read(dir_ / "drawn.json"));
  ASSERT_TRUE(draw.contains("drawn_errors_si")) << draw.dump().substr(0, 400);
  const std::string truth = write("machine.toml", drawn_truth(draw["drawn_errors_si"]));
  std::vector<nlohmann::json> statements;
  for (int year = 0; year < 3; ++year) {
    // The instrument of that year (K2 moved), on the same machine, with the noise of another seed.
    std::string text = read(kLab);
    const std::string k2 = "K2 = \"0.02 deg/s/g^2\"";
    ASSERT_NE(text.find(k2), std::string::npos);
    text.replace(text.find(k2), k2.size(),
                 fmt::format("K2 = \"{:.6f} deg/s/g^2\"", 0.02 + kSharedDrift * year));
    const std::string instrument = write(fmt::format("instrument{}.toml", year), text);
    const std::string logs = fmt::format("logs{}", year);
    const Result simulated = run(fmt::format("simulate {} --truth {} --seed {} --logs-out {} -o /dev/null",
                                             instrument, truth, 101 + year, logs));
    ASSERT_EQ(simulated.code, 0) << simulated.err;
    std::string args;
    for (const char* r : {"5g", "10g", "15g", "20g", "25g", "30g"})
      args += fmt::format(" --log {}={}/{}.csv", r, logs, r);
    const std::string out = fmt::format("statement{}.json", year);
    const Result reduced = run("reduce " + quote(kLab) + args +
                               " --statement --statement-trials 0 --statement-out " + out + " -o /dev/null");
    ASSERT_EQ(reduced.code, 0) << reduced.err;
    const Result added = run(fmt::format("history add {} --db h.sqlite --date {}-11-30", out, 2024 + year));
    ASSERT_EQ(added.code, 0) << added.err;
    statements.push_back(nlohmann::json::parse(read(dir_ / out)));
  }
  ASSERT_EQ(statements[0]["setup_sha256"], statements[2]["setup_sha256"]);
  const Result shown = run("history show 'SN 0815' --db h.sqlite --format json");
  ASSERT_EQ(shown.code, 0) << shown.err;
  const auto j = nlohmann::json::parse(shown.out);
  ASSERT_EQ(j["setups"].size(), 1u);
  EXPECT_TRUE(j["setup_changes"].empty());

  // (a) E_n of the first two by hand: C = Σ_{α,β} e_1α R_αβ e_2β over the inputs charged at their tolerance
  // in both (the statements' inputs[].effect on K0, their groups and input_correlations), then E_n = (x₂ −
  // x₁)/√(U₁² + U₂² − 2 k₁ k₂ C). The store keeps every number bit for bit, so show's E_n is the same
  // expression up to the order of the sums: 1e-12 relative.
  for (const char* name : {"K0", "K2"}) {
    const nlohmann::json &s1 = statements[0], &s2 = statements[1];
    double c = 0;
    for (const auto& a : s1["inputs"])
      for (const auto& b : s2["inputs"]) {
        if (a["measured"].get<bool>() || b["measured"].get<bool>()) continue;
        c += a["effect"][name].get<double>() * rho(s1, a, b) * b["effect"][name].get<double>();
      }
    const auto &q1 = s1["coefficients"][name], &q2 = s2["coefficients"][name];
    const double u1 = q1["expanded_uncertainty"].get<double>(), u2 = q2["expanded_uncertainty"].get<double>();
    const double k1 = q1["coverage_factor"].get<double>(), k2 = q2["coverage_factor"].get<double>();
    const double en = (q2["corrected_estimate"].get<double>() - q1["corrected_estimate"].get<double>()) /
                      std::sqrt(u1 * u1 + u2 * u2 - 2 * k1 * k2 * c);
    const auto& shown_en = j["coefficients"][name]["normalised_errors"][0];
    EXPECT_NEAR(shown_en["shared_covariance"].get<double>(), c, 1e-12 * std::abs(c)) << name;
    EXPECT_NEAR(shown_en["en"].get<double>(), en, 1e-12 * std::abs(en)) << name;
    // The shared part is most of u_B²: the difference's uncertainty is well below the independent one's.
    EXPECT_GT(c, 0.5 * std::pow(q1["type_b"]["u"].get<double>(), 2)) << name;
  }

  // (b) The drift of K2: u(b) below the machine's u_B(K2), the true 2e-4 within U(b) = 2 u(b), and b
  // significantly non-zero (|b| > 2 u(b)).
  const auto& drift = j["coefficients"]["K2"]["drift"];
  ASSERT_TRUE(drift.is_object()) << j["coefficients"]["K2"].dump();
  EXPECT_TRUE(drift["correlated"].get<bool>());
  const double b = drift["slope_per_year"].get<double>(), u_b = drift["std_slope"].get<double>();
  const double machine = statements[2]["coefficients"]["K2"]["type_b"]["u"].get<double>();
  EXPECT_LT(u_b, machine) << "u(b) " << u_b << ", u_B(K2) " << machine;
  // Charged as independent, three yearly points would give u(b) = u_c/√2 ≈ 0.7 u_B(K2) here; with the
  // machine's errors shared only the noise and the measured inputs remain (about 1.5e-6 against u_B ≈ 4e-5):
  // a tenth of u_B is far from both.
  EXPECT_LT(u_b, 0.1 * machine) << "u(b) " << u_b << ", u_B(K2) " << machine;
  EXPECT_LT(std::abs(b - kSharedDrift), 2 * u_b) << b << " ± " << u_b;
  EXPECT_GT(std::abs(b), 2 * u_b) << b << " ± " << u_b;
  // The text names the set-up and the generalised fit.
  const Result text = run("history show 'SN 0815' --db h.sqlite");
  EXPECT_NE(text.out.find("set-up S1: "), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("generalised least squares, the shared Type B taken out"), std::string::npos)
      << text.out;
}

// A hand-written statement of serial SN 9: set-up `setup` ("": none stated, as an older ccal's), K0 only, one
// input charged at its tolerance, and a certificate number and replaces.
std::string hand_statement(double k0, const std::string& setup, const std::string& number,
                           const std::string& replaces = "") {
  return fmt::format(
      R"({{{}"certificate": {{"serial_number": "SN 9", "number": "{}", "replaces": "{}"}},
      "coverage_probability": 0.95, "coefficients": {{"K0": {{"unit": "deg/s", "corrected_estimate": {},
      "expanded_uncertainty": 0.02, "coverage_factor": 2}}}},
      "inputs": [{{"id": "a", "measured": false, "effect": {{"K0": 0.008}}, "group": ""}}]}})",
      setup.empty() ? "" : "\"setup_sha256\": \"" + setup + "\", ", number, replaces, k0);
}

TEST_F(Cli, HistoryShowsItsSetUpsTheirChangesAndListsItsSerials) {
  write("s1.json", hand_statement(0.060, "", "C-1"));
  write("s2.json", hand_statement(0.061, "m1", "C-2"));
  write("s3.json", hand_statement(0.062, "m1", "C-3"));
  write("s4.json", hand_statement(0.063, "m2", "C-4"));
  write("s4b.json", hand_statement(0.0631, "m2", "C-4/1", "C-4"));
  write("bad.json", hand_statement(0.064, "m2", "C-5", "C-99"));
  for (int i = 1; i <= 4; ++i) {
    const Result added = run(fmt::format("history add s{}.json --db h.sqlite --date 202{}-01-01", i, i));
    ASSERT_EQ(added.code, 0) << added.err;
    EXPECT_EQ(added.out.find("nothing known to be shared") != std::string::npos, i == 1) << added.out;
  }
  // A corrected certificate replaces C-4: its calibration superseded in the same add; one naming no record
  // refused.
  const Result replaced = run("history add s4b.json --db h.sqlite --date 2024-02-01");
  ASSERT_EQ(replaced.code, 0) << replaced.err;
  EXPECT_NE(
      replaced.out.find("Calibration 4 superseded: its certificate C-4 is replaced by certificate C-4/1."),
      std::string::npos)
      << replaced.out;
  const Result refused = run("history add bad.json --db h.sqlite --date 2025-01-01");
  EXPECT_EQ(refused.code, 2);
  EXPECT_NE(refused.err.find("replaces certificate 'C-99', which names no calibration of 'SN 9'"),
            std::string::npos)
      << refused.err;
  // show: S1 = m1 (#2, #3), S2 = m2 (#4, #5), ? for #1; changes between #1 and #2 (not known) and #3 and #5.
  const Result text = run("history show 'SN 9' --db h.sqlite");
  ASSERT_EQ(text.code, 0) << text.err;
  for (const char* says :
       {"set-up S1: ", "(#2, #3)", "set-up S2: ", "(#4, #5)", "set-up ?: #1: recorded without what it shares",
        "change between #1 (2021-01-01) and #2 (2022-01-01): one of them does not know what it shares",
        "change between #3 (2023-01-01) and #5 (2024-02-01): another set-up; nothing shared across it",
        "superseded by #5: replaced by certificate C-4/1", "certificate C-4/1"})
    EXPECT_NE(text.out.find(says), std::string::npos) << says << "\n" << text.out;
  const auto j = nlohmann::json::parse(run("history show 'SN 9' --db h.sqlite --format json").out);
  ASSERT_EQ(j["setup_changes"].size(), 2u);
  EXPECT_TRUE(j["setup_changes"][0]["shared_unknown"].get<bool>());
  EXPECT_TRUE(j["setup_changes"][1]["setup_changed"].get<bool>());
  EXPECT_EQ(j["calibrations"][0]["setup"], "?");
  EXPECT_TRUE(j["calibrations"][0]["setup_sha256"].is_null());
  // #2 and #3 share 0.008²; E_n = 0.001/√(0.02² + 0.02² − 2·2·2·0.008²) = 0.001/√0.000288.
  const auto& en = j["coefficients"]["K0"]["normalised_errors"];
  EXPECT_NEAR(en[1]["shared_covariance"].get<double>(), 6.4e-5, 1e-18);
  EXPECT_NEAR(en[1]["en"].get<double>(), 0.001 / std::sqrt(0.000288), 1e-9);
  EXPECT_EQ(en[0]["shared_covariance"].get<double>(), 0.0);
  const Result csv = run("history show 'SN 9' --db h.sqlite --format csv");
  EXPECT_NE(csv.out.find(",id,setup,shared_covariance_to_previous\n"), std::string::npos) << csv.out;
  EXPECT_NE(csv.out.find(",1,?,\n"), std::string::npos) << csv.out;
  // list: text, JSON and CSV.
  const Result list = run("history list --db h.sqlite");
  ASSERT_EQ(list.code, 0) << list.err;
  EXPECT_NE(list.out.find("SN 9"), std::string::npos) << list.out;
  const auto l = nlohmann::json::parse(run("history list --db h.sqlite --format json").out);
  EXPECT_EQ(l["command"], "history list");
  ASSERT_EQ(l["serials"].size(), 1u);
  EXPECT_EQ(l["serials"][0]["calibrations"], 5);
  EXPECT_EQ(l["serials"][0]["superseded"], 1);
  EXPECT_EQ(l["serials"][0]["last_date"], "2024-02-01");
  EXPECT_EQ(run("history list --db h.sqlite --format csv").out,
            "serial,calibrations,superseded,last_date\n\"SN 9\",5,1,2024-02-01\n");
}

}  // namespace
