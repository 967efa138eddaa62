#include "ccal/core/units.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

#include "ccal/core/constants.hpp"

namespace ccal {
namespace {

// ---------------------------------------------------------------------------------------------------
// Unit tables

// Which prefixes a base symbol takes. g takes only milli and micro: "kg" and "ng" would read as mass or
// be meaningless for a g-level, whereas mg and µg are the usual units of accelerometer bias.
enum class Prefixes { none, all, small };

struct BaseUnit {
  std::string_view symbol;
  double factor;  // size of one unit in SI
  Dimension dim;
  Prefixes prefixes;
};

constexpr BaseUnit kBaseUnits[] = {
    {"m", 1.0, kind::length, Prefixes::all},
    {"s", 1.0, kind::time, Prefixes::all},
    {"min", 60.0, kind::time, Prefixes::none},
    {"h", 3600.0, kind::time, Prefixes::none},
    {"rad", 1.0, kind::angle, Prefixes::all},
    {"deg", constants::deg, kind::angle, Prefixes::none},
    {"°", constants::deg, kind::angle, Prefixes::none},
    {"arcmin", constants::arcmin, kind::angle, Prefixes::none},
    {"arcsec", constants::arcsec, kind::angle, Prefixes::none},
    {"rpm", constants::rpm, kind::angular_rate, Prefixes::none},
    {"g", 1.0, kind::acceleration_g, Prefixes::small},
    {"gn", 1.0, kind::acceleration_g, Prefixes::none},  // standard gravity as the g of a g-level
    {"ppm", 1e-6, kind::dimensionless, Prefixes::none},
    {"%", 1e-2, kind::dimensionless, Prefixes::none},
    {"A", 1.0, kind::current, Prefixes::all},
    {"V", 1.0, kind::voltage, Prefixes::all},
    {"ohm", 1.0, kind::resistance, Prefixes::all},
};

struct Prefix {
  std::string_view symbol;
  double factor;
  bool small;  // also allowed on bases with Prefixes::small
};

// µ (U+00B5 MICRO SIGN) is what most keyboards produce; μ (U+03BC GREEK SMALL LETTER MU) is what Unicode
// recommends. Both, and the ASCII stand-in u, mean micro.
constexpr Prefix kPrefixes[] = {
    {"n", 1e-9, false}, {"u", 1e-6, true}, {"µ", 1e-6, true},
    {"μ", 1e-6, true},  {"m", 1e-3, true}, {"k", 1e3, false},
};

// Exponents beyond this are certainly typing errors and would only risk overflowing the factor.
constexpr int kMaxExponent = 12;
// A whole expression's exponent of any dimension, likewise.
constexpr int kMaxDimensionExponent = 1000;

struct UnitValue {
  double factor;
  Dimension dim;
};

UnitValue multiply(UnitValue a, UnitValue b) { return {a.factor * b.factor, a.dim * b.dim}; }
UnitValue divide(UnitValue a, UnitValue b) { return {a.factor / b.factor, a.dim / b.dim}; }

UnitValue power(UnitValue u, int n) {
  // Repeated multiplication rather than std::pow: exact for the factors that are powers of 1 and gives
  // the same result on every platform.
  double f = 1.0;
  for (int i = 0; i < std::abs(n); ++i) f *= u.factor;
  return {n < 0 ? 1.0 / f : f, pow(u.dim, n)};
}

std::optional<UnitValue> lookup_symbol(std::string_view symbol) {
  // Whole symbols first, so that "min" is the minute and not a prefixed "in".
  for (const BaseUnit& b : kBaseUnits) {
    if (b.symbol == symbol) return UnitValue{b.factor, b.dim};
  }
  for (const Prefix& p : kPrefixes) {
    if (!symbol.starts_with(p.symbol)) continue;
    const std::string_view rest = symbol.substr(p.symbol.size());
    for (const BaseUnit& b : kBaseUnits) {
      const bool allowed = b.prefixes == Prefixes::all || (b.prefixes == Prefixes::small && p.small);
      if (allowed && b.symbol == rest) return UnitValue{p.factor * b.factor, b.dim};
    }
  }
  return std::nullopt;
}

// Appends item to a separator-joined list.
void append(std::string& list, std::string_view separator, std::string_view item) {
  if (!list.empty()) list.append(separator);
  list.append(item);
}

// All symbols and prefixes, for the message about an unknown unit when no dimension is expected.
std::string known_units() {
  std::string symbols, prefixed_all, prefixed_small;
  for (const BaseUnit& b : kBaseUnits) {
    append(symbols, ", ", b.symbol);
    if (b.prefixes == Prefixes::all) append(prefixed_all, ", ", b.symbol);
    if (b.prefixes == Prefixes::small) append(prefixed_small, ", ", b.symbol);
  }
  std::string all_prefixes, small_prefixes;
  for (const Prefix& p : kPrefixes) {
    append(all_prefixes, ", ", p.symbol);
    if (p.small) append(small_prefixes, ", ", p.symbol);
  }
  return fmt::format("{}; prefixes {} on {}; {} on {}", symbols, all_prefixes, prefixed_all, small_prefixes,
                     prefixed_small);
}

// ---------------------------------------------------------------------------------------------------
// Writing dimensions

// Symbols used to spell a dimension; unit_list tries a few of these systems.
struct UnitSystem {
  std::string_view length, time, angle, g_level, current = "A", voltage = "V";
};
constexpr UnitSystem kSi{"m", "s", "rad", "g"};

// Numerator factors joined by '*', then each denominator factor as "/x^n", e.g. rad/s/g^3 and
// m*s^2/rad^2; with an empty numerator, negative exponents: s^-1.
std::string spell(Dimension d, const UnitSystem& sys) {
  struct Factor {
    std::string_view symbol;
    int exponent;
  };
  // Order: voltage, current, length, angle, time, g-level, which reads naturally for rates and coefficients.
  const Factor factors[] = {{sys.voltage, d.voltage}, {sys.current, d.current}, {sys.length, d.length},
                            {sys.angle, d.angle},     {sys.time, d.time},       {sys.g_level, d.g_level}};
  auto term = [](std::string_view symbol, int n) {
    return n == 1 ? std::string(symbol) : fmt::format("{}^{}", symbol, n);
  };
  std::string numerator;
  for (const Factor& f : factors) {
    if (f.exponent > 0) append(numerator, "*", term(f.symbol, f.exponent));
  }
  if (numerator.empty()) {
    std::string out;
    for (const Factor& f : factors) {
      if (f.exponent < 0) append(out, "*", term(f.symbol, f.exponent));
    }
    return out;
  }
  for (const Factor& f : factors) {
    if (f.exponent < 0) append(numerator, "/", term(f.symbol, -f.exponent));
  }
  return numerator;
}

// ---------------------------------------------------------------------------------------------------
// Parsing

// What an error message needs to know about the parse in progress.
struct Context {
  std::string_view text;      // the whole text given, quoted in messages
  std::string_view name;      // quantity name, may be empty
  const Dimension* expected;  // nullptr when any dimension is accepted
};

[[noreturn]] void fail(const Context& ctx, std::string_view reason) {
  const std::string prefix = ctx.name.empty() ? "" : fmt::format("{}: ", ctx.name);
  throw UnitError(fmt::format("{}'{}': {}", prefix, ctx.text, reason));
}

std::string accepted(const Context& ctx) {
  return ctx.expected ? fmt::format("accepted: {}", unit_list(*ctx.expected))
                      : fmt::format("known units: {}", known_units());
}

// An example of valid input, for messages about missing parts.
std::string example(const Context& ctx, std::string_view number = "1") {
  if (!ctx.expected) return fmt::format("'{} arcsec'", number);
  const std::string list = unit_list(*ctx.expected);
  return fmt::format("'{} {}'", number, list.substr(0, list.find(',')));
}

// What a message about the number says is accepted: "accepted: a finite number and its unit, e.g. '1 s'".
std::string number_accepted(const Context& ctx) {
  return fmt::format("accepted: a finite number and its unit, e.g. {}", example(ctx));
}

// ASCII classification by hand: <cctype> depends on the global locale.
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_ascii_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

// The multi-byte characters allowed in symbols (UTF-8 encoded).
constexpr std::string_view kSymbolRunes[] = {"µ", "μ", "°"};

// Recursive-descent parser over a unit expression; see the grammar in units.hpp.
class UnitParser {
 public:
  UnitParser(std::string_view expr, const Context& ctx) : s_(expr), ctx_(ctx) {}

  UnitValue parse() {
    const UnitValue u = product(0);
    if (!std::isfinite(u.factor) || u.factor == 0.0) fail(ctx_, "unit factor is out of range of double");
    return u;
  }

 private:
  UnitValue product(int depth) {
    UnitValue acc = term(depth);
    for (;;) {
      skip_space();
      if (at_end() || (depth > 0 && peek() == ')')) return acc;
      const char op = peek();
      if (op == ')') fail(ctx_, "unmatched ')'");
      if (op != '*' && op != '.' && op != '/') {
        fail(ctx_, fmt::format("unexpected '{}' after the unit; join unit symbols with '*' or '/'", rest()));
      }
      ++pos_;
      const UnitValue t = term(depth);
      acc = op == '/' ? divide(acc, t) : multiply(acc, t);
      // Bounded so that a long product cannot overflow the integer exponents (no real unit comes near).
      const Dimension& d = acc.dim;
      for (int e : {d.length, d.time, d.angle, d.g_level})
        if (e < -kMaxDimensionExponent || e > kMaxDimensionExponent)
          fail(ctx_,
               fmt::format("a dimension exponent beyond {} in magnitude; accepted: a unit such as m/s^2",
                           kMaxDimensionExponent));
    }
  }

  UnitValue term(int depth) {
    skip_space();
    const UnitValue base = (!at_end() && peek() == '(') ? group(depth) : symbol();
    skip_space();
    if (!at_end() && peek() == '^') {
      ++pos_;
      return power(base, exponent());
    }
    if (rest().starts_with("²")) {
      pos_ += std::string_view("²").size();
      return power(base, 2);
    }
    if (rest().starts_with("³")) {
      pos_ += std::string_view("³").size();
      return power(base, 3);
    }
    return base;
  }

  UnitValue group(int depth) {
    if (depth > 0) fail(ctx_, "nested parentheses are not supported");
    ++pos_;  // '('
    const UnitValue inner = product(depth + 1);
    skip_space();
    if (at_end() || peek() != ')') fail(ctx_, "missing ')'");
    ++pos_;
    return inner;
  }

  UnitValue symbol() {
    const std::size_t start = pos_;
    if (!at_end() && peek() == '%') {
      ++pos_;  // '%' stands alone: it is not a letter and takes no prefix
    } else {
      while (!at_end()) {
        if (is_ascii_letter(peek())) {
          ++pos_;
          continue;
        }
        const auto rune = std::find_if(std::begin(kSymbolRunes), std::end(kSymbolRunes),
                                       [&](std::string_view r) { return rest().starts_with(r); });
        if (rune == std::end(kSymbolRunes)) break;
        pos_ += rune->size();
      }
    }
    const std::string_view sym = s_.substr(start, pos_ - start);
    if (sym.empty()) {
      fail(ctx_, at_end() ? "expected a unit symbol at the end"
                          : fmt::format("expected a unit symbol at '{}'", rest()));
    }
    const std::optional<UnitValue> u = lookup_symbol(sym);
    if (!u) fail(ctx_, fmt::format("unknown unit '{}' ({})", sym, accepted(ctx_)));
    return *u;
  }

  int exponent() {
    skip_space();
    const std::size_t start = pos_;
    if (!at_end() && (peek() == '-' || peek() == '+')) ++pos_;
    while (!at_end() && is_digit(peek())) ++pos_;
    std::string_view digits = s_.substr(start, pos_ - start);
    if (digits.starts_with('+')) digits.remove_prefix(1);  // from_chars takes '-' but not '+'
    int n = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
    if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size()) {
      fail(ctx_, "expected an integer exponent after '^'");
    }
    if (n < -kMaxExponent || n > kMaxExponent) {  // not std::abs: |INT_MIN| overflows
      fail(ctx_, fmt::format("exponent {} is out of range (at most {} in magnitude)", n, kMaxExponent));
    }
    return n;
  }

  void skip_space() {
    while (!at_end() && is_space(peek())) ++pos_;
  }
  bool at_end() const { return pos_ >= s_.size(); }
  char peek() const { return s_[pos_]; }
  std::string_view rest() const { return s_.substr(pos_); }

  std::string_view s_;
  const Context& ctx_;
  std::size_t pos_ = 0;
};

struct Parsed {
  double value_si;
  Dimension dim;
  std::string_view number;  // the number as written, for messages
  std::string_view unit;    // the unit expression as written; empty for a bare number
};

Parsed parse_text(const Context& ctx) {
  const std::string_view s = trim(ctx.text);
  if (s.empty()) fail(ctx, fmt::format("expected a number and a unit; {}", number_accepted(ctx)));

  // from_chars does not take a leading '+', which is natural in configuration files.
  const char* first = s.data();
  const char* const last = s.data() + s.size();
  if (*first == '+' && s.size() > 1 && (is_digit(first[1]) || first[1] == '.')) ++first;
  double value = 0.0;
  const auto [end, ec] = std::from_chars(first, last, value);
  const std::string_view number(s.data(), static_cast<std::size_t>(end - s.data()));
  if (ec == std::errc::invalid_argument) {
    fail(ctx, fmt::format("expected a number before the unit; {}", number_accepted(ctx)));
  }
  if (ec == std::errc::result_out_of_range)
    fail(ctx, fmt::format("'{}' is out of range of double; {}", number, number_accepted(ctx)));
  if (!std::isfinite(value)) fail(ctx, fmt::format("'{}' is not a finite number; {}", number, number_accepted(ctx)));
  // A number running into more number characters ("1.2.3", "1e", "1,5", "0x1f") is malformed; no unit symbol
  // starts with any of these characters.
  if (end != last && std::string_view("0123456789.,eExX+-").find(*end) != std::string_view::npos) {
    const auto word_end = std::find_if(s.begin(), s.end(), is_space);
    fail(ctx,
         fmt::format("malformed number '{}'; {} (a decimal point, no thousands separator)",
                     s.substr(0, static_cast<std::size_t>(word_end - s.begin())), number_accepted(ctx)));
  }

  const std::string_view unit = trim(std::string_view(end, static_cast<std::size_t>(last - end)));
  if (unit.empty()) return {value, kind::dimensionless, number, unit};
  const UnitValue u = UnitParser(unit, ctx).parse();
  const double si = value * u.factor;
  if (!std::isfinite(si)) fail(ctx, "value is out of range of double once converted to SI");
  return {si, u.dim, number, unit};
}

}  // namespace

// ---------------------------------------------------------------------------------------------------
// Public interface

Quantity parse_quantity(std::string_view text) {
  const Parsed p = parse_text(Context{text, {}, nullptr});
  return {p.value_si, p.dim};
}

double parse_as(std::string_view text, Dimension expected, std::string_view quantity_name,
                bool allow_bare_si) {
  const Context ctx{text, quantity_name, &expected};
  const Parsed p = parse_text(ctx);
  if (p.unit.empty()) {
    if (allow_bare_si) return p.value_si;  // the caller has declared the bare number to be in SI
    fail(ctx, fmt::format("a unit is required, e.g. {} ({})", example(ctx, p.number), accepted(ctx)));
  }
  if (p.dim != expected) {
    fail(ctx, fmt::format("unit '{}' is {}, expected {} ({})", p.unit, describe(p.dim), describe(expected),
                          accepted(ctx)));
  }
  return p.value_si;
}

Quantity parse_unit(std::string_view unit) {
  const Context ctx{unit, {}, nullptr};
  const std::string_view u = trim(unit);
  if (u.empty()) return {1.0, kind::dimensionless};
  const UnitValue v = UnitParser(u, ctx).parse();
  return {v.factor, v.dim};
}

double to_unit(double si, std::string_view unit) { return si / parse_unit(unit).value_si; }

double from_unit(double value, std::string_view unit) { return value * parse_unit(unit).value_si; }

std::string format_quantity(double si, Dimension dim, std::string_view unit, int significant_digits) {
  const Quantity u = parse_unit(unit);
  if (u.dim != dim) {
    throw UnitError(fmt::format("cannot write {} in '{}', which is {} (accepted: {})", describe(dim), unit,
                                describe(u.dim), unit_list(dim)));
  }
  // printf treats a precision of 0 as 1 for %g; fmt rejects negative precisions, so clamp to 1.
  const std::string number = fmt::format("{:.{}g}", si / u.value_si, std::max(1, significant_digits));
  const std::string_view trimmed = trim(unit);
  return trimmed.empty() ? number : fmt::format("{} {}", number, trimmed);
}

std::string unit_list(Dimension dim) {
  // The quantities ccal uses get a hand-picked list, in the order a user would look for them.
  if (dim == kind::angle) return "rad, mrad, urad, µrad, deg, arcmin, arcsec";
  if (dim == kind::length) return "m, mm, um, µm, nm, km";
  if (dim == kind::time) return "s, ms, us, min, h";
  if (dim == kind::angular_rate) return "rad/s, mrad/s, urad/s, deg/s, deg/h, rpm";
  if (dim == kind::acceleration_g) return "g, mg, ug, µg";
  if (dim == kind::acceleration) return "m/s^2, mm/s^2, um/s^2";
  if (dim == kind::dimensionless) return "ppm, %";
  if (dim == kind::current) return "A, mA, uA, µA";
  if (dim == kind::voltage) return "V, mV, uV, µV";
  if (dim == kind::resistance) return "ohm, kohm";

  // Anything else (coefficients per g^n, m/(rad/s)^2, ...) is spelled in SI and in the common variants
  // of the base units that appear in it; each variant is added only if it changes a symbol that occurs,
  // so none repeats.
  std::string out = spell(dim, kSi);
  if (dim.angle != 0) append(out, ", ", spell(dim, {"m", "s", "deg", "g"}));
  if (dim.angle * dim.time < 0) append(out, ", ", spell(dim, {"m", "h", "deg", "g"}));  // rate: deg/h
  if (dim.length != 0) {
    append(out, ", ", spell(dim, {"mm", "s", "rad", "g"}));
    append(out, ", ", spell(dim, {"um", "s", "rad", "g"}));
  }
  return out;
}

std::string si_unit(Dimension dim) { return spell(dim, kSi); }

std::string describe(Dimension dim) {
  if (dim == kind::angle) return "an angle";
  if (dim == kind::length) return "a length";
  if (dim == kind::time) return "a time";
  if (dim == kind::angular_rate) return "an angular rate";
  if (dim == kind::acceleration_g) return "a g-level";
  if (dim == kind::acceleration) return "an acceleration";
  if (dim == kind::dimensionless) return "dimensionless";
  if (dim == kind::current) return "a current";
  if (dim == kind::voltage) return "a voltage";
  return fmt::format("a quantity in {}", si_unit(dim));
}

std::string pulse_as_rad(std::string_view text) {
  std::string out(text);
  for (std::size_t pos = out.find("pulse"); pos != std::string::npos; pos = out.find("pulse", pos + 3))
    out.replace(pos, 5, "rad");
  return out;
}

}  // namespace ccal
