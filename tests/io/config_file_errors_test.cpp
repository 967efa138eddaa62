// Every kind of bad configuration is rejected with a one-line message naming the file, line, key and a
// remedy.
#include "config_test_support.hpp"

namespace ccal {
namespace {

using namespace config_test;

TEST(ConfigErrors, TomlSyntaxError) {
  expect_appended_error("base_plane_height = \"2 m", "", {"TOML syntax error"});
  const ConfigError e = error_of(kBase + "\n[site]\n");  // table defined twice
  EXPECT_EQ(e.line(), last_line(kBase + "\n[site]"));
  EXPECT_NE(std::string(e.what()).find("case.toml:"), std::string::npos);
}

TEST(ConfigErrors, UnknownKeyAtEveryLevel) {
  expect_appended_error("radious = \"2.5 m\"", "centrifuge.radious",
                        {"unknown key", "did you mean 'radius'?"});
  expect_appended_error("[sitee]", "sitee", {"unknown key", "did you mean 'site'?"});
  expect_appended_error("[zzzzzzzzzz]", "zzzzzzzzzz", {"unknown key", "accepted keys: site, centrifuge"});
  expect_appended_error("centrifuge_radius = \"2.5 m\"", "centrifuge.centrifuge_radius",
                        {"unknown key", "accepted keys: radius, base_plane_height"});
  expect_appended_error("[tolerances]\ndthz5 = { bond = \"1e-5 rad\" }", "tolerances.dthz5.bond",
                        {"did you mean 'bound'?"});
  expect_appended_error("[instrument]\nmodle = \"piga\"", "instrument.modle", {"did you mean 'model'?"});
  expect_appended_error("[instrument.terms]\nK1 = \"1 deg/s/g\"\nK99 = \"1 deg/s/g\"", "instrument.terms.K99",
                        {"not a term id", "K0, K1", "K_oq", "K_w"});
  expect_error(R"([site]
latitude = "45 deg"
lattitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[[plan.runs]]
g_level = "5 g"
duration = "1 s"
terminal_phase = "0 deg")",
               3, "site.lattitude", {"did you mean 'latitude'?"});
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
durration = "450 s"
[[plan.runs]]
g_level = "5 g")",
               6, "plan.durration", {"did you mean 'duration'?"});
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
duration = "1 s"
initial_phase = "0 deg"
[[plan.runs]]
g_level = "5 g"
[[plan.runs]]
g_levl = "5 g")",
               11, "plan.runs[2].g_levl", {"did you mean 'g_level'?"});
}

TEST(ConfigErrors, UnknownErrorParameterId) {
  expect_appended_error("[errors]\ndthz6 = \"1 rad\"", "errors.dthz6",
                        {"unknown error parameter", "did you mean 'dthz5'?", "dx3_c1"});
  expect_appended_error("[tolerances]\ndr_s = \"25 um\"", "tolerances.dr_s", {"did you mean 'dR_s'?"});
  expect_appended_error("[errors]\ndx3 = \"1 um\"", "errors.dx3", {"did you mean 'dx3_c0'?"});
  expect_appended_error("[errors]\nwhatever = \"1 um\"", "errors.whatever", {"a static id (dthx1t", "_c<k>"});
  expect_appended_error("[tolerances]\ndx3_c2 = \"1 um\"", "tolerances.dx3_c2",
                        {"harmonic 2 is above centrifuge.harmonic_order = 1"});
}

TEST(ConfigErrors, MissingRequiredValues) {
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
base_plane_height = "0 m"
[[plan.runs]]
g_level = "5 g")",
               3, "centrifuge.radius", {"missing value", "radius = \"2.5 m\""});
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
duration = "450 s")",
               5, "plan.runs", {"missing runs", "[[plan.runs]]"});
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
duration = "450 s"
terminal_phase = "0 deg"
[[plan.runs]]
name = "x")",
               8, "plan.runs[1].g_level", {"missing value", "g_level = \"5 g\""});
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
terminal_phase = "0 deg"
[[plan.runs]]
g_level = "5 g")",
               7, "plan.runs[1].duration", {"missing value", "duration = \"450 s\""});
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
duration = "450 s"
[[plan.runs]]
g_level = "5 g")",
               7, "plan.runs[1].terminal_phase", {"missing phase", "initial_phase"});
  expect_error(R"([site]
g = "9.8 m/s^2"
[centrifuge]
radius = "2.5 m")",
               1, "site.latitude", {"missing value", "latitude = \"45.75 deg\""});
  const ConfigError no_centrifuge = error_of("[site]\nlatitude = \"45 deg\"\n");
  EXPECT_NE(std::string(no_centrifuge.what()).find("centrifuge: missing table"), std::string::npos);
  const ConfigError no_plan = error_of("[site]\nlatitude = \"45 deg\"\n[centrifuge]\nradius = \"1 m\"\n");
  EXPECT_NE(std::string(no_plan.what()).find("plan: missing table"), std::string::npos);
  expect_appended_error("[tolerances]\ndthz5 = { distribution = \"uniform\" }", "tolerances.dthz5.bound",
                        {"missing value", "bound = \"1e-5 rad\""});
  expect_appended_error("[plan.runs2]", "plan.runs2", {"did you mean 'runs'?"});
}

TEST(ConfigErrors, WrongType) {
  expect_appended_error("base_plane_height = 2.5", "centrifuge.base_plane_height",
                        {"expected a quantity string such as \"2.5 m\""});
  expect_appended_error("instrument_height = true", "centrifuge.instrument_height",
                        {"expected a quantity string", "got a boolean"});
  expect_appended_error("harmonic_order = \"2\"", "centrifuge.harmonic_order", {"expected an integer 0..16"});
  expect_appended_error("[errors]\ndthz5 = 1e-5", "errors.dthz5",
                        {"expected a quantity string such as \"1e-05 rad\""});
  expect_appended_error("[instrument]\nrate_gain = \"1\"", "instrument.rate_gain", {"expected a number"});
  expect_appended_error("[instrument.terms]\nK1 = 505", "instrument.terms.K1",
                        {"expected a quantity string such as \"505 deg/s/g\""});
  expect_appended_error("[plan.runs.x]", "plan.runs[1].x", {"unknown key"});
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
runs = 3)",
               6, "plan.runs", {"expected an array of tables"});
  expect_appended_error("[tolerances]\ndthz5 = { bound = \"1e-5 rad\", group = 3 }", "tolerances.dthz5.group",
                        {"expected a string"});
  expect_error(R"(site = "Harbin")", 1, "site", {"expected a table"});
  expect_error(R"([site]
latitude = "45 deg"
earth_rotation = "yes")",
               3, "site.earth_rotation", {"expected true or false"});
}

TEST(ConfigErrors, WrongUnitPassesTheUnitMessageThrough) {
  expect_appended_error("base_plane_height = \"2.5 s\"", "centrifuge.base_plane_height",
                        {"unit 's' is a time, expected a length", "accepted: m, mm"});
  expect_appended_error("horizontal_axis_angle = \"2.5\"", "centrifuge.horizontal_axis_angle",
                        {"a unit is required", "rad"});
  expect_appended_error("[errors]\ndR_s = \"2 arcsec\"", "errors.dR_s", {"is an angle, expected a length"});
  expect_appended_error("[errors]\ndomega = \"1e-6 rad\"", "errors.domega", {"expected an angular rate"});
  expect_appended_error("[instrument.terms]\nK3 = \"0.003 deg/s/g^2\"", "instrument.terms.K3", {"rad/s/g^3"});
  expect_appended_error("[instrument]\noutput_unit = \"m\"", "instrument.output_unit",
                        {"is a length", "pulse/s"});
  expect_appended_error("[instrument]\nnoise_density = \"1 deg/s\"", "instrument.noise_density", {"/rtHz"});
  expect_appended_error("[errors]\ndthz5 = \"2 furlong\"", "errors.dthz5", {"unknown unit 'furlong'"});
}

TEST(ConfigErrors, OutOfRangeValues) {
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "-2.5 m")",
               4, "centrifuge.radius", {"must be positive", "\"2.5 m\""});
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "0 m")",
               4, "centrifuge.radius", {"must be positive"});
  expect_appended_error("base_plane_height = \"-1 mm\"", "centrifuge.base_plane_height",
                        {"must not be negative"});
  expect_appended_error("instrument_height = \"-1 mm\"", "centrifuge.instrument_height",
                        {"must not be negative"});
  const Config widest = parse_config(kBase + "\nharmonic_order = 16", "case.toml");
  EXPECT_EQ(widest.centrifuge.layout.harmonic_order(), 16);
  expect_appended_error("harmonic_order = 17", "centrifuge.harmonic_order", {"out of range", "0..16"});
  expect_appended_error("harmonic_order = -1", "centrifuge.harmonic_order", {"out of range"});
  expect_appended_error("[tolerances]\ndthz5 = \"0 rad\"", "tolerances.dthz5", {"must be positive"});
  expect_appended_error("[tolerances]\ndthz5 = { bound = \"-1 rad\" }", "tolerances.dthz5.bound",
                        {"must be positive"});
  expect_appended_error("[tolerances]\ndthz5 = { bound = \"1 rad\", cost = 0 }", "tolerances.dthz5.cost",
                        {"must be positive"});
  // A cost the allocation cannot weigh (1e308 overflowed its objective) is refused where written.
  expect_appended_error("[tolerances]\ndthz5 = { bound = \"1 rad\", cost = 1e308 }", "tolerances.dthz5.cost",
                        {"1e+308 is out of range; accepted: 1e-06 to 1000000"});
  expect_appended_error("[site.x]", "site.x", {"unknown key"});
  expect_error(R"([site]
latitude = "95 deg")",
               2, "site.latitude", {"outside [-90 deg, 90 deg]"});
  // The site is on the Earth: g = 0, a tiny or a huge g (a unit error) and heights beyond the normal
  // gravity formula's range (a height of 5000 km gave NaN forces with exit 0) are refused, shown as written.
  for (const char* g : {"0 m/s^2", "1e-300 m/s^2", "1e300 m/s^2", "98 m/s^2", "-9.8 m/s^2", "9.69 m/s^2"})
    expect_error(std::string("[site]\nlatitude = \"45 deg\"\ng = \"") + g + "\"", 3, "site.g",
                 {g, "not the local gravity on the Earth", "9.7 m/s^2 to 9.9 m/s^2"});
  for (const char* h : {"5e6 m", "10.001 km", "-5001 m", "1e30 m"})
    expect_error(std::string("[site]\nlatitude = \"45 deg\"\nheight = \"") + h + "\"", 3, "site.height",
                 {h, "not a height on the Earth", "-5000 m to 10000 m"});
  const std::string runs = R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
terminal_phase = "0 deg"
duration = "1 s"
[[plan.runs]]
)";
  expect_error(runs + "g_level = \"0 g\"", 9, "plan.runs[1].g_level", {"must be positive", "\"5 g\""});
  expect_error(runs + "g_level = \"-5 g\"", 9, "plan.runs[1].g_level", {"must be positive"});
  expect_error(runs + "g_level = \"5 g\"\nduration = \"-1 s\"", 10, "plan.runs[1].duration",
               {"must be positive", "\"450 s\""});
  expect_error(runs + "g_level = \"5 g\"\nduration = \"0 s\"", 10, "plan.runs[1].duration",
               {"must be positive"});
}

// Positive values beyond any centrifuge test are unit or typing errors: refused where written, shown as
// written, with the accepted range (a radius, g-level, speed or duration of 1e-300 once gave messages about
// revolutions or unobservable terms that named no key).
TEST(ConfigErrors, ImplausiblySmallOrLargeValuesAreNamedAsWritten) {
  const auto config = [](const std::string& radius, const std::string& duration, const std::string& run) {
    return "[site]\nlatitude = \"45 deg\"\n[centrifuge]\nradius = \"" + radius +
           "\"\n[plan]\nterminal_phase = \"0 deg\"\nduration = \"" + duration + "\"\n[[plan.runs]]\n" + run;
  };
  expect_error(config("1e-300 m", "1 s", "g_level = \"5 g\""), 4, "centrifuge.radius",
               {"1e-300 m is implausible", "at least 0.01 m"});
  expect_error(config("200 m", "1 s", "g_level = \"5 g\""), 4, "centrifuge.radius",
               {"is implausible", "up to 100 m"});
  expect_error(config("2.5 m", "1e-300 s", "g_level = \"5 g\""), 7, "plan.duration",
               {"1e-300 s is implausible", "at least 1 ms"});
  expect_error(config("2.5 m", "2e6 s", "g_level = \"5 g\""), 7, "plan.duration",
               {"is implausible", "1e6 s"});
  expect_error(config("2.5 m", "1 s", "g_level = \"1e-300 g\""), 9, "plan.runs[1].g_level",
               {"1e-300 g is implausible", "at least 0.001 g"});
  expect_error(config("2.5 m", "1 s", "g_level = \"2000 g\""), 9, "plan.runs[1].g_level",
               {"is implausible", "up to 1000 g"});
  expect_error(config("2.5 m", "1 s", "speed = \"1e-300 rpm\""), 9, "plan.runs[1].speed",
               {"1e-300 rpm is implausible", "at least 0.001 g"});
  EXPECT_NO_THROW(parse_config(config("0.01 m", "1 ms", "g_level = \"0.001 g\""), "edge.toml"));
}

// A run's name is a CSV cell, a log's file name and the NAME of --log NAME=FILE: a line end in it once gave
// an observations file that `ccal identify` could not read back, with exit 0.
TEST(ConfigErrors, RunNamesAreOneLineWithoutEqualsOrBlankEnds) {
  const std::string runs = R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
terminal_phase = "0 deg"
duration = "1 s"
[[plan.runs]]
g_level = "5 g"
)";
  expect_error(runs + R"(name = "a\nb,c")", 10, "plan.runs[1].name",
               {"run name \"a\\nb,c\" has a control character", "accepted: a name of printable characters"});
  expect_error(runs + R"(name = "a\tb")", 10, "plan.runs[1].name", {"\"a\\tb\" has a control character"});
  expect_error(runs + R"(name = "5g=x")", 10, "plan.runs[1].name", {"has '='"});
  expect_error(runs + R"(name = " 5g")", 10, "plan.runs[1].name", {"has a blank at one end"});
  expect_error(runs + R"(name = "5g ")", 10, "plan.runs[1].name", {"has a blank at one end"});
  EXPECT_EQ(parse_config(runs + R"x(name = "5 g, IA up (é)")x", "ok.toml").plan.runs[0].name,
            "5 g, IA up (é)");
}

TEST(ConfigErrors, NonFiniteNumbers) {
  expect_appended_error("base_plane_height = \"nan m\"", "centrifuge.base_plane_height",
                        {"not a finite number"});
  expect_appended_error("base_plane_height = \"inf m\"", "centrifuge.base_plane_height",
                        {"not a finite number"});
  expect_appended_error("base_plane_height = nan", "centrifuge.base_plane_height",
                        {"expected a quantity string"});
  expect_appended_error("[instrument]\nrate_gain = nan", "instrument.rate_gain", {"not a finite number"});
  expect_appended_error("[tolerances]\ndthz5 = { bound = \"1 rad\", cost = inf }", "tolerances.dthz5.cost",
                        {"not a finite number"});
}

TEST(ConfigErrors, BothPhasesInOneScope) {
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
duration = "1 s"
terminal_phase = "0 deg"
initial_phase = "0 deg"
[[plan.runs]]
g_level = "5 g")",
               8, "plan.initial_phase", {"both initial_phase and terminal_phase", "exactly one"});
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
duration = "1 s"
[[plan.runs]]
g_level = "5 g"
initial_phase = "0 deg"
terminal_phase = "0 deg")",
               10, "plan.runs[1].terminal_phase", {"both initial_phase and terminal_phase"});
}

TEST(ConfigErrors, UnknownWords) {
  const std::string runs = R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
terminal_phase = "0 deg"
duration = "1 s"
[[plan.runs]]
g_level = "5 g"
)";
  expect_error(
      runs + "platform = \"counter-rotating\"", 10, "plan.runs[1].platform",
      {"unknown value 'counter-rotating'", "did you mean 'counter_rotating'?", "counter_rotating, fixed"});
  expect_error(runs + "mounting = \"sideways\"", 10, "plan.runs[1].mounting",
               {"unknown value", "ia_horizontal, ia_reversed, pa_vertical, ia_vertical"});
  expect_appended_error("[tolerances]\ndthz5 = { bound = \"1 rad\", distribution = \"gaussian\" }",
                        "tolerances.dthz5.distribution", {"normal, uniform, triangular, arcsine"});
  expect_appended_error("[instrument]\nmodel = \"qa\"", "instrument.model", {"piga, ieee"});
}

TEST(ConfigErrors, DuplicateRunNames) {
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
terminal_phase = "0 deg"
duration = "1 s"
[[plan.runs]]
name = "a"
g_level = "5 g"
[[plan.runs]]
name = "a"
g_level = "6 g")",
               12, "plan.runs[2].name", {"duplicate run name 'a'", "line 9", "unique"});
  // A given name may also collide with a default one.
  expect_error(R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
terminal_phase = "0 deg"
duration = "1 s"
[[plan.runs]]
g_level = "5 g"
[[plan.runs]]
name = "run1"
g_level = "6 g")",
               11, "plan.runs[2].name", {"duplicate run name 'run1'"});
}

TEST(ConfigErrors, InstrumentNeedsTerms) {
  const std::string ieee = kBase + "\n[instrument]\nmodel = \"ieee\"";
  expect_error(ieee, last_line(ieee) - 1, "instrument.terms", {"missing table", "K1"});
  expect_appended_error("[instrument]\noutput_unit = \"g\"", "instrument.output_unit",
                        {"cannot use the paper's PIGA coefficients"});
}

TEST(ConfigErrors, Identification) {
  expect_appended_error("[identification]\nterm = [\"K0\"]", "identification.term",
                        {"unknown key", "did you mean 'terms'?"});
  expect_appended_error("[identification]\nterms = [\"K0\", \"K99\"]", "identification.terms",
                        {"'K99' is not a term id", "accepted: K0, K1", "K_pp", "K_w"});
  expect_appended_error("[identification]\nterms = [\"K0\", \"k2\"]", "identification.terms",
                        {"did you mean 'K2'?"});
  expect_appended_error("[identification]\nterms = []", "identification.terms", {"empty", "at least one"});
  expect_appended_error("[identification]\nterms = \"K0\"", "identification.terms",
                        {"expected an array of term ids", "got a string"});
  expect_appended_error("[identification]\nterms = [\"K0\", 2]", "identification.terms",
                        {"expected a term id string", "got an integer"});
  expect_appended_error("[identification]\nterms = [\"K0\", \"K2\",\n  \"K2\"]", "identification.terms",
                        {"'K2' is listed twice"});
  expect_appended_error("[identification]\nterms = [\"K0\", \"K1\", \"K2\"]\nfixed = [\"K1\"]",
                        "identification.fixed", {"'K1' is also in identification.terms", "not both"});
  expect_appended_error("[identification]\nfixed = [\"K1\", \"K4\"]", "identification.fixed",
                        {"the instrument has no term 'K4'", "accepted: K0, K1, K2, K3"});
  expect_appended_error("[identification]\nmode = \"papr\"", "identification.mode",
                        {"did you mean 'paper'?", "accepted: exact, paper"});
  expect_appended_error("[identification]\ncompensate = \"yes\"", "identification.compensate",
                        {"expected true or false"});
}

TEST(ConfigErrors, UnreadableFile) {
  try {
    load_config("/nonexistent/ccal.toml");
    ADD_FAILURE();
  } catch (const ConfigError& e) {
    EXPECT_TRUE(std::string(e.what()).starts_with("/nonexistent/ccal.toml: cannot read")) << e.what();
    EXPECT_EQ(e.line(), 0);
  }
}

TEST(ConfigErrors, SpeedAndGLevelTogetherOrNeither) {
  const std::string head = R"([site]
latitude = "45 deg"
[centrifuge]
radius = "2.5 m"
[plan]
duration = "450 s"
terminal_phase = "180 deg"
[[plan.runs]]
)";
  expect_error(head + "g_level = \"5 g\"\nspeed = \"100 rpm\"\n", 10, "plan.runs[1].speed", {"exactly one"});
  expect_error(head + "speed = \"100 m\"\n", 9, "plan.runs[1].speed", {"rpm"});
  expect_error(head + "speed = \"-100 rpm\"\n", 9, "plan.runs[1].speed", {"positive"});
}

}  // namespace
}  // namespace ccal

namespace ccal {
namespace {

using namespace config_test;

// The floor of a tolerance (the machine's best achievable bound): a quantity of the bound's dimension, > 0
// and at most the bound; read in the entry's own units.
TEST(ConfigErrors, ToleranceFloor) {
  expect_appended_error("[tolerances]\ndthz5 = { bound = \"10 arcsec\", floor = \"0 arcsec\" }",
                        "tolerances.dthz5.floor", {"must be positive", "at most the bound"});
  expect_appended_error("[tolerances]\ndthz5 = { bound = \"10 arcsec\", floor = \"-1 arcsec\" }",
                        "tolerances.dthz5.floor", {"must be positive"});
  expect_appended_error("[tolerances]\ndthz5 = { bound = \"10 arcsec\", floor = \"11 arcsec\" }",
                        "tolerances.dthz5.floor",
                        {"\"11 arcsec\" is above the bound \"10 arcsec\"", "at most the bound"});
  expect_appended_error("[tolerances]\ndthz5 = { bound = \"10 arcsec\", floor = \"1 um\" }",
                        "tolerances.dthz5.floor", {"rad"});
  expect_appended_error("[tolerances]\ndthz5 = { bound = \"10 arcsec\", flor = \"1 arcsec\" }",
                        "tolerances.dthz5.flor", {"did you mean 'floor'?"});
  const Config c =
      parse_config(kBase +
                       "\n[tolerances]\ndthz5 = { bound = \"10 arcsec\", floor = \"0.1 arcsec\" }\n"
                       "dR_s = \"25 um\"\n",
                   "case.toml");
  ASSERT_EQ(c.tolerances.size(), 2u);
  for (const Tolerance& t : c.tolerances) {
    if (t.id == "dthz5") {
      EXPECT_NEAR(t.floor, 0.1 / 3600 * kDeg, 1e-15 * t.floor);  // arcsec → rad, to round-off
      EXPECT_NEAR(t.bound, 10.0 / 3600 * kDeg, 1e-15 * t.bound);
    } else {
      EXPECT_EQ(t.floor, 0.0);  // no floor given: none
    }
  }
}

}  // namespace
}  // namespace ccal
