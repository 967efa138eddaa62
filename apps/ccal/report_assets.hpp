#pragma once
// The charting library of `ccal report` (vega, vega-lite and vega-embed from npm, web/package.json),
// embedded in the program when it was built, so that a report is written, and opens, with no network.
#include <string_view>

namespace ccal::cli {

// The three UMD builds, one after the other; empty when the program was built without them (web/node_modules
// missing: scripts/setup.sh fetches them).
std::string_view report_scripts() noexcept;

}  // namespace ccal::cli
