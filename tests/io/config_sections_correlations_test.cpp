// [[correlations]] (docs/config.md): pairs read as written, and each bad entry refused on its line naming the
// key and what is accepted: an unknown id, a source paired with itself, r outside [−1, 1], a pair given
// twice, a pair already in one group, and pairs that together no joint distribution has.
#include <fmt/format.h>

#include "config_test_support.hpp"

namespace ccal {
namespace {

using namespace config_test;

const std::string kTolerances = R"(
[tolerances]
dthy4 = "1 arcsec"
dthy5 = "1 arcsec"
dR_s = { bound = "25 um", group = "survey" }
dthz5 = { bound = "2 arcsec", group = "survey" }
)";

std::string with(const std::string& entries) { return kBase + kTolerances + entries; }

std::string pair(const std::string& a, const std::string& b, const std::string& r) {
  return fmt::format("\n[[correlations]]\nbetween = [\"{}\", \"{}\"]\nr = {}\n", a, b, r);
}

// The line of the n-th occurrence (1-based) of `what` in text.
int line_of(const std::string& text, const std::string& what, int n = 1) {
  std::size_t at = 0;
  for (int i = 0; i < n; ++i) at = text.find(what, i ? at + 1 : 0);
  return 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n'));
}

TEST(CorrelationsTable, PairsAreReadAsWritten) {
  EXPECT_TRUE(parse_config(with(""), "case.toml").correlations.empty());
  const Config c =
      parse_config(with(pair("dthy4", "dthy5", "0.6") + pair("dthz5", "dthy4", "-0.25")), "case.toml");
  ASSERT_EQ(c.correlations.size(), 2u);
  EXPECT_EQ(c.correlations[0].first, "dthy4");
  EXPECT_EQ(c.correlations[0].second, "dthy5");
  EXPECT_EQ(c.correlations[0].r, 0.6);
  EXPECT_EQ(c.correlations[1].first, "dthz5");
  EXPECT_EQ(c.correlations[1].r, -0.25);
}

TEST(CorrelationsTable, EachBadEntryIsRefusedOnItsLine) {
  const std::string unknown = with(pair("dthy4", "dthy6", "0.5"));
  expect_error(unknown, line_of(unknown, "between"), "correlations[1].between",
               {"'dthy6' has no tolerance; accepted: a source of [tolerances] (did you mean 'dthy4'?)"});
  const std::string self = with(pair("dthy4", "dthy4", "0.5"));
  expect_error(self, line_of(self, "between"), "correlations[1].between",
               {"'dthy4' twice", "accepted: two different sources"});
  const std::string big = with(pair("dthy4", "dthy5", "1.5"));
  expect_error(big, line_of(big, "r = 1.5"), "correlations[1].r",
               {"1.5 is not a correlation coefficient; accepted: a number from -1 to 1"});
  // The value as typed, not rounded to "1" (which would be accepted).
  const std::string barely = with(pair("dthy4", "dthy5", "1.0000001"));
  expect_error(barely, line_of(barely, "r = 1.0000001"), "correlations[1].r",
               {"1.0000001 is not a correlation coefficient"});
  const std::string twice = with(pair("dthy4", "dthy5", "0.5") + pair("dthy5", "dthy4", "0.4"));
  expect_error(twice, line_of(twice, "between", 2), "correlations[2].between",
               {"the pair dthy5, dthy4 is given twice (first at line " +
                std::to_string(line_of(twice, "[[correlations]]")) + "); accepted: each pair once"});
  const std::string grouped = with(pair("dR_s", "dthz5", "0.5"));
  expect_error(grouped, line_of(grouped, "between"), "correlations[1].between",
               {"dR_s and dthz5 are both in group \"survey\"", "accepted: the pair here or in one group"});
  // A pair with a grouped source stands for the whole group: another member paired with the same source is
  // the same pair again.
  const std::string via_group = with(pair("dthy4", "dR_s", "0.5") + pair("dthz5", "dthy4", "0.2"));
  expect_error(via_group, line_of(via_group, "between", 2), "correlations[2].between",
               {"the pair dthz5, dthy4 is given twice (first at line " +
                std::to_string(line_of(via_group, "[[correlations]]")) +
                ", a group standing for all its members); accepted: each pair once"});
  const std::string missing = with("\n[[correlations]]\nbetween = [\"dthy4\", \"dthy5\"]\n");
  expect_error(missing, line_of(missing, "[[correlations]]"), "correlations[1].r",
               {"missing; give the correlation coefficient, e.g. r = 0.6"});
  const std::string three = with("\n[[correlations]]\nbetween = [\"dthy4\"]\nr = 0.5\n");
  expect_error(three, line_of(three, "between"), "correlations[1].between",
               {"expected two parameter ids with a tolerance"});
  const std::string table = with("\n[correlations]\nr = 0.5\n");
  expect_error(table, line_of(table, "[correlations]"), "correlations", {"expected an array of tables"});
  const std::string key = with("\n[[correlations]]\nbetween = [\"dthy4\", \"dthy5\"]\nrho = 0.5\n");
  expect_error(key, line_of(key, "rho"), "correlations[1].rho", {"unknown key"});
}

TEST(CorrelationsTable, PairsNoDistributionHasAreRefusedAsAWhole) {
  // dthy4–dthy5 0.9, dthy4–dR_s 0.9, dthy5–dR_s −0.9: each pair is fine, the three are not (eigenvalue −0.8).
  // dthz5 moves with dR_s (their group), so it is in the offending direction too.
  const std::string text =
      with(pair("dthy4", "dthy5", "0.9") + pair("dthy4", "dR_s", "0.9") + pair("dthy5", "dR_s", "-0.9"));
  expect_error(text, line_of(text, "[[correlations]]"), "correlations",
               {"are not those of any joint distribution: the matrix is not positive semi-definite (smallest "
                "eigenvalue ",
                "along dR_s, dthy4, dthy5, dthz5", "accepted: a matrix whose eigenvalues are all >= 0"});
  // The same with |r| = 0.4 is a correlation matrix.
  EXPECT_NO_THROW(parse_config(
      with(pair("dthy4", "dthy5", "0.4") + pair("dthy4", "dR_s", "0.4") + pair("dthy5", "dR_s", "-0.4")),
      "case.toml"));
}

}  // namespace
}  // namespace ccal
