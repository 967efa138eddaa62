#pragma once
// Shared by the configuration tests: a minimal valid configuration and the checks of a located one-line
// ConfigError.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "ccal/core/constants.hpp"
#include "ccal/io/config_file.hpp"
#include "test_constants.hpp"

namespace ccal::config_test {

using ccal::test::kDeg;

// A minimal valid configuration. Tables are ordered so that the last one is [centrifuge]: a line appended
// to this text lands in [centrifuge], and a test that appends a new table puts the bad line last.
inline const std::string kBase = R"([plan]
duration = "450 s"
terminal_phase = "180 deg"
[[plan.runs]]
name = "a"
g_level = "5 g"
[site]
latitude = "45.75 deg"
g = "9.8 m/s^2"
[centrifuge]
radius = "2.5 m")";

// Line number of the last line of a text (the line a test puts the offending entry on).
inline int last_line(const std::string& text) {
  std::string t = text;
  while (!t.empty() && t.back() == '\n') t.pop_back();
  return 1 + static_cast<int>(std::count(t.begin(), t.end(), '\n'));
}

inline ConfigError error_of(const std::string& text) {
  try {
    parse_config(text, "case.toml");
  } catch (const ConfigError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return ConfigError("", 0, 0, "", "");
}

// The message has the form case.toml:<line>:<col>: <key>: ..., contains each hint, and is one line.
inline void expect_error(const std::string& text, int line, const std::string& key,
                         std::initializer_list<std::string> hints) {
  SCOPED_TRACE(text);
  const ConfigError e = error_of(text);
  const std::string what = e.what();
  EXPECT_EQ(e.source(), "case.toml");
  EXPECT_EQ(e.line(), line) << what;
  EXPECT_EQ(e.key(), key) << what;
  EXPECT_TRUE(what.starts_with("case.toml:" + std::to_string(line) + ":")) << what;
  if (!key.empty()) {
    EXPECT_NE(what.find(": " + key + ": "), std::string::npos) << what;
  }
  for (const auto& hint : hints)
    EXPECT_NE(what.find(hint), std::string::npos) << "'" << hint << "' in " << what;
  EXPECT_EQ(what.find('\n'), std::string::npos) << what;
}

// kBase + extra, with the error expected on the last line.
inline void expect_appended_error(const std::string& extra, const std::string& key,
                                  std::initializer_list<std::string> hints) {
  const std::string text = kBase + "\n" + extra;
  expect_error(text, last_line(text), key, hints);
}

// ---------------------------------------------------------------------------------------------------------
// The bundled example and the file in examples/

}  // namespace ccal::config_test
