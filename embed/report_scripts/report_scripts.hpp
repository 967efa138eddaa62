#pragma once
// The charting library of `ccal report` (vega, vega-lite and vega-embed from npm, web/package.json),
// embedded in the program and the Python module when they were built, so that a report is written, and
// opens, with no network. A library of its own (ccal_report_scripts), linked by both.
#include <string_view>

namespace ccal {

// The three UMD builds, one after the other; empty when built without them (web/node_modules missing:
// scripts/setup.sh fetches them).
std::string_view report_scripts() noexcept;
// The same, or InputError saying how to get them when they are missing.
std::string_view required_report_scripts();

}  // namespace ccal
