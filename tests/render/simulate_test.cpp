// `ccal simulate` as read (render/simulate.hpp), on results of verbs::simulate: the heading names the machine's
// errors and the noise as simulated (none; N non-zero, compensated or not; the truth file's; one draw of the
// tolerances), the run means' columns carry each regressor's unit and the output's, a test of several
// instruments gives one part per instrument, and its CSV (one table per instrument) is refused naming --format.
#include <gtest/gtest.h>

#include <string>

#include "ccal/core/options.hpp"
#include "ccal/core/format.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/render/simulate.hpp"
#include "ccal/verbs/simulate.hpp"
#include "render_support.hpp"
#include "test_paths.hpp"
#include "verbs_support.hpp"

namespace ccal {
namespace simulate_render_test {

using test::line_starting;
using test::table_cells;

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

TEST(SimulateText, TheHeadingNamesTheErrorsAndTheNoiseAsSimulated) {
  EXPECT_EQ(first_line(render::text(verbs::simulate(bundled_example()))),
            "ccal simulate: 6 runs of bundled:wang_ren_2014.toml; exact model; [errors]: none; noise: none");
  const verbs::SimulateResult uncompensated =
      verbs::simulate(parse_config(test::example_with_errors(false), "errors.toml"));
  EXPECT_EQ(first_line(render::text(uncompensated)),
            "ccal simulate: 6 runs of errors.toml; exact model; [errors]: " +
                std::to_string(uncompensated.error_count) +
                " non-zero, uncompensated (regressors computed without them); noise: none");
  const std::string compensated =
      render::text(verbs::simulate(parse_config(test::example_with_errors(true), "c.toml")));
  EXPECT_NE(first_line(compensated).find("compensated (regressors computed with them)"), std::string::npos);
  // The run means' caption follows: regressors from the [errors] values when compensated, else from zero.
  EXPECT_TRUE(line_starting(compensated, "run means (regressors: the model's, from the [errors] values; "
                                         "output: the exact chain with the [errors] values)"));
  EXPECT_TRUE(line_starting(render::text(uncompensated), "run means (regressors: the model's, from zero errors;"));
}

TEST(SimulateText, ADrawnMachineAndTheNoiseAreStatedWithTheirSeed) {
  const Config lab = load_config(CCAL_SOURCE_DIR + "/examples/lab.toml");
  verbs::SimulateOptions o;
  o.draw_truth = true;
  o.seed = 11;
  const verbs::SimulateResult r = verbs::simulate(lab, o);
  const std::string head = first_line(render::text(r));
  EXPECT_NE(head.find("machine: the [errors] plus one draw of the " + std::to_string(r.drawn.size()) +
                      " [tolerances] inputs (seed 11)"),
            std::string::npos)
      << head;
  // lab.toml: noise_density = 0.0005 deg/s/rtHz, quantum = 1e-4 deg, in the output unit, 6 digits.
  EXPECT_NE(head.find("; noise: white 0.0005 deg/s/rtHz quantum 0.0001 deg/s*s, seed 11"), std::string::npos)
      << head;
}

TEST(SimulateText, TheRunMeansCarryTheirUnitsAndTheOutputTwelveDigits) {
  const verbs::SimulateResult r = verbs::simulate(bundled_example());
  const std::string text = render::text(r);
  const auto header = line_starting(text, "run          <a_i> [g]");
  ASSERT_TRUE(header) << text;
  EXPECT_EQ(table_cells(*header), (std::vector<std::string>{"run", "<a_i> [g]", "K0 [1]", "K1 [g]", "K2 [g^2]",
                                                            "K3 [g^3]", "rate term [deg/s]", "output [deg/s]"}));
  // The run's row of the run means (its first row is in the table of the runs above).
  const auto row = table_cells(*line_starting(text.substr(text.find(*header)), "30g  "));
  ASSERT_EQ(row.size(), 8u);
  EXPECT_EQ(row[7], number(r.observations.output[5] / r.output_unit_si, 12));
  EXPECT_EQ(row[6], number(r.observations.known_rate[5] / r.output_unit_si, 6));
  // The identification of the same observations follows, with its fit statistics.
  EXPECT_TRUE(line_starting(text, "identification of these observations"));
  EXPECT_TRUE(line_starting(text, "degrees of freedom"));
}

TEST(SimulateText, EachInstrumentOfATestHasItsPartAndCsvIsRefused) {
  const Config two = load_config(CCAL_SOURCE_DIR + "/examples/two_instruments.toml");
  const verbs::SimulateResult r = verbs::simulate(two);
  ASSERT_GE(r.instruments.size(), 2u);
  const std::string text = render::text(r);
  EXPECT_EQ(first_line(text), "ccal simulate: a test of " + std::to_string(r.instruments.size()) +
                                  " instruments (" + two.source + ") on one machine");
  for (const verbs::SimulateResult& one : r.instruments)
    EXPECT_EQ(test::lines_holding(text, "=== instrument " + one.config.instrument_id + " ==="), 1u);
  try {
    (void)render::csv(r);
    ADD_FAILURE() << "csv of several instruments";
  } catch (const OptionError& e) {
    EXPECT_NE(std::string(e.what()).find("format"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("instrument"), std::string::npos) << e.what();
  }
  // One instrument: the CSV is the observations file itself.
  const verbs::SimulateResult one = verbs::simulate(bundled_example());
  EXPECT_EQ(render::csv(one), one.observations_csv);
}

}  // namespace simulate_render_test
}  // namespace ccal
