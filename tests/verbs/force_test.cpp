// verbs::force in-process (docs/cli.md `ccal force`, docs/model.md §4–5): the sensed input of an error-free
// centrifuge against its closed form, the first-order contributions of a configured error summing to the
// first-order value with a remainder of second order, and the run and time refused naming --run and --time.
#include "ccal/verbs/force.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/render/force.hpp"
#include "verbs_support.hpp"

namespace ccal::test {
namespace {

std::string without_earth_rotation() {
  return edited(std::string(bundled_example_text()), "earth_rotation = true", "earth_rotation = false");
}

TEST(ForceVerb, ErrorFreeInputIsTheClosedFormOfTheCounterRotatingArm) {
  // No errors, no Earth rate: in frame 5 the specific force is f/g = (−A cos γ, A sin γ, 1) with
  // A = Ω² R0 / g the run's g-level and γ = φ0 − Ω t on the counter-rotating platform (tests/model/
  // plan_test.cpp); the IA is x5, the PA y5, the OA z5 (ia_horizontal). The platform does not turn
  // inertially, so the rate about the IA is 0. Tolerance 1e-11 of A: the chain's angles reach Ω t ≈ 1.6e3
  // rad, whose round-off (~2e-13 rad) moves the components by that fraction of A.
  const Config config = parse_config(without_earth_rotation(), "no-earth.toml");
  for (const char* run : {"1", "3", "6"}) {
    for (double t : {0.0, 123.4, 450.0}) {
      verbs::ForceOptions o;
      o.run = run;
      o.time = t;
      const verbs::ForceResult r = verbs::force(config, o);
      const SensedInputBreakdown& in = r.input;
      const double A = in.rate * in.rate * config.centrifuge.geometry.R0 / config.site.g;
      EXPECT_NEAR(A, config.plan.runs[r.run_index].g_level, 1e-12 * A) << run;
      const double gamma = in.initial_phase - in.rate * t;
      SCOPED_TRACE(testing::Message() << "run " << run << ", t = " << t);
      EXPECT_NEAR(in.specific_force[0], -A * std::cos(gamma), 1e-11 * A);
      EXPECT_NEAR(in.specific_force[1], A * std::sin(gamma), 1e-11 * A);
      EXPECT_NEAR(in.specific_force[2], 1.0, 1e-11 * A);
      EXPECT_NEAR(in.angular_rate[0], 0.0, 1e-14 * in.rate);
      // Nothing configured: no contributions, the first-order value is the nominal one and the exact one.
      EXPECT_TRUE(in.contributions.empty());
      EXPECT_EQ(in.first_order_f_ia, in.nominal_f_ia);
      EXPECT_NEAR(in.remainder_f_ia(), 0.0, 1e-11 * A);
    }
  }
}

// The force of run 1 at t = 100 s with the instrument's azimuth zero error dthz5 set to `arcsec`.
SensedInputBreakdown with_azimuth_error(double arcsec) {
  const std::string text =
      edited(without_earth_rotation(), "# dthz5 = \"2 arcsec\"       # instrument azimuth (IA) zero error",
             "dthz5 = \"" + std::to_string(arcsec) + " arcsec\"");
  verbs::ForceOptions o;
  o.time = 100;
  return verbs::force(parse_config(text, "dthz5.toml"), o).input;
}

TEST(ForceVerb, TheRemainderOfTheFirstOrderViewIsOfSecondOrder) {
  // An azimuth error ε turns the IA in the base plane: f_ia = −A cos(γ + ε) exactly, so the first-order
  // contribution is A ε sin γ and the remainder A cos γ · ε²/2 + O(ε³). Ten times the error: the
  // contribution ten times (1e-9 relative, the linearisation is exact), the remainder a hundred times
  // (within 1 %: the third-order term is ε·tan γ ~ 1e-4 of it, the round-off of f ~ 1e-15 A is 1e-5 of it).
  const SensedInputBreakdown small = with_azimuth_error(2), large = with_azimuth_error(20);
  ASSERT_EQ(small.contributions.size(), 1u);
  ASSERT_EQ(large.contributions.size(), 1u);
  EXPECT_EQ(small.contributions[0].id, "dthz5");
  const double eps = 2.0 / 3600 * std::numbers::pi / 180, A = 5;
  const double gamma = small.initial_phase - small.rate * 100;
  EXPECT_NEAR(small.contributions[0].f_ia, A * eps * std::sin(gamma), 1e-9 * A * eps);
  EXPECT_NEAR(large.contributions[0].f_ia, 10 * small.contributions[0].f_ia,
              1e-9 * std::abs(large.contributions[0].f_ia));
  // The sum of the contributions is the first-order value less the nominal one.
  EXPECT_NEAR(small.first_order_f_ia - small.nominal_f_ia, small.contributions[0].f_ia, 1e-14 * A);
  EXPECT_GT(std::abs(small.remainder_f_ia()), 1e-12) << "the remainder must be above the round-off";
  EXPECT_NEAR(small.remainder_f_ia(), A * std::cos(gamma) * eps * eps / 2, 1e-2 * A * eps * eps / 2);
  EXPECT_NEAR(large.remainder_f_ia() / small.remainder_f_ia(), 100.0, 1.0);
}

TEST(ForceVerb, RunAndTimeOutsideThePlanAreRefusedNamingTheOption) {
  const Config config = bundled_example();
  auto message = [&](const std::string& run, double t) -> std::string {
    verbs::ForceOptions o;
    o.run = run;
    o.time = t;
    try {
      verbs::force(config, o);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(message("7", 0).rfind("run: ", 0), 0u) << message("7", 0);
  EXPECT_EQ(message("fast", 0).rfind("run: ", 0), 0u) << message("fast", 0);
  EXPECT_EQ(message("1", 450.5).rfind("time: ", 0), 0u) << message("1", 450.5);
  EXPECT_EQ(message("1", -1).rfind("time: ", 0), 0u) << message("1", -1);
  // By name as by index.
  verbs::ForceOptions by_name;
  by_name.run = "10g";
  EXPECT_EQ(verbs::force(config, by_name).run_index, 1u);
}

// `ccal force --format csv`: the first-order breakdown of IA beside the exact input, each row's numbers those of
// the result to the last bit (17 digits), the sum of the rows the first-order value.
TEST(ForceVerb, CsvIsTheBreakdownWithEveryDigit) {
  verbs::ForceOptions o;
  o.time = 100;
  const verbs::ForceResult r =
      verbs::force(parse_config(edited(without_earth_rotation(), "# dthz5 = \"2 arcsec\"       # instrument azimuth "
                                                                 "(IA) zero error",
                                       "dthz5 = \"2 arcsec\""),
                                "dthz5.toml"),
                   o);
  std::istringstream in(render::csv(r));
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::size_t at = 0;
    for (std::size_t comma; (comma = line.find(',', at)) != std::string::npos; at = comma + 1)
      cells.push_back(line.substr(at, comma - at));
    cells.push_back(line.substr(at));
    rows.push_back(cells);
  }
  ASSERT_EQ(rows.size(), 6u);  // header, nominal, dthz5, first_order, exact, remainder
  EXPECT_EQ(rows[0][0], "row");
  EXPECT_EQ(rows[1][0], "nominal");
  EXPECT_EQ(std::stod(rows[1][3]), r.input.nominal_f_ia);
  EXPECT_EQ(rows[2][0], "dthz5");
  EXPECT_EQ(std::stod(rows[2][1]), r.input.contributions[0].value_si);
  EXPECT_EQ(std::stod(rows[2][3]), r.input.contributions[0].f_ia);
  EXPECT_EQ(rows[3][0], "first_order");
  EXPECT_EQ(std::stod(rows[3][3]), r.input.first_order_f_ia);
  EXPECT_EQ(rows[4][0], "exact");
  for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(std::stod(rows[4][std::size_t(3 + axis)]), r.input.specific_force[axis]);
  EXPECT_EQ(rows[5][0], "remainder");
  EXPECT_EQ(std::stod(rows[5][3]), r.input.remainder_f_ia());
  for (const auto& row : rows) EXPECT_EQ(row.size(), 9u) << row[0];
}

}  // namespace
}  // namespace ccal::test
