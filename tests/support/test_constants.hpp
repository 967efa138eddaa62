#pragma once
// The numbers many tests use, defined once: each folder's tests compile together in one unit
// (docs/testing.md), where a second definition would clash. Written from their definitions, not taken from
// the library, so that a test does not check the library against itself.
#include <numbers>

namespace ccal::test {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = std::numbers::pi / 180.0;  // one degree in radians
// The standard normal distribution's 97.5 % quantile, Φ⁻¹(0.975), to 16 digits: k for p = 95 % at ν = ∞.
inline constexpr double kZ975 = 1.959963984540054;

}  // namespace ccal::test
