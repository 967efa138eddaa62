#include "ccal/version.hpp"

#include <string>

// version() and version_commit() are generated at build time (cmake/version_info.cmake), so that a new commit
// recompiles only that file.
namespace ccal {
std::string version_line() {
  return std::string("ccal ") + version() + " (commit " + version_commit() + ")";
}
}  // namespace ccal
