// `ccal history` as a lab relies on it, against hand computations: a calibration withdrawn without a
// replacement is left out of E_n, the drift and the prediction; the Birge ratio where it is neither 0 nor 1
// (so that its square root shows); a refused first write leaves no store behind; a serial that is not UTF-8,
// an export with two entries of one id, a non-finite or negative U refused; E_n of values near the largest
// double; a store edited by hand refused in words about the store.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

// A statement of one coefficient K0 [deg/s] with U and k = 2, dated and serialled by the options of `add`.
std::string k0_statement(double value, double expanded, const std::string& extra = "") {
  return fmt::format(R"({{"coverage_probability": 0.95{}, "coefficients": {{"K0": {{"unit": "deg/s",
      "corrected_estimate": {:.17g}, "expanded_uncertainty": {:.17g}, "coverage_factor": 2}}}}}})",
                     extra, value, expanded);
}

class HistoryTrust : public Cli {
 protected:
  void add(const std::string& name, double value, double expanded, const std::string& date,
           const std::string& db = "h.sqlite") {
    write(name, k0_statement(value, expanded));
    const Result r = run(fmt::format("history add {} --db {} --serial S1 --date {}", name, db, date));
    ASSERT_EQ(r.code, 0) << r.err;
  }
};

TEST_F(HistoryTrust, AWithdrawnCalibrationIsLeftOutOfEnTheDriftAndThePrediction) {
  // Four yearly calibrations with u = 0.1 (U = 0.2, k = 2); the second (9.0, far off) withdrawn without a
  // replacement. What remains: x = 1.0, 1.3, 1.2 at t = 0, 731, 1096 days (2024 is a leap year), in years of
  // 365.25 days; the prediction at 2024-01-01 = 1461 days.
  add("a.json", 1.0, 0.2, "2020-01-01");
  add("b.json", 9.0, 0.2, "2021-01-01");
  add("c.json", 1.3, 0.2, "2022-01-01");
  add("d.json", 1.2, 0.2, "2023-01-01");
  const Result withdrawn = run("history supersede 2 --reason 'wrong instrument mounted' --db h.sqlite");
  ASSERT_EQ(withdrawn.code, 0) << withdrawn.err;
  const Result shown = run("history show S1 --db h.sqlite --at 2024-01-01 --format json");
  ASSERT_EQ(shown.code, 0) << shown.err;
  const auto k0 = nlohmann::json::parse(shown.out)["coefficients"]["K0"];
  EXPECT_EQ(k0["calibrations"], nlohmann::json({1, 3, 4}));
  // E_n of the successive calibrations in force, 1 → 3 and 3 → 4: ±0.3 and −0.1 over √(0.2² + 0.2²); to
  // round-off of a difference of values near 1 (1e-15).
  ASSERT_EQ(k0["normalised_errors"].size(), 2u);
  EXPECT_NEAR(k0["normalised_errors"][0]["en"].get<double>(), 0.3 / std::sqrt(0.08), 1e-14);
  EXPECT_NEAR(k0["normalised_errors"][1]["en"].get<double>(), -0.1 / std::sqrt(0.08), 1e-14);
  // The line through the three by hand (equal weights w = 1/u² = 100): t̄ = mean t, S = Σ (t − t̄)²/u²,
  // b = Σ (t − t̄) x / u² / S, a = mean x, χ² = Σ r²/u², R_B = √(χ²/1); the prediction a + b (t − t̄) with
  // u² = u²/3 + (t − t̄)²/S. Sums of three terms of order 1: 1e-13 relative covers their round-off.
  const double t[] = {0, 731 / 365.25, 1096 / 365.25}, x[] = {1.0, 1.3, 1.2}, u = 0.1;
  const double t_bar = (t[0] + t[1] + t[2]) / 3, a = (x[0] + x[1] + x[2]) / 3;
  double S = 0, Sx = 0;
  for (int i = 0; i < 3; ++i) {
    S += (t[i] - t_bar) * (t[i] - t_bar) / (u * u);
    Sx += (t[i] - t_bar) * x[i] / (u * u);
  }
  const double b = Sx / S;
  double chi2 = 0;
  for (int i = 0; i < 3; ++i) chi2 += std::pow((x[i] - a - b * (t[i] - t_bar)) / u, 2);
  const auto& drift = k0["drift"];
  ASSERT_TRUE(drift.is_object()) << shown.out;
  EXPECT_NEAR(drift["slope_per_year"].get<double>(), b, 1e-13 * std::abs(b));
  EXPECT_NEAR(drift["std_slope"].get<double>(), 1 / std::sqrt(S), 1e-13 / std::sqrt(S));
  EXPECT_NEAR(drift["value_at_reference"].get<double>(), a, 1e-13);
  EXPECT_NEAR(drift["chi_squared"].get<double>(), chi2, 1e-12 * chi2);
  // R_B = √(χ²/dof) with χ² ≈ 2.6 and dof = 1: neither 0 nor 1, so χ²/dof printed for it shows.
  ASSERT_GT(chi2, 1.5);
  EXPECT_NEAR(drift["birge_ratio"].get<double>(), std::sqrt(chi2), 1e-12);
  const double tp = 1461 / 365.25, predicted = a + b * (tp - t_bar);
  EXPECT_NEAR(k0["prediction"]["value"].get<double>(), predicted, 1e-13);
  EXPECT_NEAR(k0["prediction"]["std_uncertainty"].get<double>(),
              std::sqrt(u * u / 3 + (tp - t_bar) * (tp - t_bar) / S), 1e-13);
  // The text says the same ratio, to its two decimals.
  const Result text = run("history show S1 --db h.sqlite");
  EXPECT_NE(text.out.find(fmt::format("Birge ratio {:.2f}", std::sqrt(chi2))), std::string::npos) << text.out;
}

TEST_F(HistoryTrust, ARefusedFirstWriteLeavesNoStore) {
  // A statement the store refuses only once open (its certificate replaces one it does not hold), and an
  // import refused once read: neither leaves a file.
  write("r.json", k0_statement(1.0, 0.2, R"(, "certificate": {"serial_number": "S1",
      "date_of_calibration": "2026-01-01", "number": "C-2", "replaces": "C-1"})"));
  expect_bad_input(run("history add r.json --db new.sqlite"), {"replaces certificate 'C-1'"});
  EXPECT_FALSE(fs::exists(dir_ / "new.sqlite"));
  add("a.json", 1.0, 0.2, "2024-01-01");
  add("b.json", 1.1, 0.2, "2025-01-01");
  ASSERT_EQ(run("history export S1 --db h.sqlite -o e.json").code, 0);
  auto e = nlohmann::json::parse(read(dir_ / "e.json"));
  e["calibrations"][1]["statement"]["coefficients"]["K0"]["unit"] = "rad/s";  // refused by the store
  write("units.json", e.dump());
  expect_bad_input(run("history import units.json --db new.sqlite"), {"K0 of 'S1' is in 'rad/s'"});
  EXPECT_FALSE(fs::exists(dir_ / "new.sqlite"));
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().string().find(".new"), std::string::npos) << entry.path();
  // Into an existing store: the import is one transaction, its first calibration not kept either.
  add("z.json", 5.0, 0.2, "2020-01-01", "other.sqlite");
  expect_bad_input(run("history import units.json --db other.sqlite"), {"K0 of 'S1' is in 'rad/s'"});
  const auto kept = nlohmann::json::parse(run("history show S1 --db other.sqlite --format json").out);
  EXPECT_EQ(kept["calibrations"].size(), 1u);
  // A first write that succeeds makes the store where it was asked for.
  ASSERT_EQ(run("history import e.json --db made/here.sqlite").code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "made/here.sqlite"));
}

TEST_F(HistoryTrust, AnExportWithTwoEntriesOfOneIdIsRefused) {
  add("a.json", 1.0, 0.2, "2024-01-01");
  add("b.json", 1.1, 0.2, "2025-01-01");
  add("c.json", 1.2, 0.2, "2026-01-01");
  ASSERT_EQ(run("history supersede 1 --by 2 --reason 'repeated' --db h.sqlite").code, 0);
  ASSERT_EQ(run("history export S1 --db h.sqlite -o e.json").code, 0);
  auto e = nlohmann::json::parse(read(dir_ / "e.json"));
  e["calibrations"][2]["id"] = 2;  // two entries of id 2: "superseded by 2" names which?
  write("dup.json", e.dump());
  expect_bad_input(run("history import dup.json --db new.sqlite"),
                   {"dup.json: calibrations[2] has the id 2 of calibrations[1]", "accepted: each calibration's own id"});
  EXPECT_FALSE(fs::exists(dir_ / "new.sqlite"));
}

TEST_F(HistoryTrust, WhatTheHistoryCouldNotUseIsRefusedAtAdd) {
  write("s.json", k0_statement(1.0, 0.2));
  // A serial that is not UTF-8 (Latin-1 "é"): shown escaped, refused before the store is opened.
  expect_bad_input(run("history add s.json --db h.sqlite --date 2024-01-01 --serial \"$(printf 'SN\\351 1')\""),
                   {"--serial: 'SN\\xe9 1' is not valid UTF-8 text"});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
  // U negative or beyond double precision (JSON 1e999 reads as infinity).
  write("neg.json", k0_statement(1.0, -0.2));
  expect_bad_input(run("history add neg.json --db h.sqlite --serial S1 --date 2024-01-01"),
                   {"coefficient K0 has no finite value, finite U ≥ 0 and finite k > 0"});
  write("inf.json", R"({"coverage_probability": 0.95, "coefficients": {"K0": {"unit": "deg/s",
      "corrected_estimate": 1, "expanded_uncertainty": 1e999, "coverage_factor": 2}}})");
  expect_bad_input(run("history add inf.json --db h.sqlite --serial S1 --date 2024-01-01"),
                   {"inf.json: not JSON", "number overflow parsing '1e999'"});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
}

TEST_F(HistoryTrust, NormalisedErrorNearTheLargestDouble) {
  // K0 = +1e308 then −1e308, U = 1e308 each: E_n = −2e308/√(2e616) = −√2, though the difference and the
  // squares overflow a double. Relative 1e-15: the scaled expression's round-off.
  add("a.json", 1e308, 1e308, "2024-01-01");
  add("b.json", -1e308, 1e308, "2025-01-01");
  const Result shown = run("history show S1 --db h.sqlite --format json");
  ASSERT_EQ(shown.code, 0) << shown.err;
  const auto en = nlohmann::json::parse(shown.out)["coefficients"]["K0"]["normalised_errors"][0]["en"];
  ASSERT_TRUE(en.is_number()) << shown.out;
  EXPECT_NEAR(en.get<double>(), -std::sqrt(2.0), 1e-15);
}

TEST_F(HistoryTrust, AStoreEditedByHandIsRefusedInWordsAboutTheStore) {
  add("a.json", 1.0, 0.2, "2024-01-01");
  add("b.json", 1.1, 0.2, "2025-01-01");
  // A copy of the store with the triggers dropped and the first record's date made no date, as a hand edit
  // would (sqlite3's Python module: the program has no way to do it).
  const std::string edit = fmt::format(
      "python3 -c \"import sqlite3; d = sqlite3.connect('{}'); d.execute('DROP TRIGGER calibration_kept'); "
      "d.execute(\\\"UPDATE calibration SET date = '2024-13-45' WHERE id = 1\\\"); d.commit()\"",
      (dir_ / "h.sqlite").string());
  ASSERT_EQ(std::system(edit.c_str()), 0);
  for (const char* verb : {"show S1", "export S1"})
    expect_bad_input(run(std::string("history ") + verb + " --db h.sqlite"),
                     {"h.sqlite: history store: calibration 1 as stored: its date '2024-13-45' is not YYYY-MM-DD",
                      "changed outside ccal"});
}

}  // namespace
