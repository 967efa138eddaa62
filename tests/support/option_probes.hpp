#pragma once
// Values on both sides of each end of an option row's range (core/options.hpp OptionRange), each with whether
// the row accepts it: what a test feeds an engine to show that it refuses exactly what the row refuses.

#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>
#include <variant>
#include <vector>

#include "ccal/core/options.hpp"

namespace ccal::test {

struct OptionProbe {
  double value;
  bool accepted;  // by the row's range (OptionRange::accepts)
};

// For a whole-number option (`whole`) the neighbours of an end are ±1, else the next doubles. The accepted
// extra value (e.g. 0: none) too. Ends at ±1e308 (an unbounded side) are not probed.
inline std::vector<OptionProbe> option_probes(const OptionRange& range, bool whole) {
  std::vector<double> values;
  const double inf = std::numeric_limits<double>::infinity();
  auto below = [&](double x) { return whole ? x - 1 : std::nextafter(x, -inf); };
  auto above = [&](double x) { return whole ? x + 1 : std::nextafter(x, inf); };
  if (range.low > -1e308) values.insert(values.end(), {below(range.low), range.low, above(range.low)});
  if (range.high < 1e308) values.insert(values.end(), {below(range.high), range.high, above(range.high)});
  if (range.also) values.push_back(*range.also);
  std::vector<OptionProbe> probes;
  for (double v : values) probes.push_back({v, range.accepts(v)});
  return probes;
}

// Sets a numeric row's field (a number or an optional number) to `value`; returns whether the row is one
// (false for flags, texts, lists and choices, which have no numeric range to probe).
template <class Options>
bool set_numeric_option(Options& o, const OptionSpec<Options>& row, double value) {
  return std::visit(
      [&](const auto& member) {
        if constexpr (requires { typename std::remove_cvref_t<decltype(member)>::type; }) {
          using T = typename std::remove_cvref_t<decltype(member)>::type;
          if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
            member.of(o) = static_cast<T>(value);
            return true;
          } else if constexpr (requires { typename T::value_type; }) {
            using V = typename T::value_type;
            if constexpr (std::is_same_v<T, std::optional<V>> && std::is_arithmetic_v<V>) {
              member.of(o) = static_cast<V>(value);
              return true;
            }
          }
        }
        return false;
      },
      row.member);
}

template <class Options>
bool whole_number_option(const OptionSpec<Options>& row) {
  return !std::holds_alternative<OptionField<Options, double>>(row.member) &&
         !std::holds_alternative<OptionField<Options, std::optional<double>>>(row.member);
}

}  // namespace ccal::test
