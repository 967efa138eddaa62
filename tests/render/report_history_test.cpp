// The report's history section (render/report_history.cpp) in-process, from `ccal history show`'s JSON of a
// store built here: five calibrations of K2, one superseded without a replacement and one superseded by a
// repeat. The table has a row for each calibration in force and none for the two superseded ones, which the
// section names as such; each number traced to its place in the JSON; E_n of each against the one before it in
// force; the drift with its standard uncertainty.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../src/render/report_html.hpp"
#include "ccal/render/history.hpp"
#include "ccal/verbs/history.hpp"
#include "render_support.hpp"

namespace ccal {
namespace report_history_render_test {

namespace fs = std::filesystem;

// A statement as `ccal reduce --statement-out` writes it, reduced to what the store reads: K2 with its U.
std::string report_history_statement(double k2, double u2) {
  return fmt::format(
      R"({{"budget_config": "lab.toml", "coverage_probability": 0.95, "coefficients": {{
      "K2": {{"unit": "deg/s/g^2", "corrected_estimate": {}, "expanded_uncertainty": {},
              "coverage_factor": 2.0, "effective_dof": null}}}}}})",
      k2, u2);
}

// How many times `needle` occurs in `text`.
std::size_t occurrences(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

class ReportHistory : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           fmt::format("ccal_report_history_{}_{}", getpid(),
                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // In force: #1, #3 and #5. #2 is superseded by nothing (its set-up was wrong), #4 by its repeat #5.
    add(0.0200, 1e-4, "2022-01-10");
    const std::int64_t wrong = add(0.0290, 1e-4, "2023-01-10");
    add(0.0202, 1e-4, "2024-01-10");
    const std::int64_t first_try = add(0.0210, 1e-4, "2025-01-10");
    const std::int64_t repeat = add(0.0205, 1e-4, "2025-02-10");
    supersede(wrong, 0, "wrong mounting");
    supersede(first_try, repeat, "repeated");
    verbs::HistoryShowOptions o;
    o.db = db();
    shown_ = verbs::history_show("SN 1", o);
    json_ = nlohmann::json::parse(render::json(shown_));
    section_ = render::report_html::history_section(render::report_html::Doc{"history", json_});
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::int64_t add(double k2, double u2, const std::string& date) {
    const std::string file = (dir_ / (date + ".json")).string();
    std::ofstream(file) << report_history_statement(k2, u2);
    verbs::HistoryAddOptions o;
    o.db = db();
    o.serial = "SN 1";
    o.date = date;
    return verbs::history_add(file, o).id;
  }
  void supersede(std::int64_t id, std::int64_t by, const std::string& reason) {
    verbs::HistorySupersedeOptions o;
    o.db = db();
    o.by = by;
    o.reason = reason;
    verbs::history_supersede(id, o);
  }
  std::string db() const { return (dir_ / "h.sqlite").string(); }
  // The table row of a calibration's date: from its <tr> to its </tr>; "" when there is none.
  std::string row_of(const std::string& date) const {
    const std::size_t at = section_.find("<tr><th>" + date + "</th>");
    return at == std::string::npos ? std::string() : section_.substr(at, section_.find("</tr>", at) - at);
  }
  fs::path dir_;
  verbs::HistoryShowResult shown_;
  nlohmann::json json_;
  std::string section_;
};

TEST_F(ReportHistory, ARowForEachCalibrationInForceEachNumberTracedToTheJson) {
  EXPECT_EQ(occurrences(section_, "<tr><th>20"), 3u) << section_;
  // The JSON lists every calibration, superseded ones included: the rows in force are its 0th, 2nd and 4th.
  const std::string first = row_of("2022-01-10"), third = row_of("2024-01-10"), repeat = row_of("2025-02-10");
  ASSERT_FALSE(first.empty()) << section_;
  ASSERT_FALSE(third.empty()) << section_;
  ASSERT_FALSE(repeat.empty()) << section_;
  EXPECT_NE(first.find(R"(data-src="history:/calibrations/0/coefficients/K2/value" data-digits="7">0.02</td>)"),
            std::string::npos)
      << first;
  EXPECT_NE(repeat.find(R"(data-src="history:/calibrations/4/coefficients/K2/value" data-digits="7">0.0205</td>)"),
            std::string::npos)
      << repeat;
  EXPECT_NE(repeat.find(R"(data-src="history:/calibrations/4/coefficients/K2/expanded_uncertainty" )"
                        R"(data-digits="3">0.0001</td>)"),
            std::string::npos)
      << repeat;
  EXPECT_NE(repeat.find(R"(data-src="history:/calibrations/4/coefficients/K2/coverage_factor" data-digits="3">2</td>)"),
            std::string::npos)
      << repeat;
  EXPECT_NE(first.find("<td>?</td>"), std::string::npos) << first;  // the set-up, not known
}

TEST_F(ReportHistory, EnOfEachAgainstTheOneBeforeItInForce) {
  const verbs::CoefficientHistory& k2 = shown_.coefficients.at(0);
  ASSERT_EQ(k2.agreement.size(), 2u);  // #1 → #3, #3 → #5: the superseded ones take no part
  // The first row has no E_n; the others theirs, to three digits, traced to normalised_errors.
  const std::string first = row_of("2022-01-10");
  EXPECT_EQ(first.substr(first.size() - 9), "<td></td>") << first;
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string row = row_of(k == 0 ? "2024-01-10" : "2025-02-10");
    EXPECT_NE(row.find(fmt::format(R"(data-src="history:/coefficients/K2/normalised_errors/{}/en" )"
                                   R"(data-digits="3">{:.3g}</td>)",
                                   k, k2.agreement[k].value)),
              std::string::npos)
        << row;
  }
  // E_n = (0.0202 − 0.0200) / √(U1² + U2²) = 2e-4 / 1.414e-4 = 1.41, nothing shared (no set-up known); to 1e-9,
  // the rounding of the values' decimal text.
  EXPECT_NEAR(k2.agreement[0].value, 2e-4 / std::sqrt(2e-8), 1e-9);
}

TEST_F(ReportHistory, TheDriftAndItsUncertaintyFromTheCalibrationsInForce) {
  const verbs::CoefficientHistory& k2 = shown_.coefficients.at(0);
  ASSERT_TRUE(k2.drift.available) << k2.drift.unavailable;
  EXPECT_NE(section_.find(fmt::format(R"(<p>Drift: <span class="num" data-src="history:/coefficients/K2/drift/)"
                                      R"(slope_per_year" data-digits="3">{:.3g}</span> deg/s/g^2 per year, u = )"
                                      R"(<span class="num" data-src="history:/coefficients/K2/drift/std_slope" )"
                                      R"(data-digits="2">{:.2g}</span> (weighted straight line; Birge ratio )",
                                      k2.drift.slope, k2.drift.std_slope)),
            std::string::npos)
      << section_;
  // Three points, 2022-01-10, 2024-01-10, 2025-02-10 with equal U: the slope is that of the least squares
  // line, between 1e-4 and 2e-4 deg/s/g^2 a year; the superseded 0.0290 of 2023 in it would make it far more.
  EXPECT_GT(k2.drift.slope, 1e-4);
  EXPECT_LT(k2.drift.slope, 2e-4);
  EXPECT_EQ(k2.dates, (std::vector<std::string>{"2022-01-10", "2024-01-10", "2025-02-10"}));
}

TEST_F(ReportHistory, TheSupersededOnesAreLeftOutAndNamedAsSuch) {
  EXPECT_TRUE(row_of("2023-01-10").empty()) << section_;
  EXPECT_TRUE(row_of("2025-01-10").empty()) << section_;
  EXPECT_EQ(section_.find("0.029"), std::string::npos) << section_;  // nor in the chart
  EXPECT_NE(section_.find("<p>Left out: #2 of 2023-01-10 (superseded: wrong mounting); #4 of 2025-01-10 "
                          "(superseded by #5: repeated).</p>"),
            std::string::npos)
      << section_;
}

}  // namespace report_history_render_test
}  // namespace ccal
