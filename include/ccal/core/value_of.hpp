#pragma once
// The double value of a scalar: the number itself, or the value of a (nested) automatic-differentiation
// scalar with its derivatives stripped. Needs nothing of AutoDiff, so a header that only reads values (a
// diagnostic, a rank test) does not pull the AutoDiff module in.

#include <type_traits>

namespace ccal {

template <class T>
double value_of(const T& x) {
  if constexpr (std::is_arithmetic_v<T>)
    return static_cast<double>(x);
  else
    return value_of(x.value());
}

}  // namespace ccal
