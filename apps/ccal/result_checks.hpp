#pragma once
// No nan or inf is ever printed as a result: the checks a command makes before writing its output. Each throws
// InputError naming the configuration, the coefficient and the first source whose figures are not finite
// (input beyond what double precision can carry, e.g. a tolerance of 1e200 m).

#include "ccal/allocate.hpp"
#include "ccal/budget.hpp"
#include "ccal/config.hpp"

namespace ccal::cli {

void check_finite(const Config& cfg, const BudgetResult& budget);
void check_finite(const Config& cfg, const AllocationResult& allocation);

}  // namespace ccal::cli
