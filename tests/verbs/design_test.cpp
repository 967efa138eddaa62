// `ccal design` on the bundled example (verbs/design.hpp): the cached rows score a plan exactly as the full
// budget does, the designed plan is never worse than the configured one and keeps every constraint, the
// configuration written with the designed [plan] budgets to the same numbers, and the [design] table's bad
// values are refused with their place in the file.
#include "ccal/render/design.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/design_candidates.hpp"
#include "ccal/verbs/design.hpp"
#include "verbs_support.hpp"

namespace ccal {
namespace {

using test::kSmallDesignSpace;

Config small_config(const std::string& extra = "") {
  return parse_config(std::string(bundled_example_text()) + kSmallDesignSpace + extra, "design_test.toml");
}

double relative(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

// The cache scores the configured plan with the budget's rows (output_jacobian, observe's model means,
// rate_noise_gain, groups and u_s): its U must equal the full budget's to the round-off of two different
// least-squares solutions (normal equations of scaled columns against QR): 1e-9 relative.
TEST(Design, CachedRowsScoreAsTheBudget) {
  const Config config = small_config();
  std::vector<DesignRun> runs;
  for (const ccal::Run& r : config.plan.runs) runs.push_back(design_run(r));
  const CandidateRows rows = candidate_rows(config, runs, 1);
  DesignCriterion c;
  c.weight = Eigen::VectorXd::Ones(3);
  c.reference = Eigen::VectorXd::Ones(3);
  const PlanScore s = score_plan(rows, c);
  ASSERT_TRUE(s.well_posed);
  const verbs::BudgetResult b = verbs::budget(config);
  for (Eigen::Index k = 0; k < 3; ++k)
    EXPECT_LT(relative(s.expanded[k], b.budget.expanded_uncertainty[k]), 1e-9) << b.budget.coefficients[k];
  EXPECT_LT((s.covariance - b.budget.covariance).norm(), 1e-9 * b.budget.covariance.norm());
}

// With partly correlated inputs ([[correlations]]) the cache adds the leaks through the same factor of R as
// the budget (leak rows diag(u) F): the same agreement, 1e-9.
TEST(Design, CachedRowsScoreAsTheBudgetWithCorrelations) {
  const Config config = small_config(
      "\n[[correlations]]\nbetween = [\"ripple1_c1\", \"ripple3_c1\"]\nr = -0.5\n\n[[correlations]]\n"
      "between = [\"dthy4\", \"dthy5\"]\nr = 0.6\n");
  ASSERT_EQ(config.correlations.size(), 2u);
  std::vector<DesignRun> runs;
  for (const ccal::Run& r : config.plan.runs) runs.push_back(design_run(r));
  DesignCriterion c;
  c.weight = Eigen::VectorXd::Ones(3);
  c.reference = Eigen::VectorXd::Ones(3);
  const PlanScore s = score_plan(candidate_rows(config, runs, 1), c);
  const verbs::BudgetResult b = verbs::budget(config);
  const verbs::BudgetResult independent = verbs::budget(small_config());
  for (Eigen::Index k = 0; k < 3; ++k) {
    EXPECT_LT(relative(s.expanded[k], b.budget.expanded_uncertainty[k]), 1e-9) << b.budget.coefficients[k];
    // And the correlations matter here (K0 grows by a fifth with the ripples' r = −0.5), so the test can
    // fail.
    if (k == 0) {
      EXPECT_GT(b.budget.expanded_uncertainty[k], 1.1 * independent.budget.expanded_uncertainty[k]);
    }
  }
}

// The design scores plans under the configured platform control (model.md §2.3): with the platform slaved to
// the main encoder, the main axis's once-per-revolution ripple no longer turns the instrument's heading, so
// the cache, like the budget, gives a different U for the same plan. Each mode's cached score must equal that
// mode's full budget (1e-9, as above), and the two modes must differ by more than any round-off (the bundled
// example's U(K3) falls by more than a factor 2 when the heading wobble of the ±10 ppm main ripple goes), and
// the designed plan keeps the configured mode in the file it writes.
TEST(Design, FollowsThePlatformControl) {
  std::string text = std::string(bundled_example_text()) + kSmallDesignSpace;
  const auto at = text.find("platform_control = \"speed\"");
  ASSERT_NE(at, std::string::npos);
  const Config speed = parse_config(text, "speed.toml");
  text.replace(at, std::string("platform_control = \"speed\"").size(), "platform_control = \"phase_locked\"");
  const Config locked = parse_config(text, "locked.toml");
  ASSERT_EQ(locked.centrifuge.geometry.platform_control, PlatformControl::phase_locked);

  Eigen::VectorXd u_k3(2);
  int i = 0;
  for (const Config* config : {&speed, &locked}) {
    std::vector<DesignRun> runs;
    for (const ccal::Run& r : config->plan.runs) runs.push_back(design_run(r));
    const CandidateRows rows = candidate_rows(*config, runs, 1);
    DesignCriterion c;
    c.weight = Eigen::VectorXd::Ones(3);
    c.reference = Eigen::VectorXd::Ones(3);
    const PlanScore s = score_plan(rows, c);
    ASSERT_TRUE(s.well_posed);
    const verbs::BudgetResult b = verbs::budget(*config);
    for (Eigen::Index k = 0; k < 3; ++k)
      EXPECT_LT(relative(s.expanded[k], b.budget.expanded_uncertainty[k]), 1e-9) << b.budget.coefficients[k];
    u_k3[i++] = s.expanded[2];
  }
  EXPECT_GT(u_k3[0], 2 * u_k3[1]) << "U(K3) speed " << u_k3[0] << ", phase_locked " << u_k3[1];

  const verbs::DesignResult designed = verbs::design(locked);
  EXPECT_EQ(designed.designed.centrifuge.geometry.platform_control, PlatformControl::phase_locked);
  EXPECT_LT(relative(designed.before.budget.expanded_uncertainty[2], u_k3[1]), 1e-9);
  const Config reread = parse_config(render::config_with_plan(text, designed.designed), "designed.toml");
  EXPECT_EQ(reread.centrifuge.geometry.platform_control, PlatformControl::phase_locked);
}

class DesignedExample : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { result_ = new verbs::DesignResult(verbs::design(small_config())); }
  static void TearDownTestSuite() { delete result_; }
  static const verbs::DesignResult& r() { return *result_; }
  static verbs::DesignResult* result_;
};
verbs::DesignResult* DesignedExample::result_ = nullptr;

// Never worse: the configured plan is one of the starts, so the objective (by the cache) cannot rise, and the
// full budget of the plan as run agrees with the cache on the designed plan to its rounding (below).
TEST_F(DesignedExample, NeverWorseThanTheConfiguredPlan) {
  EXPECT_LE(r().designed_objective, r().configured_objective);
  for (Eigen::Index k = 1; k < 3; ++k) {  // K2, K3: the coefficients the objective counts (all three here)
    EXPECT_LE(r().after.budget.expanded_uncertainty[k], r().before.budget.expanded_uncertainty[k])
        << r().after.budget.coefficients[k];
    // The plan as run is rounded to the machine's settings (0.01 g, 1 ms, 0.1°): it scores within 1 % of the
    // search's optimum (each setting moved by half a step at most: 0.4 % on K3, the most sensitive).
    EXPECT_LT(relative(r().search.score.expanded[k], r().after.budget.expanded_uncertainty[k]), 1e-2);
  }
}

// Every constraint of the space holds: six runs, at most the paper plan's 2700 s in all, g-levels within
// 5 … 30 g, the platform mode and mounting of the configured plan, the designed phase kind (terminal).
TEST_F(DesignedExample, EveryConstraintHolds) {
  const auto& runs = r().designed.plan.runs;
  ASSERT_EQ(runs.size(), 6u);
  double total = 0;
  for (const ccal::Run& run : runs) {
    total += run.duration;
    EXPECT_GE(run.g_level, 5.0 * (1 - 1e-15));
    EXPECT_LE(run.g_level, 30.0 * (1 + 1e-15));
    EXPECT_EQ(run.mode, PlatformMode::counter_rotating);
    EXPECT_EQ(run.mounting, Mounting::ia_horizontal);
    EXPECT_TRUE(run.terminal_phase.has_value());
  }
  EXPECT_LE(total, 2700 * (1 + 1e-12));
  // At least the free terms + 1 distinct g-levels (the default of min_g_levels), counted as the operator sets
  // them (0.01 g).
  std::set<long long> levels;
  for (const ccal::Run& run : runs) levels.insert(std::llround(run.g_level / 0.01));
  EXPECT_GE(levels.size(), 4u);
  // The run sheet is the designed plan, run by run in its order.
  ASSERT_EQ(r().sheet.lines.size(), runs.size());
  for (std::size_t j = 0; j < runs.size(); ++j) {
    EXPECT_EQ(r().sheet.lines[j].run, runs[j].name);
    EXPECT_EQ(r().sheet.lines[j].g_level, runs[j].g_level);
    EXPECT_EQ(r().sheet.lines[j].duration, runs[j].duration);
  }
}

// min_g_levels = 6: every run at a g-level of its own, where the unconstrained design pairs runs at one level
// (the pairs of opposite headings of docs/model.md §15.3).
TEST(DesignMinGLevels, EveryRunOnItsOwnLevelWhenAsked) {
  const verbs::DesignResult all = verbs::design(small_config("min_g_levels = 6\n"));
  std::set<long long> levels;
  for (const ccal::Run& run : all.designed.plan.runs) levels.insert(std::llround(run.g_level / 0.01));
  EXPECT_EQ(levels.size(), 6u);
  const verbs::DesignResult free = verbs::design(small_config("min_g_levels = 1\n"));
  levels.clear();
  for (const ccal::Run& run : free.designed.plan.runs) levels.insert(std::llround(run.g_level / 0.01));
  EXPECT_LT(levels.size(), 6u);
}

// The configuration written with the designed [plan] reads back to the same runs, bit for bit (17 digits in
// g, s and rad), so its budget equals the designed plan's (relative 1e-12; in fact exactly).
TEST_F(DesignedExample, WrittenPlanBudgetsTheSame) {
  const std::string text =
      render::config_with_plan(std::string(bundled_example_text()) + kSmallDesignSpace, r().designed);
  const Config back = parse_config(text, "designed.toml");
  ASSERT_EQ(back.plan.runs.size(), r().designed.plan.runs.size());
  for (std::size_t j = 0; j < back.plan.runs.size(); ++j) {
    EXPECT_EQ(back.plan.runs[j].g_level, r().designed.plan.runs[j].g_level);
    EXPECT_EQ(back.plan.runs[j].duration, r().designed.plan.runs[j].duration);
    EXPECT_EQ(*back.plan.runs[j].terminal_phase, *r().designed.plan.runs[j].terminal_phase);
    EXPECT_EQ(back.plan.runs[j].arm_azimuth, r().designed.plan.runs[j].arm_azimuth);
  }
  const verbs::BudgetResult b = verbs::budget(back);
  for (Eigen::Index k = 0; k < 3; ++k)
    EXPECT_LT(relative(b.budget.expanded_uncertainty[k], r().after.budget.expanded_uncertainty[k]), 1e-12);
  // The rest of the file is kept: tolerances, instrument, the [design] table itself.
  EXPECT_EQ(back.tolerances.size(), r().config.tolerances.size());
  EXPECT_EQ(back.design.turn_fractions, 4);
}

// `ccal design --format csv`: the run sheet, one row per run in the order it is run, in rpm, s and degrees as
// the operator sets them (the JSON's run_sheet.runs), each value the shortest digits of the same double.
TEST_F(DesignedExample, CsvRowsAreTheRunSheet) {
  const std::string csv = render::csv(r());
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "order,run,g_level_g,main_speed_rpm,platform,platform_speed_rpm,duration_s,turns,arm_azimuth_deg,"
            "start_phase_deg,stop_phase_deg,sets,mounting,mounting_axes");
  constexpr double kRpm = 2 * 3.14159265358979323846 / 60, kDegree = 180 / 3.14159265358979323846;
  for (const ccal::RunSheetLine& l : r().sheet.lines) {
    ASSERT_TRUE(std::getline(in, line));
    std::vector<std::string> cells;
    std::istringstream row(line.substr(0, line.find('"')));  // mounting_axes, quoted, holds commas
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 13u) << line;
    EXPECT_EQ(std::stoi(cells[0]), l.order);
    EXPECT_EQ(cells[1], l.run);
    EXPECT_EQ(std::stod(cells[2]), l.g_level);
    // rpm and degrees as the run sheet converts them; relative 1e-15 for a constant's last digit.
    EXPECT_NEAR(std::stod(cells[3]), l.main_rate / kRpm, 1e-15 * l.main_rate / kRpm);
    EXPECT_EQ(cells[4], "counter_rotating");
    EXPECT_EQ(std::stod(cells[6]), l.duration);
    EXPECT_NEAR(std::stod(cells[8]), l.arm_azimuth * kDegree, 1e-12);
    EXPECT_EQ(cells[11], l.terminal_phase ? "stop_phase" : "start_phase");
    EXPECT_EQ(cells[12], "ia_horizontal");
  }
  EXPECT_FALSE(std::getline(in, line)) << "a row more than the run sheet's: " << line;
}

// The plan text keeps every digit of values that no short decimal carries (17 significant digits).
TEST(DesignPlanText, RoundTripsEveryDigit) {
  Config c = bundled_example();
  for (std::size_t j = 0; j < c.plan.runs.size(); ++j) {
    ccal::Run& run = c.plan.runs[j];
    run.g_level = 7.0 / 3.0 + double(j);
    run.duration = 1000.0 / 7.0;
    run.terminal_phase = 1.0 / 7.0;
    run.arm_azimuth = std::exp(1.0);
  }
  const Config back = parse_config(render::config_with_plan(bundled_example_text(), c), "x.toml");
  for (std::size_t j = 0; j < c.plan.runs.size(); ++j) {
    EXPECT_EQ(back.plan.runs[j].g_level, c.plan.runs[j].g_level);
    EXPECT_EQ(back.plan.runs[j].duration, c.plan.runs[j].duration);
    EXPECT_EQ(*back.plan.runs[j].terminal_phase, *c.plan.runs[j].terminal_phase);
    EXPECT_EQ(back.plan.runs[j].arm_azimuth, c.plan.runs[j].arm_azimuth);
  }
}

// A [design] table's bad values: refused with file, line and key, or (for what depends on the plan) with the
// key and what would be accepted.
TEST(DesignConfig, BadValuesAreRefusedWithTheirPlace) {
  auto message = [](const std::string& design) -> std::string {
    try {
      const Config c = parse_config(std::string(bundled_example_text()) + "\n[design]\n" + design, "d.toml");
      verbs::design(c);
    } catch (const InputError& e) {
      return e.what();
    }
    return "accepted";
  };
  const int line =
      1 + int(std::count(bundled_example_text().begin(), bundled_example_text().end(), '\n')) + 2;
  EXPECT_EQ(message("runz = 6"),
            "d.toml:" + std::to_string(line) + ":1: design.runz: unknown key; did you mean 'runs'?");
  EXPECT_NE(message("runs = 2").find("design.runs: 2 runs cannot identify 3 free terms"), std::string::npos);
  EXPECT_NE(message("g_levels = [\"5 g\", \"40 g\"]").find("design.g_levels: 40 g exceeds max_g = 30 g"),
            std::string::npos);
  EXPECT_NE(message("g_range = [\"30 g\", \"5 g\"]").find("design.g_range"), std::string::npos);
  EXPECT_NE(message("durations = [\"900 s\"]").find("cannot fit total_time"), std::string::npos);
  EXPECT_NE(message("phase_step = \"-5 deg\"").find("design.phase_step: must be positive"),
            std::string::npos);
  EXPECT_NE(message("targets = { K9 = \"1e-6 deg/s/g^3\" }").find("not a free term"), std::string::npos);
  EXPECT_NE(message("targets = { K3 = \"1e-6 m\" }").find("design.targets.K3"), std::string::npos);
  EXPECT_NE(message("objective = \"e_optimal\"").find("accepted: uncertainty, d_optimal, a_optimal"),
            std::string::npos);
  // Two g-levels cannot separate K0, K2 and K3 on this platform: the search finds no well-posed plan.
  EXPECT_NE(message("g_levels = [\"10 g\", \"20 g\"]\nturn_fractions = 1\nphases = [\"180 "
                    "deg\"]\narm_azimuths = [\"0 deg\"]\nmin_g_levels = 2")
                .find("identifies every free term"),
            std::string::npos);
}

}  // namespace
}  // namespace ccal
