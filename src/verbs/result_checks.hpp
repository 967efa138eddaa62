#pragma once
// No nan or inf is ever printed as a result: the checks a verb makes before it returns. Each throws
// InputError naming the configuration, the coefficient and the first source whose figures are not finite
// (input beyond what double precision can carry, e.g. a tolerance of 1e200 m).

#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/allocate.hpp"
#include "ccal/uncertainty/budget.hpp"

namespace ccal::verbs {

void check_finite(const Config& cfg, const ccal::BudgetDetail& budget);
void check_finite(const Config& cfg, const ccal::AllocationDetail& allocation);

}  // namespace ccal::verbs
