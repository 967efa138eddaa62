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

struct AllocateResult {
  Config config;
  AllocationDetail allocation;
};

// The allocation of uncertainty/allocate.hpp (allocate_tolerances) with its configuration. Throws as it does,
// and InputError for a result that is not finite.
AllocateResult allocate(const Config& config, const AllocateOptions& options);

}  // namespace ccal::verbs
