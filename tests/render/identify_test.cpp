// `ccal identify` as read (render/identify.hpp, with the fit's parts of render/parts.cpp), on results of
// verbs::identify: the heading names what was fitted on what (the subtracted columns, the weights), undefined
// statistics at zero degrees of freedom read "n/a" (an empty CSV cell), never 0, a weighted fit's residual is
// normalised by sigma, and with the statement the CSV gains its columns to 17 digits.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "ccal/core/format.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/render/identify.hpp"
#include "ccal/verbs/identify.hpp"
#include "ccal/verbs/simulate.hpp"
#include "render_support.hpp"
#include "verbs_support.hpp"

namespace ccal {
namespace identify_render_test {

using test::line_starting;
using test::table_cells;

verbs::IdentifyOptions xy_options(std::vector<std::string> terms) {
  verbs::IdentifyOptions o;
  o.terms = std::move(terms);
  o.input_column = std::string("x");
  o.output_column = std::string("y");
  return o;
}

TEST(IdentifyText, NoDegreesOfFreedomReadsNotApplicableNeverZero) {
  // Two points, two free terms: s = sqrt(RSS/dof) is 0/0, so the unweighted standard errors are undefined.
  const verbs::IdentifyResult r = verbs::identify(parse_csv("x,y\n1,2\n2,3\n", "two.csv"), xy_options({"K0", "K1"}));
  const std::string text = render::text(r);
  EXPECT_EQ(text.rfind("ccal identify: two.csv, 2 rows; y fitted on K0, K1\n\n", 0), 0u) << text;
  // The units are the columns' names: y, and y/x per power of x.
  EXPECT_EQ(table_cells(*line_starting(text, "K0 ")), (std::vector<std::string>{"K0", "1", "n/a", "y"}));
  EXPECT_EQ(table_cells(*line_starting(text, "K1 ")), (std::vector<std::string>{"K1", "1", "n/a", "y/x"}));
  EXPECT_EQ(table_cells(*line_starting(text, "chi2/dof")).back(), "n/a");
  EXPECT_EQ(table_cells(*line_starting(text, "residual std")).back(), "n/a");
  EXPECT_EQ(table_cells(*line_starting(text, "degrees of freedom")).back(), "0");
  EXPECT_TRUE(line_starting(text, "- no degrees of freedom (2 rows, 2 free terms): ")) << text;
  // The CSV leaves the undefined standard error empty.
  const auto rows = test::rendered_lines(render::csv(r));
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], "coefficient,unit,value,std_error");
  EXPECT_EQ(test::csv_fields(rows[1]).back(), "");
}

TEST(IdentifyText, AWeightedFitSaysSoAndKnownColumnsAreSubtracted) {
  const std::string table = "x,y,s,z\n0.5,2.6,0.01,0.1\n1,3.4,0.02,0.1\n2,5.6,0.01,0.1\n3,7.4,0.03,0.1\n";
  verbs::IdentifyOptions o = xy_options({"K0", "K1"});
  o.weight_column = "s";
  o.known = std::vector<std::string>{"z"};
  const verbs::IdentifyResult r = verbs::identify(parse_csv(table, "w.csv"), o);
  const std::string text = render::text(r);
  EXPECT_EQ(text.rfind("ccal identify: w.csv, 4 rows; y - z fitted on K0, K1 (weights 1/s^2)\n\n", 0), 0u)
      << text;
  EXPECT_TRUE(line_starting(text, "residual std (normalised by sigma)")) << text;
  EXPECT_TRUE(line_starting(text, "known contributions subtracted from the output: z")) << text;
  // Values to 12 significant digits, standard errors to 3.
  const auto k1 = table_cells(*line_starting(text, "K1 "));
  EXPECT_EQ(k1[1], number(r.identification.fit.value[1], 12));
  EXPECT_EQ(k1[2], number(r.identification.fit.std_error[1], 3));
}

TEST(IdentifyCsv, TheStatementsColumnsFollowTheFitsToSeventeenDigits) {
  const Config paper = load_config(test::kPaperConfigPath);
  const verbs::SimulateResult sim = verbs::simulate(paper);
  verbs::IdentifyOptions o;
  o.statement = true;
  o.statement_options.statement_trials = 0;
  o.config = paper;
  const verbs::IdentifyResult r = verbs::identify(parse_csv(sim.observations_csv, "obs.csv"), o);
  ASSERT_TRUE(r.statement);
  const auto rows = test::rendered_lines(render::csv(r));
  ASSERT_EQ(rows.size(), 1 + r.identification.fit.names.size());
  EXPECT_EQ(rows[0], "coefficient,unit,value,std_error,correction,corrected,u_a,dof_a,u_b,u_c,nu_eff,"
                     "coverage_probability,k,expanded,low,high");
  const auto k2 = test::csv_fields(rows[2]);
  ASSERT_EQ(k2.size(), 16u);
  EXPECT_EQ(k2[0], r.identification.fit.names[1]);
  const CoefficientStatement& c = r.statement->coefficients[1];
  EXPECT_EQ(std::stod(k2[13]), c.expanded);  // read back to the same double
  EXPECT_EQ(std::stod(k2[14]), c.low);
  EXPECT_EQ(std::stod(k2[12]), c.coverage_factor);
  // The text gains the statement after the fit.
  const std::string text = render::text(r);
  EXPECT_LT(text.find("degrees of freedom"), text.find("calibration statement"));
}

}  // namespace identify_render_test
}  // namespace ccal
