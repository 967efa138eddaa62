#pragma once
// The measurement model of the Monte Carlo method's own tests: the output is the input, y = x, so that the
// outputs' distribution is the inputs' and every figure has a closed form; and the sources those tests draw.
#include <algorithm>
#include <span>
#include <string>
#include <utility>

#include "ccal/setup/tolerance.hpp"

namespace ccal::test {

inline void identity(std::span<const double> x, std::span<double> y) {
  std::copy(x.begin(), x.end(), y.begin());
}

// A source of the Monte Carlo: its id, bound, distribution and correlation group.
inline Tolerance source(std::string id, double bound, Distribution d, std::string group = "") {
  Tolerance t;
  t.id = std::move(id);
  t.bound = bound;
  t.distribution = d;
  t.group = std::move(group);
  return t;
}

}  // namespace ccal::test
