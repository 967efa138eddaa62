#include "ccal/version.hpp"

namespace ccal {
const char* version() noexcept { return "0.1.0"; }
}  // namespace ccal
