#pragma once
// The reports of `ccal design` (docs/cli.md): the designed plan, the configured plan against it (u and U per
// coefficient, the leading sources before and after), the mechanism, the trade-off curve and the Monte Carlo
// check, as text and JSON; and the designed plan as a configuration file.
#include <string>
#include <string_view>

#include "ccal/verbs/design.hpp"

namespace ccal::render {

std::string text(const verbs::DesignResult& result);
std::string json(const verbs::DesignResult& result);
// The designed plan, one row per run.
std::string csv(const verbs::DesignResult& result);

// The [plan] of a configuration as TOML: every run in full, g-levels in g, durations in s and angles in rad
// written with 17 significant digits, so that reading it back gives the same numbers.
std::string plan_toml(const Config& config);
// The whole configuration text `original` with its [plan] table (and its [[plan.runs]]) replaced by
// plan_toml(config); the rest of the file is kept as it was, but for a job's `setup = "…"` when `setup_path`
// is given: the set-up's path as the text, written into another folder than the job's, must name it.
std::string config_with_plan(std::string_view original, const Config& config, std::string_view setup_path = {});

}  // namespace ccal::render
