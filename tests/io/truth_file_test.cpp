// The simulation's truth file (io/truth_file.hpp): one [errors] table read against a configuration's layout, as
// a configuration's [errors] is (the same ids, units and refusals), and nothing else.
#include "ccal/io/truth_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <numbers>
#include <string>

#include "ccal/core/sha256.hpp"
#include "ccal/model/error_sources.hpp"

namespace ccal {
namespace {

std::string truth_refusal(const std::string& text) {
  try {
    parse_truth(text, "truth.toml", bundled_example());
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(TruthFile, ItsErrorsAreInSiByTheConfigurationsLayoutAndTheRestZero) {
  const Config config = bundled_example();
  const std::string text = "# the machine\n[errors]\ndthz5 = \"2 arcsec\"\ndx3_c1 = \"5 um\"\n";
  const SimulationTruth t = parse_truth(text, "truth.toml", config);
  EXPECT_EQ(t.source, "truth.toml");
  EXPECT_EQ(t.text_sha256, sha256_hex(text));
  ASSERT_EQ(t.errors.size(), config.centrifuge.errors.size());
  const ErrorLayout& layout = config.centrifuge.layout;
  // 2 arcsec = 2π/(180·3600)·2 rad, one product: 1e-18 rad (the double's spacing near 1e-5 is 1.7e-21).
  EXPECT_NEAR(t.errors[*layout.find_parameter("dthz5")], 2 * std::numbers::pi / (180 * 3600), 1e-18);
  EXPECT_NEAR(t.errors[*layout.find_parameter("dx3_c1")], 5e-6, 1e-21);
  EXPECT_EQ((t.errors.array() != 0.0).count(), 2);
  // An empty [errors] table: a machine without errors. No table at all (an empty file) is refused: it would
  // simulate that machine unasked.
  EXPECT_EQ((parse_truth("[errors]\n", "empty.toml", config).errors.array() != 0.0).count(), 0);
  EXPECT_THROW(parse_truth("", "empty.toml", config), InputError);
}

TEST(TruthFile, AnythingButTheMachinesErrorsIsRefusedWithItsPlace) {
  EXPECT_EQ(
      truth_refusal("[centrifuge]\nradius = \"2 m\"\n"),
      "truth.toml:1:2: centrifuge: a configuration's table, not a truth's; accepted: [errors] only, the "
      "values the simulated machine has (the rest of the set-up is the configuration's)");
  EXPECT_EQ(truth_refusal("[eror]\n").rfind("truth.toml:1:2: eror: unknown key; did you mean 'errors'?", 0),
            0u)
      << truth_refusal("[eror]\n");
  const std::string unknown = truth_refusal("[errors]\ndthz6 = \"2 arcsec\"\n");
  EXPECT_EQ(unknown.rfind("truth.toml:2:1: errors.dthz6: unknown error parameter; did you mean 'dthz5'?", 0), 0u)
      << unknown;
  const std::string unit = truth_refusal("[errors]\ndthz5 = \"2 um\"\n");
  EXPECT_EQ(unit.rfind("truth.toml:2:9: errors.dthz5: ", 0), 0u) << unit;
  EXPECT_NE(truth_refusal("[errors\n").find("TOML syntax error"), std::string::npos);
}

TEST(TruthFile, AFileThatCannotBeReadIsRefusedNamingIt) {
  try {
    load_truth(std::filesystem::path("no/such/truth.toml"), bundled_example());
    FAIL() << "a missing file was read";
  } catch (const ConfigError& e) {
    EXPECT_EQ(
        std::string(e.what()),
        "no/such/truth.toml: cannot read the file: no such file; accepted: the path of an existing file "
        "(check its spelling and folder)");
  }
}

}  // namespace
}  // namespace ccal
