#pragma once
// Values on both sides of each end of an option row's range (core/options.hpp OptionRange), each with whether
// the row accepts it: what a test feeds an engine to show that it refuses exactly what the row refuses.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
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

// Options whose coverage interval the engine can form at every probe, or std::nullopt for a probe of p that
// is not the row's to decide. p = ½ lets M = 2 trials give the interval's ends (q = round(pM) = 1 ≤ M − 1), so
// that only the probed row decides; probing p, M = 10⁶ (set in `trials`), which gives them for p up to
// 1 − 5·10⁻⁷; above that the interval's rule for M refuses a p the row accepts.
template <class Options, class Count>
std::optional<Options> options_for_probe(const OptionSpec<Options>& row, const OptionProbe& probe,
                                         Count Options::*trials) {
  Options o;
  o.coverage_probability = 0.5;
  if (row.field == "coverage_probability") {
    o.*trials = 1000000;
    if (probe.accepted && probe.value > 1 - 5e-7) return std::nullopt;
  }
  return o;
}

// Every numeric row's probes given to an engine: options from `make(row, probe)` (std::nullopt: a probe not the
// row's to decide, left out) with the probe's value set, then `refusal(options)`, the field the engine refuses
// or `passed` when it takes them, expected to be the row's field exactly when the row refuses the value.
// Returns the number of probes given.
template <class Options, class Make, class Refusal>
int probe_every_numeric_row(Make make, Refusal refusal, std::string_view passed) {
  int probed = 0;
  for (const OptionSpec<Options>& row : option_table<Options>()) {
    for (const OptionProbe& probe : option_probes(row.range, whole_number_option(row))) {
      std::optional<Options> options = make(row, probe);
      if (!options || !set_numeric_option(*options, row, probe.value)) continue;
      SCOPED_TRACE(std::string(row.field) + " = " + std::to_string(probe.value));
      EXPECT_EQ(refusal(*options), probe.accepted ? std::string(passed) : std::string(row.field));
      ++probed;
    }
  }
  return probed;
}

}  // namespace ccal::test
