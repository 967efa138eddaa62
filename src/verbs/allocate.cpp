#include "ccal/verbs/allocate.hpp"

#include <fmt/format.h>

#include <cmath>

#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "result_checks.hpp"

namespace ccal::verbs {

namespace {

constexpr OptionSpec<AllocateOptions> kAllocateRows[] = {
    {"targets",
     &AllocateOptions::targets,
     "COEFF=U",
     "COEFF=U: the allowed expanded uncertainty (half-width of the coverage interval) of a free coefficient, "
     "in its unit (output unit per g^n) or with a unit, e.g. K3=1e-6 or \"K3=1e-6 deg/s/g^3\"; one per "
     "coefficient",
     {},
     true},
    rows::coverage_probability(&AllocateOptions::coverage_probability,
                               "Coverage probability p of the targets, in [0.5, 1)"),
    rows::mode<&AllocateOptions::mode>(
        "Kinematics of the sensitivities and the verification: exact or paper; "
        "default: the configuration's [identification] mode"),
    {"max_scale", &AllocateOptions::max_scale, "X",
     "No tolerance is loosened by more than this factor (1e-6 to 1e6)", kMaxScaleRange},
    {"let_others_grow", &AllocateOptions::let_others_grow, "",
     "Let the coefficients without a target grow beyond their configured expanded uncertainty (default: each "
     "is held at it)"},
    rows::verify_trials(&AllocateOptions::verify_trials,
                        "Monte Carlo trials of the verification on the allocated tolerances (0: none)"),
    rows::seed(&AllocateOptions::seed, "Seed of the verification"),
    rows::threads(&AllocateOptions::threads, "Threads of the verification (0: the OpenMP default)"),
};

}  // namespace

OptionTable<AllocateOptions> options_of(std::type_identity<AllocateOptions>) { return kAllocateRows; }

AllocateResult allocate(const Config& config, const AllocateOptions& o) {
  require_one_instrument(config, "allocate");
  check_options(o, option_table<AllocateOptions>());
  if (config.tolerances.empty())
    throw InputError(config.source + ": [tolerances] is empty; the allocation needs at least one source");
  // The free terms and their units, for the targets.
  std::vector<std::string> units;
  for (const auto& id : config.identification.free_terms)
    units.push_back(coefficient_unit(config.instrument.output_unit, id, config.instrument.g_symbol));
  std::vector<AllocationTarget> targets;
  for (const auto& t : o.targets)
    targets.push_back(parse_allocation_target(t, config.identification.free_terms, units));
  ccal::AllocateOptions ao;
  ao.coverage_probability = o.coverage_probability;
  ao.mode = o.mode.value_or(config.mode);
  ao.max_scale = o.max_scale;
  ao.let_others_grow = o.let_others_grow;
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
