#include "test_paths.hpp"

namespace ccal::test {
const std::string& source_dir() {
  static const std::string dir = CCAL_TEST_SOURCE_DIR;
  return dir;
}
const std::string& binary_dir() {
  static const std::string dir = CCAL_TEST_BINARY_DIR;
  return dir;
}
}  // namespace ccal::test
