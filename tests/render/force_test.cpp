// `ccal force` as read (render/force.hpp), on results of verbs::force: the run's figures in their units, the
// joint angles wrapped to [0, 360) degrees, one first-order row per configured error with its value and unit and
// the "(no non-zero [errors])" line only without one, the remainder equal to exact minus first order, and a CSV
// whose 17 digits read back to the result's doubles.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "ccal/core/constants.hpp"
#include "ccal/core/format.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/render/force.hpp"
#include "ccal/verbs/force.hpp"
#include "render_support.hpp"
#include "verbs_support.hpp"

namespace ccal {
namespace force_render_test {

using test::line_starting;
using test::table_cells;

verbs::ForceResult force_at(const Config& config, const std::string& run, double time) {
  verbs::ForceOptions o;
  o.run = run;
  o.time = time;
  return verbs::force(config, o);
}

TEST(ForceText, TheRunsFiguresCarryTheirUnitsAndTheAnglesWrapToOneTurn) {
  // 100 s into run 1 the main axis has turned Omega t = 442.7 rad, 70 turns and more: shown within one turn.
  const verbs::ForceResult r = force_at(bundled_example(), "1", 100);
  const std::string text = render::text(r);
  EXPECT_EQ(text.rfind("ccal force: run 1 of 6, '5g', from bundled:wang_ren_2014.toml\n\n", 0), 0u) << text;
  EXPECT_EQ(table_cells(*line_starting(text, "g-level [g]")).back(), "5");
  EXPECT_EQ(table_cells(*line_starting(text, "main-axis rate Omega [rad/s]")).back(), number(r.input.rate));
  // phi0 in rad with its degrees (6 digits) in brackets.
  EXPECT_EQ(table_cells(*line_starting(text, "initial phase phi0 [rad]")).back(),
            number(r.input.initial_phase) + " (" + number(r.input.initial_phase / constants::deg, 6) + " deg)");
  const auto theta1 = table_cells(*line_starting(text, "main axis theta1"));
  ASSERT_EQ(theta1.size(), 3u);
  const double shown_deg = std::stod(theta1[1]);
  EXPECT_GE(shown_deg, 0.0);
  EXPECT_LT(shown_deg, 360.0);
  // Within the 9 significant digits shown (|angle| < 360 deg: 1e-6 deg).
  EXPECT_NEAR(shown_deg, std::fmod(r.input.joints.theta1 / constants::deg, 360.0), 1e-6);
  // The inertial rate in deg/s, not rad/s.
  const auto rate = table_cells(*line_starting(text, "angular rate [deg/s]"));
  ASSERT_EQ(rate.size(), 4u);
  EXPECT_EQ(rate[1], number(r.input.angular_rate[0] / constants::deg));
}

TEST(ForceText, EachConfiguredErrorHasItsRowAndTheEmptyLineOnlyWithoutOne) {
  const std::string clean = render::text(force_at(bundled_example(), "2", 10));
  EXPECT_TRUE(line_starting(clean, "(no non-zero [errors])").has_value()) << clean;
  const verbs::ForceResult r =
      force_at(parse_config(test::example_with_errors(false), "errors.toml"), "2", 10);
  ASSERT_GE(r.input.contributions.size(), 4u);
  const std::string text = render::text(r);
  EXPECT_FALSE(line_starting(text, "(no non-zero [errors])").has_value()) << text;
  for (const ForceContribution& c : r.input.contributions) {
    const auto row = line_starting(text, c.id + " ");
    ASSERT_TRUE(row) << c.id << "\n" << text;
    const auto cells = table_cells(*row);
    ASSERT_EQ(cells.size(), 5u) << *row;
    EXPECT_EQ(cells[1], number(c.value_si, 6)) << *row;  // the error's value, SI, 6 digits
    EXPECT_EQ(cells[2], c.unit) << *row;
    EXPECT_EQ(cells[4], number(c.w_ia / constants::deg)) << *row;
  }
  const auto remainder = table_cells(*line_starting(text, "remainder (exact - first order)"));
  ASSERT_EQ(remainder.size(), 3u);
  EXPECT_EQ(remainder[1], number(r.input.specific_force[0] - r.input.first_order_f_ia, 6));
  EXPECT_TRUE(line_starting(text, "first order along the IA (exact model)").has_value());
}

TEST(ForceCsv, TheRowsReadBackToTheResultsDoubles) {
  const verbs::ForceResult r =
      force_at(parse_config(test::example_with_errors(false), "errors.toml"), "3", 12.5);
  const auto lines = test::rendered_lines(render::csv(r));
  // header, nominal, one per error, first_order, exact, remainder
  ASSERT_EQ(lines.size(), 5 + r.input.contributions.size());
  EXPECT_EQ(lines[0],
            "row,error_value_si,error_unit,f_IA_g,f_PA_g,f_OA_g,w_IA_deg_per_s,w_PA_deg_per_s,w_OA_deg_per_s");
  const auto exact = test::csv_fields(lines[lines.size() - 2]);
  ASSERT_EQ(exact.size(), 9u);
  EXPECT_EQ(exact[0], "exact");
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_EQ(std::stod(exact[3 + axis]), r.input.specific_force[axis]) << axis;  // 17 digits: exact
    EXPECT_EQ(std::stod(exact[6 + axis]), r.input.angular_rate[axis] / constants::deg) << axis;
  }
  const auto first = test::csv_fields(lines[1]);
  EXPECT_EQ(first[0], "nominal");
  const auto error = test::csv_fields(lines[2]);
  EXPECT_EQ(error[0], r.input.contributions[0].id);
  EXPECT_EQ(std::stod(error[1]), r.input.contributions[0].value_si);
  EXPECT_EQ(std::stod(error[3]), r.input.contributions[0].f_ia);  // 17 digits on every row
}

TEST(ForceJson, RatesInDegreesPerSecondAndOneEntryPerError) {
  const verbs::ForceResult r =
      force_at(parse_config(test::example_with_errors(false), "errors.toml"), "2", 10);
  const auto j = nlohmann::json::parse(render::json(r));
  EXPECT_EQ(j["command"], "force");
  EXPECT_EQ(j["run"]["index"], 2);
  EXPECT_EQ(j["angular_rate_deg_per_s"]["PA"].get<double>(), r.input.angular_rate[1] / constants::deg);
  ASSERT_EQ(j["contributions"].size(), r.input.contributions.size());
  EXPECT_EQ(j["contributions"][0]["id"], r.input.contributions[0].id);
  EXPECT_EQ(j["first_order"]["remainder"]["f_IA_g"].get<double>(), r.input.remainder_f_ia());
}

}  // namespace force_render_test
}  // namespace ccal
