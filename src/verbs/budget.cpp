#include "ccal/verbs/budget.hpp"

#include <cmath>
#include <string>

#include "ccal/core/errors.hpp"
#include "result_checks.hpp"

namespace ccal::verbs {

BudgetResult budget(const Config& config, const BudgetOptions& options) {
  if (!(std::isfinite(options.coverage_factor) && options.coverage_factor > 0))
    throw InputError("--coverage: " + std::to_string(options.coverage_factor) +
                     " is not a positive number; accepted: a coverage factor such as 2");
  if (config.tolerances.empty())
    throw InputError(config.source + ": [tolerances] is empty; the budget needs at least one source");
  ccal::BudgetOptions bo;
  bo.mode = options.mode.value_or(config.mode);
  bo.coverage_factor = options.coverage_factor;
  bo.derivatives = options.derivatives;
  bo.compare_with_paper = options.compare_with_paper;
  BudgetResult r;
  r.config = config;
  // A term the plan cannot see would get a budget of round-off: refuse it first.
  r.observability = assess_plan(config, bo.mode);
  try {
    r.budget = compute_budget(config, bo);
  } catch (const IllPosedFit& e) {
    throw IllPosedFit(std::string("the test plan cannot identify the configured terms: ") + e.what(),
                      e.terms());
  }
  check_finite(config, r.budget);  // never a nan or inf returned as a result
  return r;
}

}  // namespace ccal::verbs
