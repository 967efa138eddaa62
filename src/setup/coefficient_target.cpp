// A target on a free coefficient as a user writes it ("K3=1e-6" in the coefficient's display unit, or with a
// unit), read into SI.
#include "ccal/setup/coefficient_target.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>

#include "../core/text_trim.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/core/units.hpp"
#include "ccal/model/instrument.hpp"

namespace ccal {
namespace {

using detail::trim_blanks;

bool is_bare_number(std::string_view s, double& value) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return ec == std::errc() && end == s.data() + s.size();
}

}  // namespace

AllocationTarget parse_allocation_target(std::string_view text, const std::vector<std::string>& coefficients,
                                         const std::vector<std::string>& units, std::string_view field) {
  const std::string option(field);
  const auto eq = text.find('=');
  const std::string_view name = trim_blanks(text.substr(0, eq));
  std::string_view value =
      eq == std::string_view::npos ? std::string_view() : trim_blanks(text.substr(eq + 1));
  if (value.size() >= 2 && (value.front() == '"' || value.front() == '\'') && value.back() == value.front())
    value = trim_blanks(value.substr(1, value.size() - 2));
  // Several targets in one ("K3=1e-3,K2=1e-5"): each is its own, as its number would be malformed.
  if (eq != std::string_view::npos && value.find('=') != std::string_view::npos)
    throw OptionError(option, fmt::format("'{}'", text),
                      "holds more than one target; accepted: one target each, COEFFICIENT=VALUE, e.g. K3=1e-6 "
                      "(the command line's flag repeated, or one entry per coefficient)");
  if (eq == std::string_view::npos || name.empty() || value.empty())
    throw OptionError(option, fmt::format("'{}'", text),
                      "is not COEFFICIENT=VALUE; accepted: e.g. K3=1e-6 (in the coefficient's unit) or "
                      "\"K3=1e-6 deg/s/g^3\"");
  const auto it = std::find(coefficients.begin(), coefficients.end(), name);
  if (it == coefficients.end()) {
    if (parse_term(name))
      throw OptionError(option, std::string(name),
                        fmt::format("is not a free term of the identification; accepted: {}",
                                    fmt::join(coefficients, ", ")));
    throw OptionError(option, "",
                      fmt::format("unknown coefficient '{}'; accepted: the free terms {}", name,
                                  fmt::join(coefficients, ", ")));
  }
  const auto k = std::size_t(it - coefficients.begin());
  const std::string unit = pulse_as_rad(units[k]);
  AllocationTarget t;
  t.coefficient = std::string(name);
  t.text = std::string(text);
  t.field = option;
  double bare = 0;
  try {
    const Dimension dim = parse_unit(unit).dim;
    if (is_bare_number(value, bare)) {
      t.expanded = from_unit(bare, unit);
    } else {
      const Quantity q = parse_quantity(pulse_as_rad(value));
      if (!(q.dim == dim))
        throw InputError(fmt::format("'{}' is {}, expected {} such as {}", value, describe(q.dim),
                                     describe(dim), units[k]));
      t.expanded = q.value_si;
    }
  } catch (const InputError& e) {
    throw OptionError(option, "", fmt::format("{}: {}", name, e.what()));
  }
  if (!(std::isfinite(t.expanded) && t.expanded > 0))
    throw OptionError(option, "",
                      fmt::format("{}: the target must be a positive expanded uncertainty, got '{}'; accepted: a "
                                  "positive finite number, e.g. {}=1e-6 (in {})",
                                  name, value, name, units[k]));
  return t;
}

}  // namespace ccal
