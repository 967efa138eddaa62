#include "ccal/verbs/montecarlo.hpp"

#include <fmt/format.h>

#include "ccal/core/errors.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/uncertainty/gaussian_copula.hpp"

namespace ccal::verbs {

namespace {

// The engine's rows that a front end sets, then the kinematics.
constexpr auto kMonteCarloRows =
    join_rows(lifted_rows<&MonteCarloOptions::propagation, kPropagationRows>(),
              std::to_array({rows::mode<&MonteCarloOptions::mode>()}));

}  // namespace

OptionTable<MonteCarloOptions> options_of(std::type_identity<MonteCarloOptions>) { return kMonteCarloRows; }

MonteCarloResult monte_carlo(const Config& config, const MonteCarloOptions& o) {
  require_one_instrument(config, "montecarlo");
  check_options(o, option_table<MonteCarloOptions>());  // the rows; the engine checks the threads it starts
  // With digits the trials given are each stage's, which the engine raises to at least kDefaultMonteCarloStage:
  // a smaller number from the user would be raised without a word (the engine's tests use the raise).
  const PropagationOptions& p = o.propagation;
  if (p.digits > 0 && p.trials && *p.trials < kDefaultMonteCarloStage)
    throw OptionError("trials", option_number_text(double(*p.trials)),
                      fmt::format("is, with {} {}, the size of each stage, which is at least {}; accepted: {} or "
                                  "more, or {} left out (stages of {})",
                                  OptionError::name("digits"), p.digits, kDefaultMonteCarloStage,
                                  kDefaultMonteCarloStage, OptionError::name("trials"), kDefaultMonteCarloStage));
  if (config.tolerances.empty())
    throw InputError(config.source + ": [tolerances] is empty; the Monte Carlo needs at least one source");
  gaussian_copula(config);  // a pair the copula cannot draw is refused before the budget's work
  const ModelMode mode = o.mode.value_or(config.mode);
  ccal::BudgetOptions bo;
  bo.mode = mode;
  bo.compare_with_paper = false;
  MonteCarloResult r;
  r.config = config;
  CalibrationModel model;
  try {
    r.budget = compute_budget(config, bo);
    model = calibration_model(config, mode);
  } catch (const IllPosedFit& e) {
    throw plan_cannot_identify(e);
  }
  r.monte_carlo = run_monte_carlo(monte_carlo_sources(config), config.correlations, model.n_outputs(),
                                  model.output_names(), calibration_trial(model), o.propagation,
                                  &r.budget.standard_uncertainty);
  return r;
}

}  // namespace ccal::verbs
