#include "ccal/uncertainty/propagation_options.hpp"

#include <fmt/format.h>

#include "ccal/core/errors.hpp"

#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal {

OptionTable<PropagationOptions> options_of(std::type_identity<PropagationOptions>) { return kPropagationRows; }

void check_propagation_options(const PropagationOptions& options) {
  check_options(options, option_table<PropagationOptions>());
  check_thread_count(options.threads, "threads");
  if (options.digits == 0)  // the adaptive stages are large enough for any p (at least 100/(1 − p) trials)
    check_coverage_interval(options.trials.value_or(kDefaultMonteCarloTrials),
                            options.coverage_probability.value_or(kDefaultCoverageProbability));
  if (options.histogram_bins < 1 || options.histogram_bins > 10000)
    throw InputError(fmt::format("Monte Carlo: histogram bins must be 1…10000, not {}", options.histogram_bins));
}

}  // namespace ccal
