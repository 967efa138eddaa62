// `ccal identify` on the command line (docs/cli.md): a fit without degrees of freedom reports its standard
// errors as undefined in every format and warns on standard error (the CSV has no place for a warning), and
// --known refuses the output column and a column listed twice.
#include <string>

#include "cli_support.hpp"

namespace ccal::test {
namespace {

class IdentifyCli : public Cli {};

TEST_F(IdentifyCli, NoDegreesOfFreedomPrintsUndefinedStandardErrors) {
  // Two rows, two free terms: s² = RSS/dof is 0/0. A 0 would claim exact coefficients.
  write("a.csv", "x,y\n1,2\n2,3\n");
  const std::string fit = "identify a.csv --input-column x --output-column y --terms K0,K1";
  const Result csv = run(fit + " --format csv");
  EXPECT_EQ(csv.code, 0) << csv.err;
  EXPECT_EQ(csv.out, "coefficient,unit,value,std_error\nK0,y,1,\nK1,y/x,1,\n");
  EXPECT_NE(csv.err.find("ccal: warning: no degrees of freedom (2 rows, 2 free terms)"), std::string::npos)
      << csv.err;
  const Result json = run(fit + " --format json");
  EXPECT_EQ(json.code, 0) << json.err;
  EXPECT_NE(json.out.find("\"std_error\": null"), std::string::npos) << json.out;
  EXPECT_NE(json.out.find("\"residual_std\": null"), std::string::npos) << json.out;
  EXPECT_NE(json.err.find("ccal: warning: no degrees of freedom"), std::string::npos) << json.err;
  const Result text = run(fit);
  EXPECT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("K0                1         n/a      y"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("reported as 0"), std::string::npos) << text.out;
}

TEST_F(IdentifyCli, KnownRefusesTheOutputColumnAndDuplicates) {
  // --known y subtracts y from itself: every coefficient 0 ± 0 with exit 0 before; --known x,x subtracts x
  // twice, where --terms refuses a duplicate.
  const std::string table = CCAL_SOURCE_DIR + "/examples/xy_sigma.csv";
  const std::string fit = "identify " + quote(table) + " --input-column x --output-column y --terms K0,K1";
  const Result output = run(fit + " --known y");
  EXPECT_EQ(output.code, 2);
  EXPECT_EQ(output.out, "");
  EXPECT_NE(output.err.find("ccal: error: --known: y is the output column (--output-column)"),
            std::string::npos)
      << output.err;
  const Result twice = run(fit + " --known x,x");
  EXPECT_EQ(twice.code, 2);
  EXPECT_NE(twice.err.find("ccal: error: --known: x is listed twice; accepted: each column once"),
            std::string::npos)
      << twice.err;
  EXPECT_EQ(run(fit + " --known x --format csv").code, 0);
}

}  // namespace
}  // namespace ccal::test
