#pragma once
// `ccal force` as a library call: the sensed input of the instrument at one instant of a run, exact and as
// first-order contributions of the configured [errors] (docs/cli.md, docs/model.md §4–5).

#include <cstddef>

#include "ccal/core/model_mode.hpp"
#include "ccal/core/options.hpp"
#include "ccal/model/sensed_input.hpp"
#include "ccal/setup/config.hpp"

namespace ccal::verbs {

struct ForceOptions {
  std::string run = "1";              // run name, or its 1-based index as text
  double time = 0;                    // t into the run [s], within [0, T]
  ModelMode mode = ModelMode::exact;  // first-order model: the linearised exact chain, or the paper's form
};

// The options' table (core/options.hpp): names, ranges and help of the fields a front end sets.
OptionTable<ForceOptions> options_of(std::type_identity<ForceOptions>);

struct ForceResult {
  Config config;               // the configuration evaluated
  std::size_t run_index = 0;   // 0-based index of the run in the plan
  SensedInputBreakdown input;  // exact, nominal, per-error contributions, remainder
};

// Throws InputError for an unknown run or a time outside it (naming `--run` / `--time`, the options' names
// in every front end).
ForceResult force(const Config& config, const ForceOptions& options = {});

}  // namespace ccal::verbs
