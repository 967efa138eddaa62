// The calibration statement's Type A part and its table of Type B inputs as read (src/render/statement_inputs.cpp),
// in-process on hand-made statements: each input that acts on a coefficient is a row with its u in the unit it
// was written in and whether this test measured it; an input that acts on none is counted under the table and
// kept in the JSON; the Type A text says which evaluation ran, and charges an excess only when there is one.
#include <gtest/gtest.h>

#include <string>

#include "../src/render/statement_part.hpp"
#include "render_support.hpp"

namespace ccal {
namespace statement_inputs_test {

using test::line_starting;
using test::table_cells;

// Two coefficients (u_c 1e-3 and 2e-4) and three inputs: a tilt written in arcsec and measured by the test, a
// radius error from its tolerance in µm, and one whose effects are below the round-off floor (1e-12 u_c).
verbs::CalibrationStatement statement() {
  verbs::CalibrationStatement st;
  for (const auto& [name, u] : {std::pair{"K0", 1e-3}, std::pair{"K2", 2e-4}}) {
    CoefficientStatement c;
    c.input.coefficient = name;
    c.combined = u;
    st.coefficients.push_back(c);
  }
  const double arcsec = 4.84813681109536e-6;
  st.inputs.push_back({"dthz5", "arcsec", arcsec, 1.5 * arcsec, true, "measured at installation", {2e-4, -3e-5}, ""});
  st.inputs.push_back({"dR_s", "um", 1e-6, 25e-6, false, "tolerance 25 um, normal", {-1e-5, 4e-5}, "radius"});
  st.inputs.push_back({"dx5", "um", 1e-6, 25e-6, false, "tolerance 25 um, normal", {1e-17, -1e-18}, ""});
  st.type_a.dof = 3;
  return st;
}

TEST(StatementInputsText, ActingInputsAreRowsInTheirWrittenUnitsAndTheSilentOneIsCounted) {
  const std::string text = render::inputs_text(statement(), 100);
  const auto tilt = line_starting(text, "dthz5 ");
  ASSERT_TRUE(tilt) << text;
  // u 1.5 in arcsec (not 7.27e-6 rad), measured, then the signed effects on K0 and K2 to 3 digits.
  EXPECT_EQ(table_cells(*tilt), (std::vector<std::string>{"dthz5", "1.5", "arcsec", "measured", "0.0002",
                                                          "-3e-05"}))
      << *tilt;
  const auto radius = line_starting(text, "dR_s ");
  ASSERT_TRUE(radius) << text;
  EXPECT_EQ(table_cells(*radius)[1], "25");
  EXPECT_EQ(table_cells(*radius)[3], "tolerance");
  EXPECT_FALSE(line_starting(text, "dx5 ")) << "an input below the round-off floor is no row\n" << text;
  EXPECT_NE(test::words_of(text).find("1 measured in this test"), std::string::npos) << text;
  EXPECT_NE(test::words_of(text).find("1 more act on no coefficient, listed in the JSON"), std::string::npos)
      << text;
  EXPECT_NE(text.find("u_i(K0)"), std::string::npos) << text;
  EXPECT_NE(text.find("u_i(K2)"), std::string::npos) << text;
}

TEST(StatementInputsText, NoInputsNoTable) {
  verbs::CalibrationStatement st = statement();
  st.inputs.clear();
  EXPECT_EQ(render::inputs_text(st, 100), "");
}

TEST(StatementInputsJson, EveryInputWithItsUInBothUnitsAndItsEffectsByCoefficient) {
  const nlohmann::ordered_json j = render::inputs_json(statement());
  ASSERT_EQ(j.size(), 3u);  // the silent input too
  EXPECT_EQ(j[0]["id"], "dthz5");
  EXPECT_DOUBLE_EQ(j[0]["u"].get<double>(), 1.5);  // u_si / unit_si: exact to round-off
  EXPECT_EQ(j[0]["unit"], "arcsec");
  EXPECT_EQ(j[0]["measured"], true);
  EXPECT_EQ(j[0]["effect"]["K2"].get<double>(), -3e-5);
  EXPECT_EQ(j[1]["group"], "radius");
  EXPECT_EQ(j[2]["id"], "dx5");
}

TEST(StatementTypeA, TheFitsScatterOrTheNoiseModelWithItsResidualCheck) {
  verbs::CalibrationStatement st = statement();
  const std::string scatter = test::words_of(render::type_a_text(st, 100));
  EXPECT_NE(scatter.find("the fit's scatter"), std::string::npos) << scatter;
  EXPECT_NE(scatter.find("nu = n - p = 3"), std::string::npos) << scatter;
  EXPECT_FALSE(render::type_a_json(st).contains("residual_check"));

  st.type_a.from_noise_model = true;
  st.type_a.statistic = 2.5;
  st.type_a.expected = 3;
  st.type_a.p_value = 0.48;
  const std::string explained = test::words_of(render::type_a_text(st, 100));
  EXPECT_NE(explained.find("S = sum r^2/sigma^2 = 2.5, expected 3, p-value 0.48 (3 degrees of freedom)"),
            std::string::npos)
      << explained;
  EXPECT_NE(explained.find("nothing more is charged"), std::string::npos) << explained;

  st.type_a.excess = true;
  st.type_a.excess_variance = 4e-6;  // σ = 2e-3 per run mean
  const std::string excess = test::words_of(render::type_a_text(st, 100));
  EXPECT_NE(excess.find("the excess, 0.002 per run mean (sigma), is charged as Type A with nu = 3"),
            std::string::npos)
      << excess;
  const nlohmann::ordered_json j = render::type_a_json(st);
  EXPECT_EQ(j["residual_check"]["excess"], true);
  EXPECT_EQ(j["residual_check"]["excess_variance"].get<double>(), 4e-6);
}

}  // namespace statement_inputs_test
}  // namespace ccal
