#pragma once
// `ccal allocate` as a library call: the largest centrifuge tolerances for which every target on the
// expanded uncertainty of an identified coefficient holds, checked by Monte Carlo (docs/model.md §10.3).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/allocate.hpp"
#include "ccal/uncertainty/option_rows.hpp"

namespace ccal::verbs {

struct AllocateOptions {
  // Targets "<coefficient>=<U> [unit]", e.g. "K3=2e-3" (in the coefficient's display unit) or
  // "K3=2e-3 deg/s/g^3"; at least one.
  std::vector<std::string> targets;
  double coverage_probability = 0.95;  // p of the expanded uncertainties (the targets), in (0, 1)
  std::optional<ModelMode> mode;       // kinematics; unset: the configuration's [identification] mode
  double max_scale = 10.0;             // no tolerance grows beyond this factor of its configured value
  // false: every free coefficient without a target is held at its configured expanded uncertainty; true:
  // they may grow (the result names each that does).
  bool let_others_grow = false;
  std::int64_t verify_trials = 2000;   // Monte Carlo check of the result; 0: none
  std::uint64_t seed = 1;
  int threads = 0;        // 0: all cores
  bool progress = false;  // draw a progress bar on standard error when it is a terminal
  ProgressCallback on_progress;  // of the verification's trials; may throw Cancelled (core/progress.hpp)
};

// The options' table (core/options.hpp): names, ranges and help of the fields a front end sets.
OptionTable<AllocateOptions> options_of(std::type_identity<AllocateOptions>);

struct AllocateResult {
  Config config;
  AllocationResult allocation;
};

// Throws OptionError naming the field for a value out of range (its table), InputError naming --target for a
// target that is not one, for an empty [tolerances], a target below what the drives' noise
// allows, or a result that is not finite.
AllocateResult allocate(const Config& config, const AllocateOptions& options);

}  // namespace ccal::verbs
