#pragma once
// A run sheet as text (docs/cli.md, `ccal design`): one row per run in the order the runs are made, each
// value to the step the machine sets it by, and what the columns mean for the operator.

#include <string>

#include "ccal/model/run_sheet.hpp"
#include "ccal/uncertainty/design_candidates.hpp"

namespace ccal::render {

// The sheet's table and its notes; g-levels, durations and angles with the decimals of their resolution.
std::string text(const RunSheet& sheet, const SettingResolution& resolution);

// The decimals that show every multiple of `step` exactly: 0.01 → 2, 0.5 → 1, 2 → 0 (at most 9).
int decimals_of(double step);

}  // namespace ccal::render
