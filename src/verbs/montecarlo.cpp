#include "ccal/verbs/montecarlo.hpp"

#include <fmt/format.h>

#include "ccal/core/errors.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/uncertainty/gaussian_copula.hpp"

namespace ccal::verbs {

namespace {

constexpr OptionSpec<MonteCarloOptions> kMonteCarloRows[] = {
    {"trials", &MonteCarloOptions::trials, "N",
     "Number of trials M (default 1000000); with digits, the stage size (default and least 10000)",
     rows::kTrials},
    rows::seed<MonteCarloOptions>(&MonteCarloOptions::seed,
                                  "Seed of the random numbers (same seed, same results)"),
    rows::threads<MonteCarloOptions>(&MonteCarloOptions::threads),
    {"digits", &MonteCarloOptions::digits, "n",
     "0: fixed M; n in 1..6: adaptive M (JCGM 101 §7.9) until n significant digits of u(y) are stable",
     OptionRange::between(1, 6).or_value(0, "fixed M")},
    {"max_trials", &MonteCarloOptions::max_trials, "N",
     "Adaptive procedure: no stage beyond this many trials", rows::kTrials},
    rows::coverage_probability<MonteCarloOptions>(&MonteCarloOptions::coverage_probability,
                                                  "Coverage probability p of the intervals, in [0.5, 1)"),
    rows::mode<&MonteCarloOptions::mode>(),
};

// The table's ranges, then what depends on the machine or on two options at once: a thread count the system
// cannot start, and a fixed M too small for the coverage interval's ends to exist.
void check_verb_options(const MonteCarloOptions& o) {
  check_options(o, option_table<MonteCarloOptions>());
  check_thread_count(o.threads, "threads");
  if (o.digits == 0)  // the adaptive stages are large enough for any p (at least 100/(1 − p) trials)
    check_coverage_interval(o.trials.value_or(kDefaultMonteCarloTrials), o.coverage_probability);
}

}  // namespace

OptionTable<MonteCarloOptions> options_of(std::type_identity<MonteCarloOptions>) { return kMonteCarloRows; }

MonteCarloResult monte_carlo(const Config& config, const MonteCarloOptions& o) {
  require_one_instrument(config, "montecarlo");
  check_verb_options(o);
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
  const ccal::MonteCarloOptions& mo = o;  // the engine's fields, as set
  r.monte_carlo =
      run_monte_carlo(monte_carlo_sources(config), config.correlations, model.n_outputs(),
                      model.output_names(), calibration_trial(model), mo, &r.budget.standard_uncertainty);
  return r;
}

}  // namespace ccal::verbs
