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

constexpr std::string_view kDerivativeNames[] = {"automatic", "linearised"};  // DerivativeMethod's order

constexpr OptionSpec<BudgetOptions> kBudgetRows[] = {
    rows::mode<&BudgetOptions::mode>(
        "Kinematics: exact (full chain) or paper (Wang & Ren first-order rules); "
        "default: the configuration's [identification] mode"),
    rows::coverage_probability(&BudgetOptions::coverage_probability,
                               "Coverage probability p of the expanded uncertainty U = k u, in [0.5, 1): k = "
                               "1.96 for 0.95, the normal LPU total's"),
    rows::coverage_factor(&BudgetOptions::coverage_factor),
    {"derivatives", enum_member<&BudgetOptions::derivatives>(kDerivativeNames), "METHOD",
     "How the sensitivities are differentiated: linearised (closed-form chain Jacobian at zero errors, AD "
     "elsewhere; fast) or automatic (forward-mode AD through everything); same numbers"},
};

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

OptionTable<BudgetOptions> options_of(std::type_identity<BudgetOptions>) { return kBudgetRows; }

BudgetResult budget(const Config& config, const BudgetOptions& options) {
  check_options(options, option_table<BudgetOptions>());
  rows::check_coverage_choice(options.coverage_probability, options.coverage_factor);
  if (config.instruments.size() > 1) return budget_of_instruments(config, options);
  if (config.tolerances.empty())
    throw InputError(config.source + ": [tolerances] is empty; the budget needs at least one source");
  ccal::BudgetOptions bo;
  bo.mode = options.mode.value_or(config.mode);
  bo.coverage_probability = options.coverage_probability;
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
    throw plan_cannot_identify(e);
  }
  check_finite(config, r.budget);  // never a nan or inf returned as a result
  r.known_error_bias = known_error_shift(config, bo.mode);
  return r;
}

}  // namespace ccal::verbs
