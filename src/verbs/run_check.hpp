#pragma once
// Each logged run's mean against what the configuration's instrument, with its nominal [instrument.terms],
// would read at that run of the plan (docs/cli.md, `ccal reduce`): a log swapped with another run's, or given under
// the wrong run's name, reads far from it. Private to the library (verbs::reduce uses it).

#include <cstddef>
#include <string>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/intake/run_log.hpp"
#include "ccal/setup/config.hpp"

namespace ccal::verbs {

// One plan run: the nominal instrument's reading and the standard uncertainty of a run's mean about it, in the
// output unit; the log's mean where the run was logged.
struct RunCheck {
  std::size_t index = 0;  // in the plan
  bool logged = false;
  double mean = 0;     // the log's mean output
  double nominal = 0;  // the nominal instrument's reading at the planned run, with the known [errors]
  double u = 0;        // standard uncertainty of a mean about it: noise, drives' rate noise, tolerances
  bool beyond = false;  // logged, u > 0 and |mean − nominal| > kRunCheckLimit·u
};

// Every run of the plan (T of the logged ones: their logs' spans). The tolerances' part of u comes from the
// configuration's budget; a configuration without one (no [tolerances], a plan that cannot identify its terms)
// has the noise's part alone, and a run with u = 0 is not judged.
std::vector<RunCheck> check_runs(const Config& config, const LogReduction& logs, ModelMode mode);

// The finding about run `check` (beyond): its mean, how far from the nominal reading in u, and the run whose
// nominal reading its mean matches within the limit, if one does (a swapped or mislabelled log).
std::string run_check_finding(const Config& config, const std::vector<RunCheck>& checks, const RunCheck& check);

}  // namespace ccal::verbs
