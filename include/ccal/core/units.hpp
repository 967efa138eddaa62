#pragma once
// Quantities with units at ccal's boundaries. Everything inside ccal is SI (m, s, rad, m/s², rad/s);
// engineering units such as arcsec, µm, deg/h or deg/s/g^3 exist only when reading input and writing
// output. Parsing checks the dimension, so a length given where an angle is expected is an error rather
// than a silently wrong number.
//
// Unit grammar (after a number and optional whitespace):
//   expression := term (('*' | '.' | '/') term)*        left to right: deg/s/g^3 is deg·s⁻¹·g⁻³
//   term       := (symbol | '(' expression ')') ('^' integer | '²' | '³')?
// Parentheses nest one level only, as in m/(rad/s)^2. Symbols are case-sensitive:
//   length  m;  time  s, min, h;  angle  rad, deg, °, arcmin, arcsec;  rate  rpm;
//   g-level g;  dimensionless  ppm, %;  current A;  voltage V;  resistance ohm.
// Prefixes n, u, µ (U+00B5), μ (U+03BC), m, k apply to m, s, rad, A, V and ohm (mm, µm, mrad, ms, mA, kohm);
// m, u, µ, μ apply to g (mg, µg), the usual units of accelerometer bias.
#include <string>
#include <string_view>

#include "ccal/core/errors.hpp"

namespace ccal {

// Exponents of the base dimensions. Angle is a base dimension of its own so that rad/s and 1/s stay
// distinct, and so that an angle given where a dimensionless ratio is expected is caught. The g-level is
// one too: an accelerometer's input is specified as a multiple of g, and its coefficients K_n are in
// output-unit per g^n, which must not be confused with output-unit per (m/s²)^n.
// Current and voltage are base dimensions too, for an instrument whose output is a current (a quartz
// accelerometer's, in mA) read as a voltage across a sampling resistor (ohm = V/A): ccal never needs them in
// kg, m and s.
struct Dimension {
  int length = 0;
  int time = 0;
  int angle = 0;
  int g_level = 0;
  int current = 0;
  int voltage = 0;

  friend constexpr bool operator==(const Dimension&, const Dimension&) = default;
};

constexpr Dimension operator*(Dimension a, Dimension b) {
  return {a.length + b.length,   a.time + b.time,       a.angle + b.angle,
          a.g_level + b.g_level, a.current + b.current, a.voltage + b.voltage};
}
constexpr Dimension operator/(Dimension a, Dimension b) {
  return {a.length - b.length,   a.time - b.time,       a.angle - b.angle,
          a.g_level - b.g_level, a.current - b.current, a.voltage - b.voltage};
}
constexpr Dimension pow(Dimension a, int n) {
  return {a.length * n, a.time * n, a.angle * n, a.g_level * n, a.current * n, a.voltage * n};
}

// The dimensions of the quantities ccal handles, with their SI unit.
namespace kind {
inline constexpr Dimension dimensionless{};
inline constexpr Dimension length{.length = 1};                   // m
inline constexpr Dimension time{.time = 1};                       // s
inline constexpr Dimension angle{.angle = 1};                     // rad
inline constexpr Dimension acceleration_g{.g_level = 1};          // g (input of the accelerometer)
inline constexpr Dimension angular_rate = angle / time;           // rad/s
inline constexpr Dimension acceleration = length / pow(time, 2);  // m/s²
inline constexpr Dimension current{.current = 1};                 // A
inline constexpr Dimension voltage{.voltage = 1};                 // V
inline constexpr Dimension resistance = voltage / current;        // ohm

// Unit of an instrument coefficient of the given order: output per g^order, e.g. K_3 of an instrument
// whose output is an angular rate is in rad/s/g^3.
constexpr Dimension coefficient(Dimension output, int order) { return output / pow(acceleration_g, order); }
}  // namespace kind

struct Quantity {
  double value_si;
  Dimension dim;
};

// Parses "number unit", e.g. "2 arcsec" or "0.003 deg/s/g^3", into SI. A bare number is returned as
// dimensionless. Throws UnitError for a malformed or non-finite number, an unknown unit or bad syntax.
Quantity parse_quantity(std::string_view text);

// Parses text and returns its value in SI, requiring the given dimension. quantity_name is used in error
// messages, which also list the accepted units. A bare number is accepted (as SI) only when allow_bare_si
// is true, because a forgotten unit is otherwise an error of a factor of 206265 (arcsec) or 1e6 (µm).
double parse_as(std::string_view text, Dimension expected, std::string_view quantity_name,
                bool allow_bare_si = false);

// Parses a unit expression alone (no number): value_si is the size of one unit in SI, e.g. "deg" gives
// π/180 and kind::angle. The empty string is dimensionless with factor 1. Throws UnitError.
Quantity parse_unit(std::string_view unit);

// Converts between SI and a unit expression; the dimension is not checked. Throw UnitError on a bad unit.
double to_unit(double si, std::string_view unit);
double from_unit(double value, std::string_view unit);

// Prints an SI value in the given unit with printf's %.{significant_digits}g, e.g. "2 arcsec" or
// "0.00291 deg/s/g^3" (an empty unit prints the number alone). Throws UnitError if the unit is unknown or
// its dimension is not dim. 17 significant digits make the text parse back to the same double in the unit.
std::string format_quantity(double si, Dimension dim, std::string_view unit, int significant_digits = 6);

// Comma-separated list of the usual units for a dimension, e.g. "rad, mrad, urad, µrad, deg, arcmin,
// arcsec" for an angle. Every entry is accepted by the parser.
std::string unit_list(Dimension dim);

// SI unit expression of a dimension, e.g. "rad/s/g^3" or "m*s^2/rad^2"; empty for dimensionless.
std::string si_unit(Dimension dim);

// Noun phrase for messages: "an angle", "an angular rate", or "a quantity in rad/s/g^3".
std::string describe(Dimension dim);

// The instrument's output may be counted in pulses, which the units above do not know: "pulse" read as "rad"
// (a pulse is then one unit of an angle-like count), e.g. "pulse/s/g" → "rad/s/g".
std::string pulse_as_rad(std::string_view text);

}  // namespace ccal
