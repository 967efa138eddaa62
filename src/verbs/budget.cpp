#include "ccal/verbs/budget.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/uncertainty/statement.hpp"
#include "result_checks.hpp"

namespace ccal::verbs {

namespace {

// A test of several instruments: the budget of each, and the covariance of all their coefficients.
BudgetResult budget_of_instruments(const Config& config, const BudgetOptions& options) {
  BudgetResult r;
  r.config = config;
  for (const Config& one : config.instruments) {
    try {
      r.instruments.push_back(budget(one, options));
    } catch (const OptionError&) {
      throw;
    } catch (const InputError& e) {
      throw InputError(fmt::format("instrument '{}': {}", one.instrument_id, e.what()));
    }
  }
  // The LPU alone (no trials): its diagonal blocks are the budgets' tolerance parts.
  r.covariance = instrument_covariance(config.instruments, options.mode.value_or(config.mode), 0, 0, 0);
  return r;
}

}  // namespace

BudgetResult budget(const Config& config, const BudgetOptions& options) {
  check_options(options, option_table<BudgetOptions>());
  rows::check_coverage_choice(options.coverage_probability, options.coverage_factor);
  if (config.instruments.size() > 1) return budget_of_instruments(config, options);
  if (config.tolerances.empty())
    throw InputError(config.source + ": [tolerances] is empty; the budget needs at least one source");
  ccal::BudgetOptions bo = options;
  bo.mode = options.mode.value_or(config.mode);
  BudgetResult r;
  r.config = config;
  // A term the plan cannot see would get a budget of round-off: refuse it first.
  r.observability = assess_plan(config, *bo.mode);
  try {
    r.budget = compute_budget(config, bo);
  } catch (const IllPosedFit& e) {
    throw plan_cannot_identify(e);
  }
  check_finite(config, r.budget);  // never a nan or inf returned as a result
  r.known_error_bias = known_error_shift(config, *bo.mode);
  return r;
}

}  // namespace ccal::verbs
