#include "ccal/verbs/allocate.hpp"

#include <fmt/format.h>

#include <cmath>

#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "result_checks.hpp"

namespace ccal::verbs {

AllocateResult allocate(const Config& config, const AllocateOptions& o) {
  if (!(o.coverage_probability > 0 && o.coverage_probability < 1))
    throw InputError(fmt::format("--coverage-probability: {} is not a probability in (0, 1); e.g. 0.95",
                                 o.coverage_probability));
  if (!(std::isfinite(o.max_scale) && o.max_scale > 0))
    throw InputError(fmt::format("--max-scale: {} is not a number > 0; e.g. 10", o.max_scale));
  if (o.verify_trials < 0 || o.verify_trials == 1 || o.verify_trials > 1000000000)
    throw InputError(
        fmt::format("--verify-trials: {} is out of range; accepted: 0 (no verification) or 2 to 1000000000",
                    o.verify_trials));
  check_thread_count(o.threads, "--threads");
  if (config.tolerances.empty())
    throw InputError(config.source + ": [tolerances] is empty; the allocation needs at least one source");
  // The free terms and their units, for the targets.
  std::vector<std::string> units;
  for (const auto& id : config.identification.free_terms)
    units.push_back(coefficient_unit(config.instrument.output_unit, id));
  std::vector<AllocationTarget> targets;
  for (const auto& t : o.targets)
    targets.push_back(parse_allocation_target(t, config.identification.free_terms, units));
  ccal::AllocateOptions ao;
  ao.coverage = o.coverage_probability;
  ao.mode = o.mode.value_or(config.mode);
  ao.max_scale = o.max_scale;
  ao.verify_trials = std::uint64_t(o.verify_trials);
  ao.seed = o.seed;
  ao.threads = o.threads;
  ao.progress = o.progress;
  ao.on_progress = o.on_progress;
  AllocateResult r;
  r.config = config;
  r.allocation = allocate_tolerances(config, targets, ao);
  check_finite(config, r.allocation);  // never a nan or inf returned as a result
  return r;
}

}  // namespace ccal::verbs
