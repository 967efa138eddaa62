#include "ccal/uncertainty/propagation_options.hpp"

#include <fmt/format.h>

#include "ccal/core/errors.hpp"

#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal {

OptionTable<PropagationOptions> options_of(std::type_identity<PropagationOptions>) { return kPropagationRows; }

void check_propagation_options(const PropagationOptions& options) {
  check_options(options, option_table<PropagationOptions>());
  check_thread_count(options.threads, "threads");
  // max_trials bounds the adaptive procedure's stages only: with a fixed M it would be passed over in silence.
  // Given at its default value too: the option is refused, not its value.
  if (options.digits == 0 && options.max_trials)
    throw OptionError("max_trials", std::to_string(*options.max_trials),
                      fmt::format("bounds the adaptive procedure, which {} 0 does not run (M is then {}); "
                                  "accepted: {} with {} 1 to 6, or {} left out",
                                  OptionError::name("digits"), OptionError::name("trials"),
                                  OptionError::name("max_trials"), OptionError::name("digits"),
                                  OptionError::name("max_trials")));
  if (options.digits == 0)  // the adaptive stages are large enough for any p (at least 100/(1 − p) trials)
    check_coverage_interval(options.trials.value_or(kDefaultMonteCarloTrials),
                            options.coverage_probability.value_or(kDefaultCoverageProbability));
  if (options.histogram_bins < 1 || options.histogram_bins > 10000)
    throw InputError(fmt::format("Monte Carlo: histogram bins must be 1…10000, not {}", options.histogram_bins));
}

}  // namespace ccal
