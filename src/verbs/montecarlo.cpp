#include "ccal/verbs/montecarlo.hpp"

#include <fmt/format.h>

#include "ccal/core/errors.hpp"

namespace ccal::verbs {

namespace {

void check_options(const MonteCarloOptions& o) {
  if (o.trials != 0 && (o.trials < 2 || o.trials > kMaxMonteCarloTrials))
    throw InputError(fmt::format("--trials: {} is out of range; accepted: 2 to {} (0: the default)", o.trials,
                                 kMaxMonteCarloTrials));
  if (o.max_trials < 2 || o.max_trials > kMaxMonteCarloTrials)
    throw InputError(fmt::format("--max-trials: {} is out of range; accepted: 2 to {}", o.max_trials,
                                 kMaxMonteCarloTrials));
  check_thread_count(o.threads, "--threads");
  if (o.digits < 0 || o.digits > 6)
    throw InputError(fmt::format("--digits: {} is out of range; accepted: 0 (fixed M) or 1..6", o.digits));
  if (!(o.coverage_probability > 0 && o.coverage_probability < 1))
    throw InputError(fmt::format("--coverage-probability: {} is not a probability in (0, 1); e.g. 0.95",
                                 o.coverage_probability));
  if (o.digits == 0)  // the adaptive stages are large enough for any p (at least 100/(1 − p) trials)
    check_coverage_interval(std::uint64_t(o.trials != 0 ? o.trials : kDefaultMonteCarloTrials),
                            o.coverage_probability, "--trials", "--coverage-probability");
}

}  // namespace

MonteCarloResult monte_carlo(const Config& config, const MonteCarloOptions& o) {
  check_options(o);
  if (config.tolerances.empty())
    throw InputError(config.source + ": [tolerances] is empty; the Monte Carlo needs at least one source");
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
    throw IllPosedFit(std::string("the test plan cannot identify the configured terms: ") + e.what(),
                      e.terms());
  }
  ccal::MonteCarloOptions mo;
  mo.trials = std::uint64_t(o.trials != 0  ? o.trials
                            : o.digits > 0 ? kDefaultMonteCarloStage
                                           : kDefaultMonteCarloTrials);
  mo.seed = o.seed;
  mo.threads = o.threads;
  mo.significant_digits = o.digits;
  mo.max_trials = o.max_trials;
  mo.coverage = o.coverage_probability;
  mo.keep_samples = o.keep_samples;
  mo.progress = o.progress;
  mo.on_progress = o.on_progress;
  r.monte_carlo = run_monte_carlo(monte_carlo_sources(config), model.n_outputs(), model.output_names(),
                                  calibration_trial(model), mo, &r.budget.standard_uncertainty);
  return r;
}

}  // namespace ccal::verbs
