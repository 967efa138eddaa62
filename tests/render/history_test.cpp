// `ccal history` as read (render/history.hpp), on results of verbs::history_add and history_show over a store
// of three calibrations at three dates: E_n of each against the one before (none for the first, the sign shown,
// the disagreement beyond |E_n| = 1 named), the drift line with its per-year unit and the prediction at a date,
// a statement without a set-up fingerprint said to be independent, and JSON and CSV with the same numbers.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "ccal/render/history.hpp"
#include "ccal/verbs/history.hpp"
#include "render_support.hpp"

namespace ccal {
namespace history_render_test {

namespace fs = std::filesystem;
using test::line_starting;

// A statement as `ccal reduce --statement-out` writes it, reduced to what the store reads: K2 with its U.
std::string statement_of(double k2, double u2) {
  return fmt::format(
      R"({{"budget_config": "lab.toml", "coverage_probability": 0.95, "coefficients": {{
      "K2": {{"unit": "deg/s/g^2", "corrected_estimate": {}, "expanded_uncertainty": {},
              "coverage_factor": 2.0, "effective_dof": null}}}}}})",
      k2, u2);
}

class HistoryRender : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           fmt::format("ccal_history_render_{}_{}", getpid(),
                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  verbs::HistoryAddResult add(double k2, double u2, const std::string& date) {
    const std::string file = (dir_ / (date + ".json")).string();
    std::ofstream(file) << statement_of(k2, u2);
    verbs::HistoryAddOptions o;
    o.db = db();
    o.serial = "SN 1";
    o.date = date;
    return verbs::history_add(file, o);
  }
  std::string db() const { return (dir_ / "h.sqlite").string(); }
  fs::path dir_;
};

TEST_F(HistoryRender, EnOfEachAgainstTheOneBeforeAndTheDriftWithItsPrediction) {
  const verbs::HistoryAddResult first = add(0.0200, 1e-4, "2024-01-10");
  // The add's text: what was recorded, and that nothing is known to be shared.
  const std::string added = render::text(first);
  EXPECT_EQ(added.rfind("Recorded calibration 1 of SN 1 on 2024-01-10 (1 coefficients) in " + db() +
                            "; 1 calibration of SN 1 there.\n",
                        0),
            0u)
      << added;
  EXPECT_TRUE(line_starting(added, "The statement states no set-up fingerprint (setup_sha256)")) << added;
  add(0.0201, 1e-4, "2025-01-10");  // E_n = 1e-4 / sqrt(2) / 1e-4 ... agreeing
  add(0.0205, 1e-4, "2026-01-10");  // 4e-4 apart: |E_n| > 1
  verbs::HistoryShowOptions o;
  o.db = db();
  o.at = "2027-01-10";
  const verbs::HistoryShowResult r = verbs::history_show("SN 1", o);
  const std::string text = render::text(r);
  const verbs::CoefficientHistory& h = r.coefficients.at(0);
  ASSERT_EQ(h.agreement.size(), 2u);
  // The first calibration has no E_n; the others theirs, signed, 2 decimals.
  const auto row1 = test::table_cells(*line_starting(text, "2024-01-10"));
  EXPECT_EQ(row1.size(), 4u) << text;
  const auto row2 = test::table_cells(*line_starting(text, "2025-01-10"));
  ASSERT_EQ(row2.size(), 5u) << text;
  EXPECT_EQ(row2[4], fmt::format("{:+.2f}", h.agreement[0].value));
  const auto row3 = line_starting(text, "2026-01-10");
  EXPECT_NE(row3->find(fmt::format("{:+.2f}  |E_n| > 1: disagrees with the calibration before",
                                   h.agreement[1].value)),
            std::string::npos)
      << text;
  EXPECT_EQ(row2[1], fmt::format("{:.7g}", 0.0201));
  ASSERT_TRUE(h.drift.available) << h.drift.unavailable;
  EXPECT_TRUE(line_starting(text, fmt::format("drift: {:+.4g} deg/s/g^2 per year, u = ", h.drift.slope))) << text;
  ASSERT_TRUE(h.prediction);
  EXPECT_TRUE(line_starting(text, fmt::format("predicted on 2027-01-10: {:.7g} deg/s/g^2, u = {:.2g} (U = {:.2g} "
                                              "for k = 2)",
                                              h.prediction->value, h.prediction->std_uncertainty,
                                              2 * h.prediction->std_uncertainty)))
      << text;
  EXPECT_TRUE(line_starting(text, "set-up ?: #1, #2, #3: recorded without what it shares")) << text;
}

TEST_F(HistoryRender, JsonAndCsvCarryTheSameNumbers) {
  add(0.0200, 1e-4, "2024-01-10");
  add(0.0203, 1e-4, "2025-01-10");
  verbs::HistoryShowOptions o;
  o.db = db();
  const verbs::HistoryShowResult r = verbs::history_show("SN 1", o);
  const verbs::CoefficientHistory& h = r.coefficients.at(0);
  const auto j = nlohmann::json::parse(render::json(r));
  EXPECT_EQ(j["command"], "history show");
  ASSERT_EQ(j["calibrations"].size(), 2u);
  EXPECT_FALSE(j["calibrations"][0]["shared_known"].get<bool>());
  EXPECT_TRUE(j["calibrations"][0]["setup_sha256"].is_null());
  const auto& k2 = j["coefficients"]["K2"];
  ASSERT_EQ(k2["normalised_errors"].size(), 1u);
  EXPECT_EQ(k2["normalised_errors"][0]["en"].get<double>(), h.agreement[0].value);
  EXPECT_EQ(k2["normalised_errors"][0]["from"], "2024-01-10");
  // Two calibrations: no drift line, and why.
  EXPECT_TRUE(k2["drift"].is_null());
  EXPECT_EQ(k2["drift_unavailable"], h.drift.unavailable);
  EXPECT_FALSE(k2.contains("prediction"));
  const auto rows = test::rendered_lines(render::csv(r));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], "serial,coefficient,unit,date,value,expanded_uncertainty,coverage_factor,en_to_previous,id,"
                     "setup,shared_covariance_to_previous");
  const auto first = test::csv_fields(rows[1]), second = test::csv_fields(rows[2]);
  EXPECT_EQ(first[7], "");  // no E_n for the first
  EXPECT_EQ(std::stod(second[7]), h.agreement[0].value);
  EXPECT_EQ(second[0], "\"SN 1\"");
  EXPECT_EQ(second[9], "?");
}

}  // namespace history_render_test
}  // namespace ccal
