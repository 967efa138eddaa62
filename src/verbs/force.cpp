#include "ccal/verbs/force.hpp"

#include <fmt/format.h>

#include "ccal/core/errors.hpp"
#include "ccal/core/format.hpp"

namespace ccal::verbs {

namespace {

constexpr OptionSpec<ForceOptions> kForceRows[] = {
    {"run", &ForceOptions::run, "J", "Run name or 1-based index"},
    {"time", &ForceOptions::time, "T", "Time into the run [s], within [0, T] (the run's duration)",
     OptionRange::at_least(0)},
    {"mode", enum_member<&ForceOptions::mode>(kModeNames), "MODE",
     "First-order model: exact (linearised exact chain) or paper (Wang & Ren Eq.14 form)"},
};

}  // namespace

OptionTable<ForceOptions> options_of(std::type_identity<ForceOptions>) { return kForceRows; }

ForceResult force(const Config& config, const ForceOptions& options) {
  require_one_instrument(config, "force");
  ForceResult r;
  r.config = config;
  r.run_index = select_run(config.plan, options.run, "run");
  const Run& run = config.plan.runs[r.run_index];
  const double t = options.time;
  if (!(t >= 0.0 && t <= run.duration))
    throw OptionError("time", number(t) + " s",
                      fmt::format("is outside run '{}'; accepted: 0 to {} s", run.name, number(run.duration)));
  r.input = evaluate_force(config.site, config.centrifuge, run, t, options.mode);
  return r;
}

}  // namespace ccal::verbs
