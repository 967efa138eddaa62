#pragma once
// What ccal was built from: the library version (the project version of the top-level CMakeLists.txt) and the
// git commit of the sources, both fixed at build time (cmake/version_info.cmake).
#include <string>

namespace ccal {
// MAJOR.MINOR.PATCH, e.g. "0.1.0".
const char* version() noexcept;
// Abbreviated hash of the commit the library was built from (`git rev-parse --short HEAD` when the build ran),
// or "unknown" when the sources were not a git checkout or git was not found.
const char* version_commit() noexcept;
// "ccal <version> (commit <version_commit()>)", e.g. "ccal 0.1.0 (commit abc1234)": what `ccal --version`
// prints.
std::string version_line();
}  // namespace ccal
