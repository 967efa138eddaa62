#include "report_scripts.hpp"

#include "ccal/core/errors.hpp"

#ifdef CCAL_REPORT_ASSETS_DIR
// The files' bytes go into the program's read-only data as they are (the assembler's .incbin), between two
// symbols; a newline separates them. CCAL_REPORT_ASSETS_SHA256 (their hash, set by CMake) makes a changed
// file change this source, so no cache of compiled objects can keep the old bytes.
#define CCAL_STRINGIFY_(x) #x
#define CCAL_STRINGIFY(x) CCAL_STRINGIFY_(x)
asm(".pushsection .rodata\n"
    ".global ccal_report_scripts_begin\n"
    "ccal_report_scripts_begin:\n"
    ".incbin \"" CCAL_REPORT_ASSETS_DIR
    "/vega/build/vega.min.js\"\n"
    ".byte 10\n"
    ".incbin \"" CCAL_REPORT_ASSETS_DIR
    "/vega-lite/build/vega-lite.min.js\"\n"
    ".byte 10\n"
    ".incbin \"" CCAL_REPORT_ASSETS_DIR
    "/vega-embed/build/vega-embed.min.js\"\n"
    ".byte 10\n"
    ".global ccal_report_scripts_end\n"
    "ccal_report_scripts_end:\n"
    ".byte 0\n"
    ".popsection\n"
    "# " CCAL_STRINGIFY(CCAL_REPORT_ASSETS_SHA256) "\n");

extern "C" const char ccal_report_scripts_begin[];
extern "C" const char ccal_report_scripts_end[];

namespace ccal {
std::string_view report_scripts() noexcept {
  return {ccal_report_scripts_begin,
          static_cast<std::size_t>(ccal_report_scripts_end - ccal_report_scripts_begin)};
}
}  // namespace ccal
#else
namespace ccal {
std::string_view report_scripts() noexcept { return {}; }
}  // namespace ccal
#endif

namespace ccal {
std::string_view required_report_scripts() {
  const std::string_view scripts = report_scripts();
  if (scripts.empty())
    throw InputError(
        "report: this ccal was built without its charting library (web/node_modules was missing); run "
        "scripts/setup.sh (or `npm ci --prefix web`), then build again");
  return scripts;
}
}  // namespace ccal
