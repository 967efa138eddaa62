#include "ccal/verbs/allocate.hpp"

#include <fmt/format.h>

#include <cmath>

#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "result_checks.hpp"

namespace ccal::verbs {

AllocateResult allocate(const Config& config, const AllocateOptions& o) {
  require_one_instrument(config, "allocate");
  AllocateResult r;
  r.config = config;
  r.allocation = allocate_tolerances(config, o);
  check_finite(config, r.allocation);  // never a nan or inf returned as a result
  return r;
}

}  // namespace ccal::verbs
