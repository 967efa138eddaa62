// Configuration loading: the bundled example gives the paper's numbers, units convert, defaults apply.
// (Bad input: config_file_errors_test.cpp.)
#include "ccal/setup/input_description.hpp"
#include "config_test_support.hpp"
#include "test_paths.hpp"

namespace ccal {
namespace {

using namespace config_test;

TEST(Example, HasThePapersSetUp) {
  const Config c = bundled_example();
  EXPECT_EQ(c.source, kBundledExampleName);
  EXPECT_DOUBLE_EQ(c.centrifuge.geometry.R0, 2.5);
  EXPECT_DOUBLE_EQ(c.centrifuge.geometry.L, 0.0);
  EXPECT_DOUBLE_EQ(c.centrifuge.geometry.l, 0.0);
  EXPECT_DOUBLE_EQ(c.centrifuge.geometry.beta, 0.0);
  EXPECT_EQ(c.centrifuge.layout.harmonic_order(), 1);
  EXPECT_TRUE((c.centrifuge.errors.array() == 0.0).all());
  EXPECT_DOUBLE_EQ(c.site.g, 9.8);
  EXPECT_NEAR(c.site.latitude, 45.75 * kDeg, 1e-15);
  EXPECT_TRUE(c.site.earth_rotation);

  ASSERT_EQ(c.plan.runs.size(), 6u);
  const double levels[] = {5, 10, 15, 20, 25, 30};
  for (std::size_t k = 0; k < 6; ++k) {
    const ccal::Run& r = c.plan.runs[k];
    EXPECT_EQ(r.name, std::to_string(int(levels[k])) + "g");
    EXPECT_DOUBLE_EQ(r.g_level, levels[k]);
    EXPECT_DOUBLE_EQ(r.duration, 450.0);
    EXPECT_EQ(r.mode, PlatformMode::counter_rotating);
    ASSERT_TRUE(r.terminal_phase.has_value());
    EXPECT_DOUBLE_EQ(*r.terminal_phase, std::numbers::pi);
    EXPECT_FALSE(r.initial_phase.has_value());
    EXPECT_DOUBLE_EQ(r.arm_azimuth, 0.0);
    EXPECT_EQ(r.mounting, Mounting::ia_horizontal);
  }
  // model.md §6.1 (g = 9.8): φ0 of the six runs.
  const double phi0[] = {3.6068, 5.7202, 4.3250, 4.0720, 3.1359, 1.0656};
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_NEAR(initial_phase(c.plan.runs[k], c.centrifuge.geometry, c.site), phi0[k], 1e-4) << k;

  // The paper's PIGA, in SI (rad/s per g^n).
  EXPECT_EQ(c.instrument.term_ids, (std::vector<std::string>{"K0", "K1", "K2", "K3"}));
  EXPECT_NEAR(*c.instrument.coefficient("K0"), 0.061973 * kDeg, 1e-15);
  EXPECT_NEAR(*c.instrument.coefficient("K1"), 505.2097 * kDeg, 1e-12);
  EXPECT_NEAR(*c.instrument.coefficient("K2"), 0.02 * kDeg, 1e-16);
  EXPECT_NEAR(*c.instrument.coefficient("K3"), 0.003 * kDeg, 1e-17);
  EXPECT_DOUBLE_EQ(c.instrument.rate_gain, 1.0);
}

TEST(Example, TolerancesCoverEveryStaticChannelAndFirstHarmonic) {
  const Config c = bundled_example();
  EXPECT_GE(c.tolerances.size(), 40u);
  auto find = [&](std::string_view id) -> const Tolerance* {
    for (const auto& t : c.tolerances)
      if (t.id == id) return &t;
    return nullptr;
  };
  for (int ch = 0; ch < kChannelCount; ++ch) {
    const Channel& channel = channels()[ch];
    if (channel.joint == Joint::none) {
      EXPECT_NE(find(channel.id), nullptr) << channel.id;
      continue;
    }
    for (const char* suffix : {"_c1", "_s1"}) {
      const std::string id = std::string(channel.id) + suffix;
      const Tolerance* t = find(id);
      ASSERT_NE(t, nullptr) << id;
      EXPECT_EQ(t->distribution, Distribution::arcsine) << id;
    }
  }
  // Ordered as the catalogue, each pointing at its own parameter.
  for (std::size_t k = 0; k < c.tolerances.size(); ++k) {
    EXPECT_EQ(describe_input(c, c.tolerances[k].parameter).id, c.tolerances[k].id);
    if (k > 0) {
      EXPECT_LT(c.tolerances[k - 1].parameter, c.tolerances[k].parameter);
    }
  }
  EXPECT_DOUBLE_EQ(find("dthz5")->bound, 1e-5);
  EXPECT_EQ(find("dthz5")->distribution, Distribution::normal);
  EXPECT_NEAR(find("dR_s")->bound, 25e-6, 1e-18);  // 1e-5 · R0
  EXPECT_NEAR(find("dx3_c1")->bound, 10e-6, 1e-18);
  EXPECT_NEAR(find("domega")->bound, 0.5e-6, 1e-20);
  EXPECT_NEAR(find("dOmega")->bound, 0.5e-6, 1e-20);
  // Arm stretch: 10 µm at 30 g (Ω² = 30 · 9.8 / 2.5).
  EXPECT_NEAR(find("arm_stretch")->bound * 30 * 9.8 / 2.5, 10e-6, 0.1e-6);
  EXPECT_DOUBLE_EQ(find("dthz5")->cost, 1.0);
  EXPECT_EQ(find("dthz5")->group, "");
}

TEST(Example, FileInExamplesIsTheBundledText) {
  const std::filesystem::path file = std::filesystem::path(CCAL_SOURCE_DIR) / "examples/wang_ren_2014.toml";
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), bundled_example_text());
  const Config c = load_config(file);
  EXPECT_EQ(c.source, file.string());
  EXPECT_EQ(c.plan.runs.size(), 6u);
  EXPECT_EQ(c.tolerances.size(), bundled_example().tolerances.size());
}

// ---------------------------------------------------------------------------------------------------------
// Units, defaults, and the values of every section

TEST(Config, ConvertsUnitsToSiInEverySection) {
  const Config c = parse_config(R"toml([site]
latitude = "0.5 rad"
g = "9810 mm/s^2"
height = "0.1 km"
earth_rotation = false
[centrifuge]
radius = "1250 mm"
base_plane_height = "200 mm"
instrument_height = "5e4 um"
horizontal_axis_angle = "30 arcmin"
harmonic_order = 2
[errors]
dthz5 = "2 arcsec"
dx3_c1 = "5 um"
dthy3_s2 = "-3 urad"
domega = "1 deg/h"
arm_stretch = "1e-7 m/(rad/s)^2"
[instrument]
output_unit = "rad/s"
[instrument.terms]
K1 = "8.8 rad/s/g"
K3 = "0.003 deg/s/g^3"
[plan]
duration = "7.5 min"
initial_phase = "90 deg"
arm_azimuth = "1 rad"
[[plan.runs]]
g_level = "3000 mg"
)toml",
                                "x.toml");
  EXPECT_DOUBLE_EQ(c.site.latitude, 0.5);
  EXPECT_NEAR(c.site.g, 9.81, 1e-14);
  EXPECT_FALSE(c.site.earth_rotation);
  EXPECT_NEAR(c.centrifuge.geometry.R0, 1.25, 1e-15);
  EXPECT_NEAR(c.centrifuge.geometry.L, 0.2, 1e-15);
  EXPECT_NEAR(c.centrifuge.geometry.l, 0.05, 1e-15);
  EXPECT_NEAR(c.centrifuge.geometry.beta, 0.5 * kDeg, 1e-15);
  EXPECT_EQ(c.centrifuge.layout.harmonic_order(), 2);
  EXPECT_NEAR(c.centrifuge.error("dthz5"), 2 * constants::arcsec, 1e-20);
  EXPECT_NEAR(c.centrifuge.error("dx3_c1"), 5e-6, 1e-20);
  EXPECT_NEAR(c.centrifuge.error("dthy3_s2"), -3e-6, 1e-20);
  EXPECT_NEAR(c.centrifuge.error("domega"), kDeg / 3600, 1e-20);
  EXPECT_NEAR(c.centrifuge.error("arm_stretch"), 1e-7, 1e-22);
  EXPECT_EQ(c.instrument.output_unit, "rad/s");
  EXPECT_EQ(c.instrument.term_ids, (std::vector<std::string>{"K1", "K3"}));
  EXPECT_NEAR(*c.instrument.coefficient("K1"), 8.8, 1e-15);
  EXPECT_NEAR(*c.instrument.coefficient("K3"), 0.003 * kDeg, 1e-18);
  ASSERT_EQ(c.plan.runs.size(), 1u);
  const ccal::Run& r = c.plan.runs[0];
  EXPECT_NEAR(r.g_level, 3.0, 1e-15);
  EXPECT_DOUBLE_EQ(r.duration, 450.0);
  EXPECT_NEAR(*r.initial_phase, std::numbers::pi / 2, 1e-15);
  EXPECT_FALSE(r.terminal_phase);
  EXPECT_DOUBLE_EQ(r.arm_azimuth, 1.0);
}

TEST(Config, Defaults) {
  const Config c = parse_config(R"([site]
latitude = "30 deg"
[centrifuge]
radius = "2 m"
[[plan.runs]]
g_level = "5 g"
duration = "100 s"
terminal_phase = "0 deg"
[[plan.runs]]
g_level = "6 g"
duration = "100 s"
initial_phase = "0 deg"
)",
                                "d.toml");
  // Normal gravity at 30° from WGS-84's published γe, γp and semi-axes by Somigliana's formula (written out
  // in tests/model/site_test.cpp): 9.7932472692 m/s². Tolerance 1e-9 m/s²: ten-digit constants.
  EXPECT_NEAR(c.site.g, 9.7932472692, 1e-9);
  EXPECT_TRUE(c.site.earth_rotation);
  EXPECT_DOUBLE_EQ(c.centrifuge.geometry.L, 0.0);
  EXPECT_DOUBLE_EQ(c.centrifuge.geometry.l, 0.0);
  EXPECT_DOUBLE_EQ(c.centrifuge.geometry.beta, 0.0);
  EXPECT_EQ(c.centrifuge.layout.harmonic_order(), 1);
  EXPECT_TRUE((c.centrifuge.errors.array() == 0.0).all());
  EXPECT_TRUE(c.tolerances.empty());
  // No [instrument]: the paper's PIGA.
  const InstrumentModel piga = paper_piga();
  EXPECT_EQ(c.instrument.term_ids, piga.term_ids);
  EXPECT_TRUE(c.instrument.coefficients.isApprox(piga.coefficients));
  EXPECT_EQ(c.instrument.rate_gain, 1.0);
  EXPECT_EQ(c.instrument.noise_density, 0.0);
  EXPECT_EQ(c.instrument.quantum, 0.0);
  // Run names, platform, mounting and azimuth.
  ASSERT_EQ(c.plan.runs.size(), 2u);
  EXPECT_EQ(c.plan.runs[0].name, "run1");
  EXPECT_EQ(c.plan.runs[1].name, "run2");
  for (const ccal::Run& r : c.plan.runs) {
    EXPECT_EQ(r.mode, PlatformMode::counter_rotating);
    EXPECT_EQ(r.mounting, Mounting::ia_horizontal);
    EXPECT_EQ(r.arm_azimuth, 0.0);
  }
  // A given g overrides normal gravity; height lowers normal gravity.
  const Config h = parse_config(R"([site]
latitude = "30 deg"
height = "1000 m"
[centrifuge]
radius = "2 m"
[[plan.runs]]
g_level = "5 g"
duration = "100 s"
terminal_phase = "0 deg"
)",
                                "h.toml");
  // 1000 m lowers it by the free-air gradient 3.086e-6 s⁻²/m (model.md §1): 3.086e-3 m/s².
  EXPECT_NEAR(h.site.g, 9.7932472692 - 3.086e-3, 1e-9);
  EXPECT_LT(h.site.g, c.site.g);
}

TEST(Config, RunValuesOverridePlanDefaults) {
  const Config c = parse_config(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
duration = "450 s"
terminal_phase = "180 deg"
platform = "fixed"
mounting = "ia_reversed"
arm_azimuth = "10 deg"
[[plan.runs]]
name = "plain"
g_level = "5 g"
[[plan.runs]]
name = "own"
g_level = "10 g"
duration = "60 s"
initial_phase = "30 deg"
platform = "counter_rotating"
mounting = "pa_vertical"
arm_azimuth = "20 deg"
[[plan.runs]]
name = "vertical"
g_level = "1 g"
mounting = "ia_vertical"
)",
                                "o.toml");
  const ccal::Run& a = c.plan.runs[0];
  EXPECT_DOUBLE_EQ(a.duration, 450.0);
  EXPECT_DOUBLE_EQ(*a.terminal_phase, std::numbers::pi);
  EXPECT_FALSE(a.initial_phase);
  EXPECT_EQ(a.mode, PlatformMode::fixed);
  EXPECT_EQ(a.mounting, Mounting::ia_reversed);
  EXPECT_NEAR(a.arm_azimuth, 10 * kDeg, 1e-15);
  const ccal::Run& b = c.plan.runs[1];
  EXPECT_DOUBLE_EQ(b.duration, 60.0);
  EXPECT_NEAR(*b.initial_phase, 30 * kDeg, 1e-15);
  EXPECT_FALSE(b.terminal_phase);  // the run's initial phase replaces the plan's terminal phase
  EXPECT_EQ(b.mode, PlatformMode::counter_rotating);
  EXPECT_EQ(b.mounting, Mounting::pa_vertical);
  EXPECT_NEAR(b.arm_azimuth, 20 * kDeg, 1e-15);
  EXPECT_EQ(c.plan.runs[2].mounting, Mounting::ia_vertical);
}

TEST(Config, EachDistributionWord) {
  const std::pair<const char*, Distribution> words[] = {{"normal", Distribution::normal},
                                                        {"uniform", Distribution::uniform},
                                                        {"triangular", Distribution::triangular},
                                                        {"arcsine", Distribution::arcsine}};
  for (const auto& [word, d] : words) {
    const Config c = parse_config(kBase + "\n[tolerances]\ndR_s = { bound = \"25 um\", distribution = \"" +
                                      word + "\", group = \"radius\", cost = 2.5 }\n",
                                  "t.toml");
    ASSERT_EQ(c.tolerances.size(), 1u) << word;
    const Tolerance& t = c.tolerances[0];
    EXPECT_EQ(t.distribution, d) << word;
    EXPECT_EQ(distribution_name(d), word);
    EXPECT_EQ(t.id, "dR_s");
    EXPECT_EQ(t.parameter, ch::dR_s);
    EXPECT_NEAR(t.bound, 25e-6, 1e-18);
    EXPECT_EQ(t.group, "radius");
    EXPECT_DOUBLE_EQ(t.cost, 2.5);
  }
  EXPECT_DOUBLE_EQ(standard_uncertainty(1.0, Distribution::normal), 1.0);
  EXPECT_DOUBLE_EQ(standard_uncertainty(1.0, Distribution::uniform), 1.0 / std::sqrt(3.0));
  EXPECT_DOUBLE_EQ(standard_uncertainty(1.0, Distribution::triangular), 1.0 / std::sqrt(6.0));
  EXPECT_DOUBLE_EQ(standard_uncertainty(1.0, Distribution::arcsine), 1.0 / std::sqrt(2.0));
}

// The divisor the budget tables print (GUM 4.3.7, 4.3.9; JCGM 101 6.4.6 for the arcsine) is the one σ is
// computed with: bound / divisor, bit for bit, so the table's u(x_i) is its bound over its divisor.
TEST(Config, DivisorOfEachDistribution) {
  const std::pair<Distribution, double> divisors[] = {{Distribution::normal, 1.0},
                                                      {Distribution::uniform, std::sqrt(3.0)},
                                                      {Distribution::triangular, std::sqrt(6.0)},
                                                      {Distribution::arcsine, std::sqrt(2.0)}};
  for (const auto& [d, want] : divisors) {
    EXPECT_EQ(divisor(d), want) << distribution_name(d);  // the correctly rounded root: exact
    for (const double bound : {1.0, 25e-6, 2 * constants::arcsec, 1e-5})
      EXPECT_EQ(standard_uncertainty(bound, d), bound / divisor(d)) << distribution_name(d);
  }
}

TEST(Config, ToleranceShorthandIsNormalSigma) {
  const Config c =
      parse_config(kBase + "\n[tolerances]\ndthz5 = \"2 arcsec\"\ndomega = \"1e-6 rad/s\"\n", "t.toml");
  ASSERT_EQ(c.tolerances.size(), 2u);
  EXPECT_EQ(c.tolerances[0].id, "dthz5");
  EXPECT_NEAR(c.tolerances[0].bound, 2 * constants::arcsec, 1e-20);
  EXPECT_EQ(c.tolerances[0].distribution, Distribution::normal);
  EXPECT_EQ(c.tolerances[0].cost, 1.0);
  EXPECT_EQ(c.tolerances[1].id, "domega");
}

TEST(Config, IeeeAndPulseInstruments) {
  const Config c = parse_config(kBase + R"toml(
[instrument]
model = "ieee"
noise_density = "10 ug/rtHz"
quantum = "1e-6 g*s"
[instrument.terms]
K_p = "1e-4 g/g"
K0 = "50 ug"
K1 = "1 g/g"
K2 = "20 ug/g^2"
K_w = "0 g/(rad/s)"
)toml",
                                "i.toml");
  EXPECT_EQ(c.instrument.output_unit, "g");
  EXPECT_EQ(c.instrument.rate_gain, 0.0);
  EXPECT_EQ(c.instrument.term_ids, (std::vector<std::string>{"K0", "K1", "K2", "K_p", "K_w"}));
  EXPECT_NEAR(*c.instrument.coefficient("K0"), 50e-6, 1e-18);
  EXPECT_NEAR(*c.instrument.coefficient("K2"), 20e-6, 1e-18);
  EXPECT_NEAR(c.instrument.noise_density, 10e-6, 1e-18);
  EXPECT_NEAR(c.instrument.quantum, 1e-6, 1e-18);

  const Config p = parse_config(kBase + R"(
[instrument]
output_unit = "pulse/s"
rate_gain = 0.5
quantum = "1 pulse"
[instrument.terms]
K1 = "1000 pulse/s/g"
)",
                                "p.toml");
  EXPECT_EQ(p.instrument.output_unit, "pulse/s");
  EXPECT_DOUBLE_EQ(*p.instrument.coefficient("K1"), 1000.0);
  EXPECT_DOUBLE_EQ(p.instrument.rate_gain, 0.5);
  EXPECT_DOUBLE_EQ(p.instrument.quantum, 1.0);
  // A pulse-output instrument's coefficients must be in pulses.
  expect_appended_error("[instrument]\noutput_unit = \"pulse/s\"\n[instrument.terms]\nK1 = \"1000 deg/s/g\"",
                        "instrument.terms.K1", {"pulses", "1 pulse/s/g"});
}

TEST(Config, IdentificationSection) {
  // The example states the paper's choice explicitly; a file without the section gets the same default.
  for (const Config& c : {bundled_example(), parse_config(kBase, "d.toml")}) {
    EXPECT_EQ(c.identification.free_terms, (std::vector<std::string>{"K0", "K2", "K3"})) << c.source;
    ASSERT_EQ(c.identification.fixed_terms.size(), 1u) << c.source;
    EXPECT_EQ(c.identification.fixed_terms.at("K1"), *c.instrument.coefficient("K1"));
    EXPECT_FALSE(c.identification.compensate);
    EXPECT_FALSE(c.identification.paper_cross_terms);
    EXPECT_EQ(c.mode, ModelMode::exact);
  }
  const Config c = parse_config(kBase + R"toml(
[identification]
terms = ["K3", "K0", "K_pp"]
fixed = ["K2", "K1"]
compensate = true
mode = "paper"
paper_cross_terms = true
)toml",
                                "i.toml");
  EXPECT_EQ(c.identification.free_terms, (std::vector<std::string>{"K3", "K0", "K_pp"}));  // order kept
  ASSERT_EQ(c.identification.fixed_terms.size(), 2u);
  EXPECT_NEAR(c.identification.fixed_terms.at("K1"), 505.2097 * kDeg, 1e-12);
  EXPECT_NEAR(c.identification.fixed_terms.at("K2"), 0.02 * kDeg, 1e-16);
  EXPECT_TRUE(c.identification.compensate);
  EXPECT_TRUE(c.identification.paper_cross_terms);
  EXPECT_EQ(c.mode, ModelMode::paper);
  // K1 free: the default holds nothing fixed; fixed = [] holds nothing either.
  const Config k1 =
      parse_config(kBase + "\n[identification]\nterms = [\"K0\", \"K1\", \"K2\", \"K3\"]", "k.toml");
  EXPECT_TRUE(k1.identification.fixed_terms.empty());
  const Config none = parse_config(kBase + "\n[identification]\nfixed = []", "n.toml");
  EXPECT_TRUE(none.identification.fixed_terms.empty());
  EXPECT_EQ(none.identification.free_terms.size(), 3u);
  // An instrument without K1 has no default fixed term.
  const Config ieee =
      parse_config(kBase + "\n[instrument]\nmodel = \"ieee\"\n[instrument.terms]\nK0 = \"1 mg\"", "e.toml");
  EXPECT_TRUE(ieee.identification.fixed_terms.empty());
  // The experiment carries the configuration's parts.
  const Experiment ex = bundled_example().experiment();
  EXPECT_EQ(ex.plan.runs.size(), 6u);
  EXPECT_EQ(ex.instrument.term_ids, bundled_example().instrument.term_ids);
  EXPECT_EQ(ex.layout.size(), bundled_example().centrifuge.layout.size());
}

TEST(Config, SelectRunByNameOrIndex) {
  const Config c = bundled_example();
  EXPECT_EQ(select_run(c.plan, "20g", "--run"), 3u);
  EXPECT_EQ(select_run(c.plan, "1", "--run"), 0u);
  EXPECT_EQ(select_run(c.plan, "6", "--run"), 5u);
  for (const char* bad : {"0", "7", "x", "", "2x", "-1"}) {
    try {
      select_run(c.plan, bad, "--run");
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_TRUE(what.starts_with("--run: ")) << what;
      EXPECT_NE(what.find("5g, 10g"), std::string::npos) << what;
      EXPECT_NE(what.find("1..6"), std::string::npos) << what;
    }
  }
}

TEST(Config, EditDistance) {
  EXPECT_EQ(edit_distance("radius", "radious"), 1u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("same", "same"), 0u);
}

TEST(Config, NearestName) {
  const std::vector<std::string> verbs = {"budget",   "montecarlo", "simulate",
                                          "identify", "allocate",   "design"};
  // The least distance d, if 3·d <= the name's length: "budgte" is 2 from "budget" (6 >= 6).
  EXPECT_EQ(nearest_name("budgte", verbs), "budget");
  EXPECT_EQ(nearest_name("simulat", verbs), "simulate");
  EXPECT_EQ(nearest_name("design", verbs), "design");
  // Ties go to the first name: "abc" is 1 from both "abd" and "xbc".
  const std::vector<std::string> tied = {"abd", "xbc"};
  EXPECT_EQ(nearest_name("abc", tied), "abd");
  // Too far (the nearest to "mont" is "budget", 5 away), but the only name starting with what was typed.
  EXPECT_EQ(nearest_name("mont", verbs), "montecarlo");
  EXPECT_EQ(nearest_name("al", verbs), "allocate");
  // Too far and no single name it starts: nothing.
  const std::vector<std::string> two = {"identify", "ident_table"};
  EXPECT_EQ(nearest_name("iden", two), std::nullopt);
  EXPECT_EQ(nearest_name("zzzzzz", verbs), std::nullopt);
  EXPECT_EQ(nearest_name("", verbs), std::nullopt);
  EXPECT_EQ(nearest_name("budget", std::vector<std::string>{}), std::nullopt);
}

}  // namespace
}  // namespace ccal

namespace ccal::test {
namespace {

TEST(Config, RunBySpeedInsteadOfGLevel) {
  // speed = "120 rpm" on R0 = 2.5 m with g = 9.8: A = Ω²R0/g = (4π)² · 2.5 / 9.8 = 40.28 g; the nominal rate
  // then returns Ω exactly (round-off, 1e-14 relative).
  const Config c = parse_config(R"([site]
latitude = "45 deg"
g = "9.8 m/s^2"
[centrifuge]
radius = "2.5 m"
[plan]
duration = "450 s"
terminal_phase = "180 deg"
[[plan.runs]]
speed = "120 rpm"
)",
                                "speed.toml");
  const double omega = 4 * std::numbers::pi;
  EXPECT_NEAR(c.plan.runs[0].g_level, omega * omega * 2.5 / 9.8, 1e-14 * 40.0);
  EXPECT_NEAR(nominal_rate(c.plan.runs[0], c.centrifuge.geometry, c.site), omega, 1e-14 * omega);
}

}  // namespace
}  // namespace ccal::test
