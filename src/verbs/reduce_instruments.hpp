#pragma once
// `reduce` of a test of several instruments (Config::instruments), private to the library: each instrument's
// reduction of the same logs through its own output column, and the covariance of their coefficients.
#include "ccal/verbs/reduce.hpp"

namespace ccal::verbs {

ReduceResult reduce_instruments(const Config& config, const ReduceOptions& options);

}  // namespace ccal::verbs
