// `ccal design` as read (render/design.hpp), on one result of verbs::design over a small design space (192
// candidates): both plans' tables with their totals, the objective line, the comparison in each coefficient's
// display unit, and a JSON whose designed plan, coefficients, trade-off and Monte Carlo check are the result's
// (the last two only when asked for); the CSV is the run sheet, one line per run.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <string>

#include "ccal/core/format.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/render/design.hpp"
#include "ccal/verbs/design.hpp"
#include "render_support.hpp"
#include "verbs_support.hpp"

namespace ccal {
namespace design_render_test {

using test::line_starting;

// One design for the file's tests (a second or two): with a Monte Carlo check and a two-point trade-off.
const verbs::DesignResult& small_design() {
  static const verbs::DesignResult r = [] {
    verbs::DesignOptions o;
    o.cache_folder.clear();
    o.threads = 1;
    o.verify_trials = 300;
    o.tradeoff = {0.8, 1};  // fractions of the total time limit
    return verbs::design(parse_config(std::string(bundled_example_text()) + test::kSmallDesignSpace, "small.toml"),
                         o);
  }();
  return r;
}

TEST(DesignText, BothPlansWithTheirTotalsAndTheObjective) {
  const verbs::DesignResult& r = small_design();
  const std::string text = render::text(r);
  EXPECT_EQ(text.rfind("Test-plan design (docs/model.md §15) of small.toml\n", 0), 0u) << text;
  const auto configured = text.find("\nConfigured plan\n"), designed = text.find("\nDesigned plan\n");
  ASSERT_NE(configured, std::string::npos) << text;
  ASSERT_NE(designed, std::string::npos) << text;
  EXPECT_LT(configured, designed);
  // Each designed run has its row (name, g-level) under "Designed plan", and the plan its total.
  double total = 0;
  for (const ccal::Run& run : r.designed.plan.runs) {
    const auto row = line_starting(text.substr(designed), run.name + " ");
    ASSERT_TRUE(row) << run.name;
    EXPECT_EQ(test::table_cells(*row).at(1), number(run.g_level)) << *row;
    total += run.duration;
  }
  EXPECT_TRUE(line_starting(text.substr(designed), fmt::format("total {} s", number(total)))) << text.substr(designed);
  EXPECT_TRUE(line_starting(text, fmt::format("Objective: configured {}, designed {}", number(r.configured_objective, 5),
                                                  number(r.designed_objective, 5))))
      << text;
}

TEST(DesignText, TheComparisonIsInEachCoefficientsDisplayUnit) {
  const verbs::DesignResult& r = small_design();
  const std::string text = render::text(r);
  const auto at = text.find("\nConfigured against designed");
  ASSERT_NE(at, std::string::npos) << text;
  const BudgetDetail& b0 = r.before.budget;
  const BudgetDetail& b1 = r.after.budget;
  for (std::size_t k = 0; k < b0.coefficients.size(); ++k) {
    const auto row = line_starting(text.substr(at), b0.coefficients[k] + " ");
    ASSERT_TRUE(row) << b0.coefficients[k];
    const std::string& line = *row;
    EXPECT_NE(line.find(fmt::format(" {} ", b0.units[k])), std::string::npos) << line;
    const double f = b0.display_scale[k];
    EXPECT_NE(line.find(fmt::format(" {} ", number(b0.expanded_uncertainty[Eigen::Index(k)] * f, 4))), std::string::npos)
        << line;
    EXPECT_NE(line.find(fmt::format(" {} ", number(b1.expanded_uncertainty[Eigen::Index(k)] * f, 4))), std::string::npos)
        << line;
  }
}

TEST(DesignJson, ThePlanTheCoefficientsTheTradeoffAndTheCheckAreTheResults) {
  const verbs::DesignResult& r = small_design();
  const auto j = nlohmann::json::parse(render::json(r));
  EXPECT_EQ(j["command"], "design");
  ASSERT_EQ(j["designed_plan"].size(), r.designed.plan.runs.size());
  for (std::size_t i = 0; i < r.designed.plan.runs.size(); ++i) {
    const ccal::Run& run = r.designed.plan.runs[i];
    const auto& o = j["designed_plan"][i];
    EXPECT_EQ(o["name"], run.name);
    EXPECT_EQ(o["duration_s"].get<double>(), run.duration);
    EXPECT_EQ(o.contains("terminal_phase_rad"), run.terminal_phase.has_value());
    EXPECT_EQ(o["arm_azimuth_rad"].get<double>(), run.arm_azimuth);
  }
  const BudgetDetail& b0 = r.before.budget;
  for (std::size_t k = 0; k < b0.coefficients.size(); ++k) {
    const auto& c = j["coefficients"][b0.coefficients[k]];
    const double f = b0.display_scale[k];
    EXPECT_EQ(c["unit"], b0.units[k]);
    EXPECT_EQ(c["configured_expanded"].get<double>(), b0.expanded_uncertainty[Eigen::Index(k)] * f);
    EXPECT_EQ(c["designed_tolerance_expanded"].get<double>(), r.tolerance_after[Eigen::Index(k)] * f);
    EXPECT_EQ(c["reference"].get<double>(), r.targets[k].reference * f);
  }
  ASSERT_EQ(j["tradeoff"].size(), 2u);
  EXPECT_EQ(j["tradeoff"][1]["total_time_s"].get<double>(), r.space.total_time);
  ASSERT_TRUE(r.verification);
  EXPECT_EQ(j["verification"]["trials"], 300);
  EXPECT_EQ(j["verification"][b0.coefficients[0]]["mc_std_uncertainty"].get<double>(),
            r.verification->monte_carlo.outputs[0].std_dev * r.after.budget.display_scale[0]);
  EXPECT_EQ(j["search"]["best_start"], r.search.start + 1);
  // The CSV: the run sheet, a header and one line per run.
  const auto rows = test::rendered_lines(render::csv(r));
  EXPECT_EQ(rows.size(), 1 + r.designed.plan.runs.size());
  EXPECT_EQ(rows[0].rfind("order,run,g_level_g,main_speed_rpm,", 0), 0u) << rows[0];
  // The mounting's axes are quoted (they hold commas): the last field of each run line.
  EXPECT_TRUE(rows[1].ends_with(",ia_horizontal,\"IA = x5, PA = y5, OA = z5\"")) << rows[1];
  EXPECT_EQ(test::csv_fields(rows[1]).at(1), r.designed.plan.runs[0].name);
}

}  // namespace design_render_test
}  // namespace ccal
