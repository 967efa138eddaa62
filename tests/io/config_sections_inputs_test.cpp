// The measuring chain's inputs in a configuration (docs/config.md): their tolerances in [tolerances] in their
// own units (g in m/s², a fixed term in its unit or relative to its value, an encoder's error as an angle),
// the inputs a lab declares ([[inputs]]), a truth file's errors of the chain, and each misuse refused on its
// line with what is accepted.
#include <fmt/format.h>

#include "ccal/io/truth_file.hpp"
#include "ccal/setup/input_description.hpp"
#include "config_test_support.hpp"

namespace ccal {
namespace {

using namespace config_test;

const std::string kChain = R"(
[tolerances]
g = "0.001 m/s^2"
time_base = "0.1 ppm"
output_gain = { bound = "10 ppm", distribution = "uniform" }
output_offset = "1e-4 deg/s"
K1 = "1 ppm"
encoder1_c1 = { bound = "0.5 arcsec", distribution = "arcsine" }

[[inputs]]
id = "temperature"
description = "the instrument's temperature"
unit = "K"
bound = 0.05
distribution = "uniform"
sensitivity = { K0 = "0.002 deg/s", K2 = "1e-6 deg/s/g^2" }
)";

// The line of `what` in text.
int line_holding(const std::string& text, const std::string& what) {
  return 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(text.find(what)), '\n'));
}

const Tolerance& tolerance(const Config& c, const std::string& id) {
  for (const Tolerance& t : c.tolerances)
    if (t.id == id) return t;
  ADD_FAILURE() << id << " has no tolerance";
  return c.tolerances.front();
}

TEST(ChainInputsTable, EachInputIsReadInItsUnitIntoSI) {
  const Config c = parse_config(kBase + kChain, "case.toml");
  ASSERT_EQ(c.tolerances.size(), 7u);
  EXPECT_EQ(tolerance(c, "g").bound, 0.001);
  EXPECT_EQ(tolerance(c, "g").unit, "m/s^2");
  EXPECT_NEAR(tolerance(c, "time_base").bound, 1e-7, 1e-22);
  EXPECT_EQ(tolerance(c, "output_gain").distribution, Distribution::uniform);
  EXPECT_NEAR(tolerance(c, "output_offset").bound, 1e-4 * kDeg, 1e-20);
  // 1 ppm of the fixed K1 (505.2097 deg/s/g in the default instrument) in its SI unit, rad/s/g.
  EXPECT_NEAR(tolerance(c, "K1").bound, 1e-6 * c.identification.fixed_terms.at("K1"), 1e-18);
  EXPECT_NEAR(tolerance(c, "encoder1_c1").bound, 0.5 / 206264.80624709636, 1e-20);
  // The declared input: its bound in its own unit, its sensitivities in SI per that unit.
  ASSERT_EQ(c.chain.declared.size(), 1u);
  EXPECT_EQ(c.chain.declared[0].unit, "K");
  EXPECT_EQ(tolerance(c, "temperature").bound, 0.05);
  ASSERT_EQ(c.chain.declared[0].sensitivity.size(), 2u);
  EXPECT_NEAR(c.chain.declared[0].sensitivity[0].second, 0.002 * kDeg, 1e-18);
  // The chain's inputs after the centrifuge's, each described in words and units for the tables.
  const InputDescription g = describe_input(c, tolerance(c, "g").parameter);
  EXPECT_EQ(g.si_unit, "m/s^2");
  EXPECT_NE(g.name.find("gravity"), std::string::npos);
  const InputDescription t = describe_input(c, tolerance(c, "temperature").parameter);
  EXPECT_TRUE(t.own_unit);
  EXPECT_EQ(t.display_unit, "K");
}

TEST(ChainInputsTable, MisusesAreRefusedWithWhatIsAccepted) {
  // A free term is identified, not an input.
  expect_appended_error("[tolerances]\nK0 = \"1 ppm\"", "tolerances.K0", {"free term", "fixed term (K1)"});
  // g in the wrong dimension.
  expect_appended_error("[tolerances]\ng = \"1 arcsec\"", "tolerances.g", {"m/s^2"});
  // An encoder harmonic above the harmonic order.
  expect_appended_error("[tolerances]\nencoder3_s2 = \"1 arcsec\"", "tolerances.encoder3_s2",
                        {"harmonic_order = 1"});
  // A chain input in the lab's [errors]: its value is the configuration's.
  expect_appended_error("[errors]\ng = \"0.001 m/s^2\"", "errors.g", {"[site] g", "truth file"});
  // An unknown id names the chain's inputs among the accepted.
  expect_appended_error("[tolerances]\ntimebase = \"1 ppm\"", "tolerances.timebase", {"time_base"});
  // A declared input's bound lives in its [[inputs]] entry.
  const std::string declared = std::string(kChain).replace(kChain.find("K1 = \"1 ppm\""), 0, "temperature = 0.1\n");
  const std::string text = kBase + declared;
  expect_error(text, line_holding(text, "temperature = 0.1"), "tolerances.temperature", {"[[inputs]]"});
  // [[inputs]]: an id that names a modelled input, a sensitivity on no term, no sensitivity at all.
  const std::string named_g =
      kBase + "\n[[inputs]]\nid = \"g\"\nunit = \"K\"\nbound = 1\nsensitivity = { K0 = \"1 deg/s\" }";
  expect_error(named_g, line_holding(named_g, "id = \"g\""), "inputs[1].id", {"names an input ccal models"});
  expect_appended_error("[[inputs]]\nid = \"t\"\nunit = \"K\"\nbound = 1\nsensitivity = { K9 = \"1 deg/s\" }",
                        "inputs[1].sensitivity.K9", {"no term of the instrument"});
}

TEST(ChainInputsTable, StandardGravityIsTheGOfTheCoefficientsWhereTheSiteSaysSo) {
  std::string text = kBase;
  const std::string g = "g = \"9.8 m/s^2\"";
  text.replace(text.find(g), g.size(), g + "\ng_unit = \"standard\"");
  const Config c = parse_config(text, "case.toml");
  EXPECT_EQ(c.site.unit_g, kStandardGravity);
  EXPECT_EQ(c.site.g_unit(), 9.80665);
  EXPECT_EQ(c.instrument.g_symbol, "gn");
  EXPECT_EQ(coefficient_unit(c.instrument.output_unit, "K2", c.instrument.g_symbol), "deg/s/gn^2");
  EXPECT_EQ(parse_config(kBase, "case.toml").site.g_unit(), 9.8);  // the local g by default
  text.replace(text.find("\"standard\""), 10, "\"normal\"");
  expect_error(text, line_holding(text, "g_unit"), "site.g_unit", {"local", "standard"});
}

TEST(ChainInputsTable, ASamplingResistorConvertsACurrentOutputOnly) {
  // [instrument] comes last in these texts, so the offending key is on the last line.
  const Config c = parse_config(kBase + "\n[instrument]\nmodel = \"ieee\"\noutput_unit = \"mA\"\n"
                                         "sampling_resistor = \"250 ohm\"\n[instrument.terms]\nK1 = \"1.3 mA/g\"",
                                "case.toml");
  EXPECT_EQ(c.instrument.sampling_resistor, 250.0);
  expect_appended_error("[instrument]\noutput_unit = \"deg/s\"\nsampling_resistor = \"250 ohm\"",
                        "instrument.sampling_resistor", {"converts a current output", "output_unit = \"mA\""});
  const std::string quartz = "[instrument]\nmodel = \"ieee\"\nterms = { K1 = \"1.3 mA/g\" }\noutput_unit = \"mA\"\n";
  expect_appended_error(quartz + "sampling_resistor = \"250 V\"",
                        "instrument.sampling_resistor", {"ohm"});
  expect_appended_error(quartz + "sampling_resistor = \"-1 ohm\"",
                        "instrument.sampling_resistor", {"must be positive"});
  expect_appended_error("[instrument]\noutput_unit = \"kg\"", "instrument.output_unit", {"a current (mA, uA)"});
}

TEST(ChainInputsTable, ATruthFileSetsTheChainsErrors) {
  const Config c = parse_config(kBase + kChain, "case.toml");
  const SimulationTruth t =
      parse_truth("[errors]\ng = \"-0.0005 m/s^2\"\nK1 = \"0.5 ppm\"\ntemperature = 0.02\n", "truth.toml", c);
  ASSERT_EQ(t.chain_errors.size(), 3u);
  MeasuringChain errors = c.chain;
  errors.errors = t.chain_errors;
  EXPECT_EQ(errors.error(tolerance(c, "g").parameter), -0.0005);
  EXPECT_NEAR(errors.error(tolerance(c, "K1").parameter), 0.5e-6 * c.identification.fixed_terms.at("K1"), 1e-18);
  EXPECT_EQ(errors.error(tolerance(c, "temperature").parameter), 0.02);
  EXPECT_EQ((t.errors.array() != 0.0).count(), 0);
}

}  // namespace
}  // namespace ccal
