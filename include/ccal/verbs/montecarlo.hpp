#pragma once
// `ccal montecarlo` as a library call: the propagation of the configured tolerances to the identified
// coefficients by the Monte Carlo method of JCGM 101, with the validation of the budget's LPU (§8 of JCGM
// 101, docs/model.md §10.2).

#include <cstdint>
#include <optional>

#include "ccal/core/model_mode.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "ccal/uncertainty/propagation_options.hpp"
#include "ccal/uncertainty/option_rows.hpp"

namespace ccal::verbs {

// The options of `ccal montecarlo`: the engine's (uncertainty/propagation_options.hpp: trials, seed, threads,
// digits, max_trials, coverage_probability, progress, keep_samples) and the kinematics of the model. Its table
// lifts the engine's rows, so a front end sets what the engine reads and the engine checks it.
struct MonteCarloOptions {
  PropagationOptions propagation;
  std::optional<ModelMode> mode;  // kinematics; unset: the configuration's [identification] mode
};

// The options' table (core/options.hpp): names, ranges and help of the fields a front end sets.
OptionTable<MonteCarloOptions> options_of(std::type_identity<MonteCarloOptions>);

struct MonteCarloResult {
  Config config;
  ccal::BudgetDetail budget;  // the LPU that the Monte Carlo validates, and the display units
  ccal::MonteCarloDetail monte_carlo;
};

// Throws OptionError naming the field for a value out of range (its table), InputError for an empty
// [tolerances] or a plan that cannot identify the terms.
MonteCarloResult monte_carlo(const Config& config, const MonteCarloOptions& options = {});

}  // namespace ccal::verbs
