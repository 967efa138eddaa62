#pragma once
// The per-term observability (ccal/reduction/observability.hpp, docs/model.md §14) as the verbs use it: what
// is known of the runs, the refusal of an unobservable term and the warning of a weak one (returned, for the
// front end to show).

#include <string>
#include <string_view>
#include <vector>

#include "ccal/reduction/fit.hpp"
#include "ccal/reduction/observability.hpp"
#include "ccal/reduction/observe.hpp"
#include "ccal/setup/config.hpp"

namespace ccal::verbs {

// What is known of the runs beyond a table of run means, in the table's output unit.
struct DataResolution {
  std::vector<RunResolutionInfo> runs;
  double noise_density = 0;  // output unit/√Hz
  double quantum = 0;        // output unit·s
};

// The resolution of runs of a configuration (durations, platform turns, input and rate magnitudes, the
// instrument's noise density and quantum and the magnitude of its output), one per row of `obs`, in the
// output unit. `runs` are the runs as reduced (planned, or as measured by `ccal reduce`), `rates` their Ω
// [rad/s].
DataResolution run_resolution(const std::vector<Run>& runs, const std::vector<double>& rates,
                              const Observations<double>& obs, const IdentificationSpec& spec,
                              const InstrumentModel& instrument);

struct ObservabilityReport {
  ObservabilityResult result;
  std::vector<std::string> units;  // coefficient unit per free term
  std::string basis;               // what the run resolution is made of, in words
  std::vector<std::string> warnings;
};

// Assesses the free terms of a solved fit (free columns of `problem` as in `fit`, fitted values as
// references). Without `resolution` the resolution of a run is the floating-point resolution of its mean and
// the fit's scatter: the σ of the weights, else the residual standard deviation. Throws InputError
// "<source>: the test plan cannot observe <term>: <reason>; <fix>" for an unobservable term; weak terms give
// a warning each (in the report's warnings).
ObservabilityReport assess_fit(const FitProblem& problem, const FitResult& fit,
                               const std::vector<std::string>& units, const DataResolution* resolution,
                               std::string_view source);

// The same for a configuration's plan before anything is fitted (`ccal budget`): the noise-free observations
// of the plan are fitted (so that dependent terms get the fit's message), the configured coefficients are the
// references. Throws InputError as above.
ObservabilityReport assess_plan(const Config& config, ModelMode mode);

}  // namespace ccal::verbs
