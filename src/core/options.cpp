#include "ccal/core/options.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>
#include <utility>

namespace ccal {

namespace {
constexpr char kNameMark = '\x1f';  // around an option's field inside a problem's text

// The text with each marked field replaced by spelling(field).
std::string with_names(std::string_view text, const std::function<std::string(std::string_view)>& spelling) {
  std::string out;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t open = text.find(kNameMark, at);
    const std::size_t close = open == std::string_view::npos ? open : text.find(kNameMark, open + 1);
    if (close == std::string_view::npos) {
      out += text.substr(at);
      break;
    }
    out += text.substr(at, open - at);
    out += spelling(text.substr(open + 1, close - open - 1));
    at = close + 1;
  }
  return out;
}

std::string as_field(std::string_view field) { return std::string(field); }
}  // namespace

OptionError::OptionError(std::string field, std::string value, std::string problem)
    : InputError(field + ": " + (value.empty() ? "" : value + " ") + with_names(problem, as_field)),
      field_(std::move(field)),
      value_(std::move(value)),
      problem_(std::move(problem)) {}

std::string OptionError::name(std::string_view field) { return kNameMark + std::string(field) + kNameMark; }

std::string OptionError::worded(const std::function<std::string(std::string_view)>& spelling) const {
  return spelling(field_) + ": " + (value_.empty() ? "" : value_ + " ") + with_names(problem_, spelling);
}

bool OptionRange::accepts(double x) const noexcept {
  if (also && x == *also) return true;
  if (!std::isfinite(x)) return false;
  const bool above = low_open ? x > low : x >= low;
  const bool below = high_open ? x < high : x <= high;
  return above && below;
}

namespace {
// The one table of fields whose flag is not the field's name: lists given one element per flag.
constexpr std::pair<std::string_view, std::string_view> kFlagSpellings[] = {
    {"targets", "target"},
    {"logs", "log"},
};
}  // namespace

std::string option_flag(std::string_view field, std::string_view prefix) {
  // The spelling applies to the field's last word too: report's allocate_targets → --allocate-target.
  std::string name(field);
  for (const auto& [from, to] : kFlagSpellings)
    if (field == from || (field.ends_with(from) && field.size() > from.size() &&
                          field[field.size() - from.size() - 1] == '_'))
      name = std::string(field.substr(0, field.size() - from.size())) + std::string(to);
  name = std::string(prefix) + name;
  for (char& c : name)
    if (c == '_') c = '-';
  return "--" + name;
}

std::string option_number_text(double x) {
  if (std::isfinite(x) && x == std::floor(x) && std::fabs(x) < 1e20) return fmt::format("{:.0f}", x);
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return ec == std::errc() ? std::string(buffer, end) : fmt::format("{}", x);
}

std::string OptionRange::text() const {
  const bool bounded_low = low > -1e308, bounded_high = high < 1e308;
  std::string range;
  if (bounded_low && bounded_high && !low_open && !high_open)
    range = option_number_text(low) + " to " + option_number_text(high);
  else if (bounded_low && bounded_high)
    range = fmt::format("a number in {}{}, {}{}", low_open ? "(" : "[", option_number_text(low),
                        option_number_text(high), high_open ? ")" : "]");
  else if (bounded_low)
    range = fmt::format("a number {} {}", low_open ? ">" : ">=", option_number_text(low));
  else if (bounded_high)
    range = fmt::format("a number {} {}", high_open ? "<" : "<=", option_number_text(high));
  else
    range = "a finite number";
  std::string text =
      also ? fmt::format("{} ({}) or {}", option_number_text(*also), also_meaning, range) : range;
  if (!example.empty()) text += fmt::format(", e.g. {}", example);
  if (!note.empty()) text += fmt::format("; {}", note);
  return text;
}

std::string OptionRange::interval() const {
  const bool bounded_low = low > -1e308, bounded_high = high < 1e308;
  if (bounded_low && bounded_high)
    return fmt::format("{}{}, {}{}", low_open ? "(" : "[", option_number_text(low), option_number_text(high),
                       high_open ? ")" : "]");
  if (bounded_low) return fmt::format("{} {}", low_open ? ">" : "≥", option_number_text(low));
  if (bounded_high) return fmt::format("{} {}", high_open ? "<" : "≤", option_number_text(high));
  return "a finite number";
}

std::string option_help(std::string_view help, const OptionRange& range) {
  constexpr std::string_view kMark = "{range}";
  std::string text(help);
  for (auto at = text.find(kMark); at != std::string::npos; at = text.find(kMark, at))
    text.replace(at, kMark.size(), range.interval());
  return text;
}

void check_option_value(std::string_view field, double value, const std::string& value_text,
                        const OptionRange& range) {
  if (!range.accepts(value))
    throw OptionError(std::string(field), value_text, "is out of range; accepted: " + range.text());
}

}  // namespace ccal

namespace ccal {

namespace {

// Without surrounding blanks and a leading '+' (which std::from_chars does not take).
std::string_view trimmed(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  return text;
}

// The text as the user wrote it, quoted, for a message.
std::string quoted(std::string_view text) { return "'" + std::string(text) + "'"; }

// A whole number written as text: exact digits, or a float notation whose value is a whole number.
std::optional<double> whole_number(std::string_view text, bool& integral) {
  double x = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), x);
  if (ec == std::errc::result_out_of_range && end == text.data() + text.size()) {
    // Beyond double's range: a huge whole number (beyond every option's range), or a tiny fraction.
    const bool tiny = text.find("e-") != std::string_view::npos || text.find("E-") != std::string_view::npos;
    integral = !tiny;
    const double huge = std::numeric_limits<double>::infinity();
    return tiny ? 0.5 : text.front() == '-' ? -huge : huge;
  }
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(x)) return std::nullopt;
  integral = x == std::floor(x);
  return x;
}

}  // namespace

std::int64_t parse_integer_option(std::string_view field, std::string_view text, std::int64_t low,
                                  std::int64_t high) {
  const std::string_view t = trimmed(text);
  const std::string accepted = fmt::format("accepted: a whole number from {} to {}", low, high);
  std::int64_t value = 0;
  if (!t.empty()) {
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec == std::errc() && end == t.data() + t.size()) {
      if (value < low || value > high)
        throw OptionError(std::string(field), std::string(t), "is out of range; " + accepted);
      return value;
    }
  }
  bool integral = false;
  const std::optional<double> x = t.empty() ? std::nullopt : whole_number(t, integral);
  if (!x) throw OptionError(std::string(field), quoted(text), "is not a number; " + accepted);
  if (!integral) throw OptionError(std::string(field), std::string(t), "is not a whole number; " + accepted);
  // ±2^63 bound the conversion: the doubles below 2^63 in magnitude are exact 64-bit integers.
  constexpr double kTwo63 = 9223372036854775808.0;
  if (*x >= kTwo63 || *x < -kTwo63 || std::int64_t(*x) < low || std::int64_t(*x) > high)
    throw OptionError(std::string(field), std::string(t), "is out of range; " + accepted);
  return std::int64_t(*x);
}

std::uint64_t parse_unsigned_option(std::string_view field, std::string_view text) {
  const std::string_view t = trimmed(text);
  const std::string accepted = "accepted: a whole number from 0 to 18446744073709551615";
  std::uint64_t value = 0;
  if (!t.empty() && t.front() != '-' && t.front() != '+') {
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec == std::errc() && end == t.data() + t.size()) return value;
    if (ec == std::errc::result_out_of_range && end == t.data() + t.size())
      throw OptionError(std::string(field), std::string(t), "is out of range; " + accepted);
  }
  bool integral = false;
  const std::optional<double> x = t.empty() ? std::nullopt : whole_number(t, integral);
  if (!x) throw OptionError(std::string(field), quoted(text), "is not a number; " + accepted);
  if (!integral) throw OptionError(std::string(field), std::string(t), "is not a whole number; " + accepted);
  // 2^64 is the first double beyond the range; every whole double below it converts exactly.
  if (*x < 0 || *x >= 18446744073709551616.0)
    throw OptionError(std::string(field), std::string(t), "is out of range; " + accepted);
  return std::uint64_t(*x);
}

namespace {

// A refusal of the integer parsers (problem "is …; accepted: a whole number from <type's limits>") said with
// the option's own range: an out-of-range whole number as check_options says it, anything else (2.5, nan) as
// "a whole number" of that range. A range left unbounded (a seed) keeps the type's words.
OptionError in_range_words(const OptionError& e, const OptionRange& range) {
  if (!(range.low > -1e308 || range.high < 1e308)) return e;
  const std::string& problem = e.problem();
  const std::string what = problem.substr(0, problem.find("; accepted: "));
  if (what == "is out of range")
    return OptionError(e.field(), e.value(), what + "; accepted: " + range.text());
  const bool plain = !range.also && !range.low_open && !range.high_open && range.low > -1e308 &&
                     range.high < 1e308 && range.example.empty() && range.note.empty();
  return OptionError(e.field(), e.value(),
                     what + "; accepted: a whole number" + (plain ? " from " : ", ") + range.text());
}

}  // namespace

std::uint64_t parse_unsigned_option(std::string_view field, std::string_view text, const OptionRange& range) {
  try {
    return parse_unsigned_option(field, text);
  } catch (const OptionError& e) {
    throw in_range_words(e, range);
  }
}

std::int64_t parse_integer_option(std::string_view field, std::string_view text, std::int64_t low,
                                  std::int64_t high, const OptionRange& range) {
  try {
    return parse_integer_option(field, text, low, high);
  } catch (const OptionError& e) {
    throw in_range_words(e, range);
  }
}

double parse_real_option(std::string_view field, std::string_view text) {
  const std::string_view t = trimmed(text);
  double x = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size() || !std::isfinite(x))
    throw OptionError(std::string(field), quoted(text), "is not a finite number; accepted: e.g. 0.5 or 2e-3");
  return x;
}

double parse_real_option(std::string_view field, std::string_view text, const OptionRange& range) {
  try {
    return parse_real_option(field, text);
  } catch (const OptionError& e) {
    if (!(range.low > -1e308 || range.high < 1e308)) throw;
    throw OptionError(e.field(), e.value(), "is not a finite number; accepted: " + range.text());
  }
}

std::vector<std::string> split_option_list(std::string_view field, std::string_view text) {
  std::vector<std::string> items;
  for (std::size_t begin = 0;;) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    if (end == begin)
      throw OptionError(std::string(field), "'" + std::string(text) + "'",
                        "has an empty item; accepted: items separated by single commas, e.g. K0,K2,K3");
    items.emplace_back(text.substr(begin, end - begin));
    if (end == text.size()) return items;
    begin = end + 1;
  }
}

std::size_t parse_choice_option(std::string_view field, std::string_view text,
                                std::span<const std::string_view> names) {
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] == text) return k;
  std::string accepted;
  for (std::string_view name : names) accepted += (accepted.empty() ? "'" : ", '") + std::string(name) + "'";
  throw OptionError(std::string(field), quoted(text), "is not accepted; accepted: " + accepted);
}

}  // namespace ccal
