#pragma once
// Library version, as set in the top-level CMakeLists.txt.
namespace ccal {
const char* version() noexcept;
}  // namespace ccal
