#pragma once
// `ccal budget` as a library call: what each centrifuge tolerance costs every identified coefficient (the law
// of propagation of uncertainty, docs/model.md §10.1), with the per-term observability of the plan (§14).

#include <optional>

#include "ccal/core/model_mode.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/verbs/instrument_covariance.hpp"
#include "ccal/verbs/observability_report.hpp"
#include "ccal/uncertainty/option_rows.hpp"

namespace ccal::verbs {

// The options are the engine's (uncertainty/budget.hpp: BudgetOptions and its table): mode, coverage_probability,
// coverage_factor, derivatives, compare_with_paper.

struct BudgetResult {
  Config config;                      // the configuration budgeted
  ccal::BudgetDetail budget;          // per source and per coefficient (SI, with display scales)
  ObservabilityReport observability;  // of the free terms under this plan
  // The bias of the coefficients from the configuration's known [errors] when the model leaves them out
  // (SI, per coefficient; uncertainty/statement.hpp known_error_shift): empty when compensated or none.
  Eigen::VectorXd known_error_bias;
  // A test of several instruments (two or more [[instruments]]): each one's budget, exactly what budget() of
  // that instrument's configuration (config.instruments[i]) gives, in the file's order; and the tolerances'
  // covariance of all their coefficients (the LPU, verbs/instrument_covariance.hpp: the machine's errors are one
  // for all). The fields above are then empty: config is the whole configuration. Empty and unset for one
  // instrument.
  std::vector<BudgetResult> instruments;
  std::optional<InstrumentCovariance> covariance;
};

// Throws InputError (OptionError naming the field) for a coverage probability outside (0, 1), a coverage
// factor below 1 or not finite, both a coverage factor and a coverage probability given, an empty [tolerances], a term the plan
// cannot observe or identify, or a result that is not finite (tolerances beyond double precision); for a test
// of several instruments, whatever it refuses of one of them, the message naming that instrument.
BudgetResult budget(const Config& config, const BudgetOptions& options = {});

}  // namespace ccal::verbs
