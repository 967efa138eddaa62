// The version the library reports, and the release files that must agree with it: LICENSE (the BSD 3-Clause
// text) and CITATION.cff (its version: field).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "ccal/version.hpp"
#include "test_paths.hpp"

namespace {

std::string read_source_file(const std::string& relative) {
  const std::filesystem::path path = std::filesystem::path(CCAL_SOURCE_DIR) / relative;
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << "cannot read " << path;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Words of a text separated by single spaces, so that the checks do not depend on line breaks.
std::string normalise_spaces(const std::string& text) {
  return std::regex_replace(text, std::regex(R"(\s+)"), " ");
}

}  // namespace

TEST(Version, IsTheProjectVersion) {
  // CCAL_PROJECT_VERSION: project(ccal VERSION ...) of the top-level CMakeLists.txt.
  EXPECT_EQ(std::string(ccal::version()), CCAL_PROJECT_VERSION);
  EXPECT_TRUE(std::regex_match(ccal::version(), std::regex(R"(\d+\.\d+\.\d+)"))) << ccal::version();
}

TEST(Version, CommitIsAGitHashOrUnknown) {
  const std::string commit = ccal::version_commit();
  // git rev-parse --short: at least 7 hexadecimal digits (more when needed to be unique), at most a full hash.
  EXPECT_TRUE(commit == "unknown" || std::regex_match(commit, std::regex("[0-9a-f]{7,40}"))) << commit;
}

TEST(Version, LineNamesVersionAndCommit) {
  EXPECT_EQ(ccal::version_line(),
            std::string("ccal ") + CCAL_PROJECT_VERSION + " (commit " + ccal::version_commit() + ")");
}

TEST(ReleaseFiles, LicenseIsBsd3Clause) {
  const std::string license = normalise_spaces(read_source_file("LICENSE"));
  // The three clauses and the disclaimer of the BSD 3-Clause licence (SPDX BSD-3-Clause), as Ceres Solver
  // uses it, with the project's copyright holder.
  for (const char* phrase : {
           "BSD 3-Clause License",
           "Copyright (c) 2026, The ccal authors",
           "1. Redistributions of source code must retain the above copyright notice, this list of conditions "
           "and the following disclaimer.",
           "2. Redistributions in binary form must reproduce the above copyright notice, this list of "
           "conditions and the following disclaimer in the documentation and/or other materials provided with "
           "the distribution.",
           "3. Neither the name of the copyright holder nor the names of its contributors may be used to "
           "endorse or promote products derived from this software without specific prior written permission.",
           "THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS \"AS IS\"",
           "IN NO EVENT SHALL THE COPYRIGHT HOLDER OR CONTRIBUTORS BE LIABLE",
           "EVEN IF ADVISED OF THE POSSIBILITY OF SUCH DAMAGE.",
       }) {
    EXPECT_NE(license.find(phrase), std::string::npos) << "LICENSE lacks: " << phrase;
  }
  // A fourth (advertising) clause would make it the 4-clause licence.
  EXPECT_EQ(license.find("4."), std::string::npos);
}

TEST(ReleaseFiles, CitationVersionIsTheProjectVersion) {
  const std::string citation = read_source_file("CITATION.cff");
  EXPECT_TRUE(citation.starts_with("cff-version: 1.2.0\n"));
  // The top-level version: key (not indented), quoted or not.
  std::smatch match;
  ASSERT_TRUE(std::regex_search(citation, match, std::regex(R"re((^|\n)version: *"?([^"\n]*?)"? *\n)re")))
      << "CITATION.cff has no top-level version:";
  EXPECT_EQ(match[2].str(), CCAL_PROJECT_VERSION);
  EXPECT_NE(citation.find("\nlicense: BSD-3-Clause\n"), std::string::npos);
}

TEST(ReleaseFiles, ChangelogHasThisVersion) {
  // Keep a Changelog: an Unreleased section and a "## [x.y.z] - YYYY-MM-DD" entry for this version.
  const std::string changelog = read_source_file("CHANGELOG.md");
  EXPECT_NE(changelog.find("\n## [Unreleased]\n"), std::string::npos);
  EXPECT_TRUE(std::regex_search(
      changelog, std::regex(std::string(R"(\n## \[)") + std::regex_replace(CCAL_PROJECT_VERSION, std::regex(R"(\.)"), R"(\.)") +
                                R"(\] - \d{4}-\d{2}-\d{2}\n)")))
      << "CHANGELOG.md has no entry '## [" << CCAL_PROJECT_VERSION << "] - YYYY-MM-DD'";
}
