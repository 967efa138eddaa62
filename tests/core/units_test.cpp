#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/constants.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"

namespace ccal {
// Lets GoogleTest print dimensions in failure messages.
void PrintTo(const Dimension& d, std::ostream* os) {
  *os << "{L" << d.length << " T" << d.time << " A" << d.angle << " G" << d.g_level << "}";
}
}  // namespace ccal

namespace {

using ccal::Dimension;
namespace kind = ccal::kind;
constexpr double pi = std::numbers::pi;  // reference values are built from this, not from ccal's constants

// Relative tolerances used below, with their reason:
// - kExact: the SI value is obtained by multiplying by 1 or a power of two, or the expected value is
//   computed by exactly the same floating-point operations, so it must be bit-identical.
constexpr double kExact = 0.0;
// - kOneRounding: one rounding separates the two sides, e.g. 25 * 1e-6 (1e-6 is itself rounded) against
//   the literal 25e-6, or 120 * fl(π/30) against 4π. Each rounding is at most 2^-53 ≈ 1.1e-16 relative;
//   a few of them stay below 1e-15.
constexpr double kFewRoundings = 1e-15;
// - kCorrectlyRounded: a constant that must be the correctly rounded ratio (e.g. π/648000); 1e-16 is below
//   one unit in the last place (1.1e-16..2.2e-16 relative), so even a one-ulp error fails.
constexpr double kCorrectlyRounded = 1e-16;

void ExpectRelative(double actual, double expected, double rel_tol) {
  EXPECT_NEAR(actual, expected, rel_tol * std::abs(expected)) << "relative tolerance " << rel_tol;
}

// Runs f, which must throw UnitError, and returns the message.
std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const ccal::UnitError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected ccal::UnitError";
  return {};
}

void ExpectContains(const std::string& message, std::string_view part) {
  EXPECT_NE(message.find(part), std::string::npos)
      << "message: " << message << "\nexpected to contain: " << part;
}

// ---------------------------------------------------------------------------------------------------
// The examples from the specification, and a few more spellings.

struct Example {
  std::string_view text;
  double si;
  Dimension dim;
  double rel_tol;
};

// Shows the text of a failing example instead of its bytes.
void PrintTo(const Example& ex, std::ostream* os) { *os << "'" << ex.text << "'"; }

class ParseExample : public testing::TestWithParam<Example> {};

TEST_P(ParseExample, GivesSiValueAndDimension) {
  const Example& ex = GetParam();
  const ccal::Quantity q = ccal::parse_quantity(ex.text);
  ExpectRelative(q.value_si, ex.si, ex.rel_tol);
  EXPECT_EQ(q.dim, ex.dim);
  // parse_as with the right dimension gives the same number.
  EXPECT_EQ(ccal::parse_as(ex.text, ex.dim, "example"), q.value_si);
}

const Dimension kRatePerG = kind::coefficient(kind::angular_rate, 1);
const Dimension kRatePerG3 = kind::coefficient(kind::angular_rate, 3);
const Dimension kLengthPerRate2{.length = 1, .time = 2, .angle = -2};

INSTANTIATE_TEST_SUITE_P(
    Specification, ParseExample,
    testing::Values(
        Example{"1e-5 rad", 1e-5, kind::angle, kExact},                        // factor 1
        Example{"2 arcsec", 2 * pi / 648000, kind::angle, kCorrectlyRounded},  // 2·x is exact
        Example{"10 urad", 1e-5, kind::angle, kFewRoundings},                  // 10·fl(1e-6) vs fl(1e-5)
        Example{"10 µrad", 1e-5, kind::angle, kFewRoundings},                  // same
        Example{"10 μrad", 1e-5, kind::angle, kFewRoundings},                  // same, Greek mu
        Example{"25 um", 25e-6, kind::length, kFewRoundings},                  // 25·fl(1e-6) vs fl(25e-6)
        Example{"25 µm", 25e-6, kind::length, kFewRoundings},                  // same
        Example{"2.5 m", 2.5, kind::length, kExact},                           // factor 1
        Example{"0.5e-6 rad/s", 0.5e-6, kind::angular_rate, kExact},           // factor 1/1
        Example{"30 g", 30.0, kind::acceleration_g, kExact},                   // factor 1
        Example{"120 rpm", 4 * pi, kind::angular_rate, kFewRoundings},         // 120·fl(π/30)
        Example{"0.003 deg/s/g^3", 0.003 * (pi / 180), kRatePerG3, kExact},    // same operations
        Example{"505.2097 deg/s/g", 505.2097 * (pi / 180), kRatePerG, kExact},
        Example{"1 mm", 1e-3, kind::length, kExact},  // 1·fl(1e-3) is the literal 1e-3
        Example{"3 deg", 3 * (pi / 180), kind::angle, kExact},
        Example{"0.01 mrad", 1e-5, kind::angle, kFewRoundings},  // fl(0.01)·fl(1e-3) vs fl(1e-5)
        Example{"1 arcmin", pi / 10800, kind::angle, kCorrectlyRounded},
        Example{"1 deg/h", pi / 180 / 3600, kind::angular_rate, kExact},  // same operations
        Example{"9.8 m/s^2", 9.8, kind::acceleration, kExact},            // factor 1
        Example{"450 s", 450.0, kind::time, kExact}, Example{"1 min", 60.0, kind::time, kExact},
        Example{"1 h", 3600.0, kind::time, kExact}, Example{"1 m/(rad/s)^2", 1.0, kLengthPerRate2, kExact},
        // Further spellings the grammar allows.
        Example{"3 °", 3 * (pi / 180), kind::angle, kExact},
        Example{"3°", 3 * (pi / 180), kind::angle, kExact},
        Example{"25um", 25e-6, kind::length, kFewRoundings}, Example{"  +2 m  ", 2.0, kind::length, kExact},
        Example{"-3 arcsec", -3 * pi / 648000, kind::angle, kFewRoundings},
        Example{"9.8 m/s²", 9.8, kind::acceleration, kExact},
        Example{"9.8 m*s^-2", 9.8, kind::acceleration, kExact},
        Example{"2 deg / s", 2 * (pi / 180), kind::angular_rate, kExact},
        Example{"1 m.s", 1.0, Dimension{.length = 1, .time = 1}, kExact},
        Example{"1 m*s^2/rad^2", 1.0, kLengthPerRate2, kExact},
        Example{"5 ms", 5e-3, kind::time, kFewRoundings},  // 5·fl(1e-3) vs fl(5e-3)
        Example{"3 nm", 3e-9, kind::length, kFewRoundings}, Example{"2 km", 2e3, kind::length, kExact},
        Example{"20 µg", 20e-6, kind::acceleration_g, kFewRoundings},
        Example{"2 mg", 2e-3, kind::acceleration_g, kFewRoundings},
        Example{"50 ppm", 50e-6, kind::dimensionless, kFewRoundings},
        Example{"2 %", 0.02, kind::dimensionless, kFewRoundings},
        Example{"10 urad/s", 1e-5, kind::angular_rate, kFewRoundings}));

// ---------------------------------------------------------------------------------------------------
// Specific properties

TEST(Units, MicroPrefixesAreEqual) {
  // Same operations whatever the spelling of micro, so the values must be bit-identical.
  for (std::string_view base : {"rad", "m", "s", "g"}) {
    const std::string u = std::string("10 u") + std::string(base);
    const double ascii = ccal::parse_quantity(u).value_si;
    EXPECT_EQ(ccal::parse_quantity(std::string("10 µ") + std::string(base)).value_si, ascii) << base;
    EXPECT_EQ(ccal::parse_quantity(std::string("10 μ") + std::string(base)).value_si, ascii) << base;
  }
}

TEST(Units, CubicCoefficientHasGExponentMinusThree) {
  const ccal::Quantity q = ccal::parse_quantity("0.003 deg/s/g^3");
  EXPECT_EQ(q.dim.g_level, -3);
  EXPECT_EQ(q.dim.angle, 1);
  EXPECT_EQ(q.dim.time, -1);
  EXPECT_EQ(q.dim.length, 0);
  ExpectRelative(q.value_si, 0.003 * pi / 180, kFewRoundings);  // order of operations differs: 2 roundings
}

TEST(Units, RpmIsFourPiAt120) {
  // 120 rpm = 2 rev/s = 4π rad/s; fl(π/30) and the product are each rounded once.
  ExpectRelative(ccal::parse_as("120 rpm", kind::angular_rate, "rate"), 4 * pi, kFewRoundings);
}

TEST(Units, ParenthesisedDenominator) {
  const Dimension d = ccal::parse_quantity("1 m/(rad/s)^2").dim;
  EXPECT_EQ(d.length, 1);
  EXPECT_EQ(d.time, 2);
  EXPECT_EQ(d.angle, -2);
  EXPECT_EQ(d.g_level, 0);
  // (deg/s)^2 in the denominator divides by deg² exactly as written.
  ExpectRelative(ccal::parse_quantity("1 m/(deg/s)^2").value_si, 1 / ((pi / 180) * (pi / 180)),
                 kFewRoundings);
}

TEST(Units, RadPerSecondDiffersFromPerSecond) {
  EXPECT_NE(ccal::parse_quantity("1 rad/s").dim, ccal::parse_quantity("1 s^-1").dim);
  const std::string msg = ErrorOf([] { ccal::parse_as("2 s^-1", kind::angular_rate, "omega"); });
  ExpectContains(msg, "unit 's^-1' is a quantity in s^-1, expected an angular rate");
}

TEST(Units, GLevelDiffersFromAcceleration) {
  EXPECT_NE(kind::acceleration_g, kind::acceleration);
  const std::string msg = ErrorOf([] { ccal::parse_as("9.8 m/s^2", kind::acceleration_g, "input"); });
  ExpectContains(msg, "unit 'm/s^2' is an acceleration, expected a g-level");
}

TEST(Units, ArcsecFactorIsPiOver648000) {
  // One unit in the last place of 4.85e-6 is 1.7e-16 relative, so 1e-16 admits only the correctly rounded
  // π/648000. Common wrong factors fail by far more: 1/206265 (9.4e-7), 4.8481368e-6 (2.3e-9).
  ExpectRelative(ccal::parse_as("1 arcsec", kind::angle, "a"), pi / 648000, kCorrectlyRounded);
  ExpectRelative(ccal::constants::arcsec, pi / 648000, kCorrectlyRounded);
  ExpectRelative(ccal::from_unit(1.0, "arcsec"), pi / 648000, kCorrectlyRounded);
  // A full turn: 1296000 arcsec = 2π; one extra rounding from the multiplication.
  ExpectRelative(ccal::parse_as("1296000 arcsec", kind::angle, "a"), 2 * pi, kFewRoundings);
}

TEST(Units, Constants) {
  using namespace ccal::constants;
  ExpectRelative(deg, pi / 180, kCorrectlyRounded);
  ExpectRelative(arcmin, pi / 10800, kCorrectlyRounded);
  ExpectRelative(rpm, 2 * pi / 60, kCorrectlyRounded);  // 2π/60 and π/30 are the same real number
  EXPECT_EQ(standard_gravity, 9.80665);                 // exact by definition; same decimal literal
  EXPECT_EQ(earth_rotation_rate, 7.2921150e-5);         // WGS-84 value; same decimal literal
}

// ---------------------------------------------------------------------------------------------------
// Output

TEST(Units, FormatUsesPercentG) {
  // %.6g drops trailing zeros; the value divided back by the same factor rounds to the decimal shown.
  EXPECT_EQ(ccal::format_quantity(2 * ccal::constants::arcsec, kind::angle, "arcsec"), "2 arcsec");
  EXPECT_EQ(ccal::format_quantity(0.003 * ccal::constants::deg, kRatePerG3, "deg/s/g^3"), "0.003 deg/s/g^3");
  EXPECT_EQ(ccal::format_quantity(4 * pi, kind::angular_rate, "rpm"), "120 rpm");
  EXPECT_EQ(ccal::format_quantity(pi, kind::angle, "deg", 3), "180 deg");
  EXPECT_EQ(ccal::format_quantity(pi, kind::angle, "rad", 4), "3.142 rad");
  EXPECT_EQ(ccal::format_quantity(0.25, kind::dimensionless, ""), "0.25");
  EXPECT_EQ(ccal::format_quantity(1.5e-5, kind::dimensionless, "ppm"), "15 ppm");
}

TEST(Units, FormatRejectsWrongDimensionAndUnknownUnit) {
  ExpectContains(ErrorOf([] { ccal::format_quantity(1.0, kind::angle, "mm"); }),
                 "cannot write an angle in 'mm', which is a length");
  ExpectContains(ErrorOf([] { ccal::format_quantity(1.0, kind::angle, "furlong"); }),
                 "unknown unit 'furlong'");
}

struct RoundTrip {
  double si;
  Dimension dim;
  std::string_view unit;
};

TEST(Units, FormatThenParseRoundTrips) {
  const std::vector<RoundTrip> cases = {
      {2.3e-5, kind::angle, "arcsec"},        {1.7e-3, kind::angle, "mrad"},
      {0.123456789, kind::angle, "deg"},      {2.5e-5, kind::length, "µm"},
      {3.3e-7, kind::angular_rate, "deg/h"},  {12.56, kind::angular_rate, "rpm"},
      {5.2e-5, kRatePerG3, "deg/s/g^3"},      {8.8176, kRatePerG, "deg/s/g"},
      {0.37, kLengthPerRate2, "m/(rad/s)^2"}, {7.2921150e-5, kind::angular_rate, "rad/s"},
      {1.2e-4, kind::acceleration_g, "µg"},   {5400.0, kind::time, "h"},
  };
  for (const RoundTrip& c : cases) {
    SCOPED_TRACE(c.unit);
    // 17 significant digits print the value in the unit exactly; SI → unit → SI then costs one rounding
    // for the division and one for the multiplication: at most 2 units in the last place, 4.5e-16.
    const std::string exact = ccal::format_quantity(c.si, c.dim, c.unit, 17);
    ExpectRelative(ccal::parse_as(exact, c.dim, "round trip"), c.si, 4.5e-16);
    // With the default 6 significant digits the printed decimal is within half a unit of the 6th digit,
    // i.e. 5e-6 relative at worst (mantissa 1.00000), plus the two roundings.
    const std::string rounded = ccal::format_quantity(c.si, c.dim, c.unit);
    ExpectRelative(ccal::parse_as(rounded, c.dim, "round trip"), c.si, 5e-6 + 4.5e-16);
  }
}

TEST(Units, ToAndFromUnit) {
  ExpectRelative(ccal::to_unit(pi, "deg"), 180.0, kFewRoundings);  // π / fl(π/180): one or two roundings
  ExpectRelative(ccal::from_unit(180.0, "deg"), pi, kFewRoundings);
  ExpectRelative(ccal::to_unit(1e-3, "um"), 1000.0, kFewRoundings);  // fl(1e-3) / fl(1e-6)
  EXPECT_EQ(ccal::from_unit(2.0, "h"), 7200.0);                      // exact integers
  EXPECT_EQ(ccal::to_unit(0.5, ""), 0.5);                            // dimensionless, factor 1
  ExpectContains(ErrorOf([] { ccal::to_unit(1.0, "parsec"); }), "unknown unit 'parsec'");
  ExpectContains(ErrorOf([] { ccal::from_unit(1.0, "m/"); }), "expected a unit symbol");
}

TEST(Units, ParseUnitGivesFactorAndDimension) {
  const ccal::Quantity deg = ccal::parse_unit("deg");
  EXPECT_EQ(deg.value_si, pi / 180);  // the correctly rounded factor itself
  EXPECT_EQ(deg.dim, kind::angle);
  EXPECT_EQ(ccal::parse_unit("").dim, kind::dimensionless);
  EXPECT_EQ(ccal::parse_unit("").value_si, 1.0);
}

// ---------------------------------------------------------------------------------------------------
// Listing and describing dimensions

TEST(Units, UnitListForAngleMatchesMessages) {
  EXPECT_EQ(ccal::unit_list(kind::angle), "rad, mrad, urad, µrad, deg, arcmin, arcsec");
  EXPECT_EQ(ccal::unit_list(kRatePerG3), "rad/s/g^3, deg/s/g^3, deg/h/g^3");
}

TEST(Units, EveryListedUnitParsesToItsDimension) {
  const std::vector<Dimension> dims = {kind::angle,
                                       kind::length,
                                       kind::time,
                                       kind::angular_rate,
                                       kind::acceleration,
                                       kind::acceleration_g,
                                       kind::dimensionless,
                                       kRatePerG,
                                       kRatePerG3,
                                       kLengthPerRate2,
                                       Dimension{.time = -1},
                                       kind::coefficient(kind::length, 2)};
  for (const Dimension& d : dims) {
    const std::string list = ccal::unit_list(d);
    ASSERT_FALSE(list.empty());
    std::size_t start = 0;
    while (start <= list.size()) {
      const std::size_t comma = std::min(list.find(", ", start), list.size());
      const std::string unit = list.substr(start, comma - start);
      EXPECT_EQ(ccal::parse_unit(unit).dim, d) << "'" << unit << "' in '" << list << "'";
      start = comma + 2;
    }
  }
}

TEST(Units, SiUnitSpellsDimensions) {
  EXPECT_EQ(ccal::si_unit(kRatePerG3), "rad/s/g^3");
  EXPECT_EQ(ccal::si_unit(kLengthPerRate2), "m*s^2/rad^2");
  EXPECT_EQ(ccal::si_unit(kind::acceleration), "m/s^2");
  EXPECT_EQ(ccal::si_unit(Dimension{.time = -1}), "s^-1");
  EXPECT_EQ(ccal::si_unit(Dimension{.time = -1, .g_level = -2}), "s^-1*g^-2");
  EXPECT_EQ(ccal::si_unit(kind::dimensionless), "");
  // The SI spelling parses back to the same dimension with factor 1 (exact: products of 1).
  const ccal::Quantity q = ccal::parse_unit(ccal::si_unit(kLengthPerRate2));
  EXPECT_EQ(q.dim, kLengthPerRate2);
  EXPECT_EQ(q.value_si, 1.0);
}

TEST(Units, Describe) {
  EXPECT_EQ(ccal::describe(kind::angle), "an angle");
  EXPECT_EQ(ccal::describe(kind::acceleration_g), "a g-level");
  EXPECT_EQ(ccal::describe(kind::dimensionless), "dimensionless");
  EXPECT_EQ(ccal::describe(kRatePerG), "a quantity in rad/s/g");
}

// ---------------------------------------------------------------------------------------------------
// Errors

TEST(UnitErrors, MismatchedDimensionNamesQuantityUnitAndAcceptedList) {
  const std::string msg = ErrorOf([] { ccal::parse_as("3 mm", kind::angle, "dthz5"); });
  ExpectContains(msg, "dthz5");
  ExpectContains(msg, "'3 mm'");
  ExpectContains(
      msg, "unit 'mm' is a length, expected an angle (accepted: rad, mrad, urad, µrad, deg, arcmin, arcsec)");
}

TEST(UnitErrors, MismatchedCoefficientOrder) {
  const std::string msg = ErrorOf([] { ccal::parse_as("0.003 deg/s/g^2", kRatePerG3, "K3"); });
  ExpectContains(msg, "K3");
  ExpectContains(msg, "unit 'deg/s/g^2' is a quantity in rad/s/g^2, expected a quantity in rad/s/g^3");
  ExpectContains(msg, "accepted: rad/s/g^3, deg/s/g^3, deg/h/g^3");
}

TEST(UnitErrors, UnknownUnitListsAcceptedOnes) {
  const std::string msg = ErrorOf([] { ccal::parse_as("3 furlong", kind::length, "radius"); });
  ExpectContains(msg, "radius");
  ExpectContains(msg, "'3 furlong'");
  ExpectContains(msg, "unknown unit 'furlong'");
  ExpectContains(msg, "accepted: m, mm, um, µm, nm, km");
  // Without an expected dimension every symbol and prefix is listed.
  const std::string any = ErrorOf([] { ccal::parse_quantity("3 furlong"); });
  ExpectContains(any, "unknown unit 'furlong'");
  ExpectContains(any, "known units: m, s, min, h, rad, deg, °, arcmin, arcsec, rpm, g, gn, ppm, %, A, V, ohm");
  // Prefixes only where they are defined.
  ExpectContains(ErrorOf([] { ccal::parse_quantity("2 kg"); }), "unknown unit 'kg'");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("2 mdeg"); }), "unknown unit 'mdeg'");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("2 M"); }), "unknown unit 'M'");  // case-sensitive
}

TEST(Units, CurrentVoltageAndResistanceForAnOutputReadAcrossAResistor) {
  // A quartz accelerometer's output in mA read as volts across a resistor: V = I R, each a dimension of its own.
  const ccal::Quantity i = ccal::parse_quantity("2.5 mA");
  EXPECT_EQ(i.dim, kind::current);
  EXPECT_DOUBLE_EQ(i.value_si, 2.5e-3);
  EXPECT_EQ(ccal::parse_quantity("250 ohm").dim, kind::resistance);
  EXPECT_DOUBLE_EQ(ccal::parse_quantity("1.5 kohm").value_si, 1500.0);
  EXPECT_EQ(ccal::parse_quantity("3 mV").dim * ccal::parse_quantity("1 A").dim / kind::voltage, kind::current);
  EXPECT_EQ(ccal::parse_quantity("1.3 mA/g").dim, kind::coefficient(kind::current, 1));
  EXPECT_EQ(ccal::si_unit(kind::coefficient(kind::current, 2)), "A/g^2");
  EXPECT_EQ(ccal::describe(kind::current), "a current");
  // gn, standard gravity as the g of a g-level: the same dimension as g, for coefficients per g_n.
  EXPECT_EQ(ccal::parse_quantity("0.02 deg/s/gn^2").dim, ccal::parse_quantity("0.02 deg/s/g^2").dim);
  EXPECT_NE(ErrorOf([] { ccal::parse_quantity("2 A"); ccal::parse_as("2 mA", kind::voltage, "x"); }).find("x"),
            std::string::npos);
}

TEST(UnitErrors, BareNumberNeedsUnitUnlessAllowed) {
  const std::string msg = ErrorOf([] { ccal::parse_as("0.001", kind::angle, "dthz5"); });
  ExpectContains(msg, "dthz5");
  ExpectContains(msg, "a unit is required, e.g. '0.001 rad'");
  EXPECT_EQ(ccal::parse_as("0.001", kind::angle, "dthz5", /*allow_bare_si=*/true), 0.001);  // taken as is
  // Also for dimensionless quantities: a bare 100 might have been meant in ppm.
  ExpectContains(ErrorOf([] { ccal::parse_as("100", kind::dimensionless, "scale error"); }),
                 "a unit is required, e.g. '100 ppm'");
  // parse_quantity reports a bare number as dimensionless.
  EXPECT_EQ(ccal::parse_quantity("42").dim, kind::dimensionless);
}

TEST(UnitErrors, NonFiniteNumbers) {
  ExpectContains(ErrorOf([] { ccal::parse_as("nan rad", kind::angle, "x"); }),
                 "'nan' is not a finite number");
  ExpectContains(ErrorOf([] { ccal::parse_as("inf m", kind::length, "x"); }), "'inf' is not a finite number");
  ExpectContains(ErrorOf([] { ccal::parse_as("-inf m", kind::length, "x"); }), "not a finite number");
  ExpectContains(ErrorOf([] { ccal::parse_as("nan", kind::length, "x", true); }), "not a finite number");
}

TEST(UnitErrors, OutOfRange) {
  ExpectContains(ErrorOf([] { ccal::parse_as("1e400 m", kind::length, "x"); }), "'1e400' is out of range");
  // Finite as a number, infinite once multiplied by the unit's factor.
  ExpectContains(ErrorOf([] { ccal::parse_as("1e306 km", kind::length, "x"); }),
                 "out of range of double once converted to SI");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("1 m^99"); }), "exponent 99 is out of range");
}

TEST(UnitErrors, MissingNumberOrEverything) {
  ExpectContains(ErrorOf([] { ccal::parse_as("", kind::angle, "tilt"); }),
                 "tilt: '': expected a number and a unit; accepted: a finite number and its unit, e.g. '1 rad'");
  ExpectContains(ErrorOf([] { ccal::parse_as("   ", kind::angle, "tilt"); }), "expected a number and a unit");
  ExpectContains(ErrorOf([] { ccal::parse_as("rad", kind::angle, "tilt"); }),
                 "tilt: 'rad': expected a number before the unit");
}

TEST(UnitErrors, MalformedText) {
  ExpectContains(ErrorOf([] { ccal::parse_quantity("1.2.3 m"); }), "malformed number '1.2.3'");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("1,5 m"); }), "malformed number '1,5'");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("2e m"); }), "malformed number '2e'");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("2 m x"); }), "unexpected 'x' after the unit");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("2 m/"); }), "expected a unit symbol at the end");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("2 m/(rad/s"); }), "missing ')'");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("2 m)"); }), "unmatched ')'");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("2 m/((rad/s))"); }), "nested parentheses");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("2 m^"); }), "expected an integer exponent");
  ExpectContains(ErrorOf([] { ccal::parse_quantity("2 m^x"); }), "expected an integer exponent");
}

TEST(UnitErrors, AreInputErrors) {
  // Callers may catch all bad-input errors through the base class.
  EXPECT_THROW(ccal::parse_quantity("2 furlong"), ccal::InputError);
  EXPECT_THROW(ccal::parse_quantity("2 furlong"), std::runtime_error);
}

}  // namespace
