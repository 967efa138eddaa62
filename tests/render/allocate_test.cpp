// `ccal allocate` as read (render/allocate.hpp), on results of verbs::allocate: the coefficients' table with
// the targets' verdicts and the held ones, the allocated tolerances as [tolerances] entries rounded down (never
// looser than allocated), the warning naming a coefficient that grew under --let-others-grow, and a JSON whose
// verification part is there only when the Monte Carlo ran.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "ccal/core/format.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/render/allocate.hpp"
#include "ccal/verbs/allocate.hpp"
#include "render_support.hpp"

namespace ccal {
namespace allocate_render_test {

using test::line_starting;
using test::table_cells;

verbs::AllocateResult allocation(bool let_others_grow, std::uint64_t verify_trials) {
  AllocateOptions o;
  o.targets = {"K2=2e-5", "K3=2e-3"};
  o.let_others_grow = let_others_grow;
  o.verify_trials = verify_trials;
  o.threads = 1;
  return verbs::allocate(bundled_example(), o);
}

const AllocatedCoefficient& coefficient(const verbs::AllocateResult& r, const std::string& id) {
  for (const AllocatedCoefficient& c : r.allocation.coefficients)
    if (c.id == id) return c;
  throw std::logic_error("no coefficient " + id);
}

TEST(AllocateText, TargetsAreActiveOrInactiveAndTheOthersHeld) {
  const verbs::AllocateResult r = allocation(false, 0);
  const std::string text = render::text(r);
  const AllocatedCoefficient& k2 = coefficient(r, "K2");
  const auto row = table_cells(*line_starting(text, "K2 [deg/s/g^2]"));
  ASSERT_GE(row.size(), 6u) << text;
  EXPECT_EQ(row[1], number(k2.target * k2.display_scale, 4));
  EXPECT_EQ(row[3], number(k2.allocated_expanded * k2.display_scale, 6));
  EXPECT_EQ(row[5], k2.active ? "active" : "inactive");
  // K0 has no target: a dash, and "held" at its configured U.
  const auto k0 = table_cells(*line_starting(text, "K0 [deg/s]"));
  ASSERT_GE(k0.size(), 6u) << text;
  EXPECT_EQ(k0[1], "-");
  EXPECT_EQ(k0[5], "held");
  EXPECT_TRUE(line_starting(text, "Coefficients without a target are held at their configured U")) << text;
}

TEST(AllocateText, TheEntriesToPasteAreRoundedDownNeverLooser) {
  const verbs::AllocateResult r = allocation(false, 0);
  const std::string text = render::text(r);
  const auto at = text.find("Allocated [tolerances] in configuration style (bounds rounded down to 4 digits):");
  ASSERT_NE(at, std::string::npos) << text;
  // Every source written in rad or rad/s (SI: the pasted figure is the bound itself) is pasted rounded down
  // to 4 significant digits, on the grid 10^(floor(log10 v) - 3); at least one of them has a fifth digit of 5
  // or more, where rounding to nearest would differ.
  std::size_t checked = 0, differs_from_nearest = 0;
  for (const AllocatedSource& s : r.allocation.sources) {
    const auto entry = line_starting(text.substr(at), s.id + " = ");
    ASSERT_TRUE(entry) << s.id;
    const auto quote = entry->find('"');
    const auto space = entry->find(' ', quote);
    const std::string unit = entry->substr(space + 1, entry->find('"', space) - space - 1);
    if (unit != "rad" && unit != "rad/s") continue;
    const double pasted = std::stod(entry->substr(quote + 1)), v = s.allocated_bound;
    EXPECT_LE(pasted, v) << *entry;
    // Tolerance 1e-12 relative: the text's decimal against the same grid point computed here.
    const double step = std::pow(10.0, std::floor(std::log10(v)) - 3);
    EXPECT_NEAR(pasted, std::floor(v / step) * step, 1e-12 * pasted) << *entry;
    ++checked;
    differs_from_nearest += std::round(v / step) != std::floor(v / step);
  }
  EXPECT_GE(checked, 5u);
  EXPECT_GE(differs_from_nearest, 1u);
  // An arcsine source keeps its distribution in the entry.
  EXPECT_TRUE(line_starting(text.substr(at), "ripple1_c1 = { bound = \"")) << text.substr(at);
  EXPECT_NE(line_starting(text.substr(at), "ripple1_c1 = ")->find("distribution = \"arcsine\""), std::string::npos);
}

TEST(AllocateText, ACoefficientThatGrewIsNamedInAWarning) {
  const verbs::AllocateResult r = allocation(true, 0);
  const std::string text = render::text(r);
  const AllocatedCoefficient& k0 = coefficient(r, "K0");
  if (k0.grew) {
    EXPECT_NE(text.find("WARNING: without a target (--let-others-grow), U grew: K0 from "), std::string::npos)
        << text;
  } else {
    EXPECT_EQ(text.find("WARNING"), std::string::npos) << text;
  }
  EXPECT_EQ(text.find("Coefficients without a target are held"), std::string::npos) << text;
  const auto j = nlohmann::json::parse(render::json(r));
  EXPECT_TRUE(j["let_others_grow"].get<bool>());
  EXPECT_EQ(j["coefficients"]["K0"]["grew"].get<bool>(), k0.grew);
  EXPECT_FALSE(j["coefficients"]["K0"].contains("active"));  // a target's fields only for a target
  EXPECT_TRUE(j["coefficients"]["K2"].contains("active"));
}

TEST(AllocateJson, TheVerificationIsThereOnlyWhenItRan) {
  const auto none = nlohmann::json::parse(render::json(allocation(false, 0)));
  EXPECT_TRUE(none["verification"].is_null());
  EXPECT_FALSE(none["coefficients"]["K2"].contains("mc"));
  const verbs::AllocateResult r = allocation(false, 500);
  const auto j = nlohmann::json::parse(render::json(r));
  EXPECT_EQ(j["verification"]["trials"], 500);
  const AllocatedCoefficient& k2 = coefficient(r, "K2");
  EXPECT_EQ(j["coefficients"]["K2"]["mc"]["std_dev"].get<double>(), k2.mc_std * k2.display_scale);
  EXPECT_TRUE(j["coefficients"]["K2"].contains("verdict"));
  EXPECT_FALSE(j["coefficients"]["K0"].contains("verdict"));  // no target, no verdict
  ASSERT_EQ(j["sources"].size(), r.allocation.sources.size());
  EXPECT_EQ(j["sources"][0]["rank"], 1);
  EXPECT_EQ(j["sources"][0]["id"], r.allocation.sources[0].id);
  EXPECT_EQ(j["targets"], nlohmann::json::array({"K2", "K3"}));
}

}  // namespace allocate_render_test
}  // namespace ccal
