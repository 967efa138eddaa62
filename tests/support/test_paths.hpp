#pragma once
// The source and build folders of this build, for the tests that read files of the source tree (examples/,
// tests/data/) or run programs of the build tree. Only tests/support/test_paths.cpp is compiled with the two
// paths, so that the tests' own compile lines name no folder of this machine: a clone in another folder (CI)
// compiles them to the same objects, and ccache reuses them.
#include <string>

namespace ccal::test {
const std::string& source_dir();
const std::string& binary_dir();
}  // namespace ccal::test

#define CCAL_SOURCE_DIR (::ccal::test::source_dir())
#define CCAL_BINARY_DIR (::ccal::test::binary_dir())
