#pragma once
// Shared by the in-process tests of the verbs (tests/verbs/): configurations edited as text, and the
// configured value of a coefficient in the unit the identification reports it in.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include "ccal/io/config_file.hpp"
#include "test_paths.hpp"

namespace ccal::test {

// The paper's set-up as published: the bundled example without the drives' rate ripple and rate noise, so
// that the budget's u is the Type B part of a statement.
inline const std::string kPaperConfigPath = CCAL_SOURCE_DIR + "/tests/data/wang_ren_2014_paper.toml";

// The text of a file (a configuration to edit).
inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  EXPECT_TRUE(in.good()) << path;
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// `text` with its one occurrence of `from` replaced by `to` (a test failure when `from` is missing).
inline std::string edited(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "not in the configuration: " << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// The bundled example with known [errors]: the instrument's azimuth zero error and the main axis' levelling
// (arcseconds), a platform runout (µm) and the drives' rate errors; the regressors computed with them
// (compensate) or without.
inline std::string example_with_errors(bool compensate) {
  std::string text = edited(std::string(bundled_example_text()),
                            "# dthz5 = \"2 arcsec\"       # instrument azimuth (IA) zero error",
                            "dthz5 = \"2 arcsec\"\ndthy1t = \"3 arcsec\"\ndomega = \"2e-6 rad/s\"\n"
                            "dOmega = \"-1e-6 rad/s\"");
  text = edited(text, "# dx3_c1 = \"5 um\"", "dx3_c1 = \"5 um\"");
  return compensate ? edited(text, "compensate = false", "compensate = true") : text;
}

// The configured value of `term` in the identification's unit (the output unit per gⁿ): SI / output_unit_si.
inline double configured(const Config& config, const std::string& term, double output_unit_si) {
  const auto value = config.instrument.coefficient(term);
  EXPECT_TRUE(value.has_value()) << term;
  return value.value_or(0) / output_unit_si;
}

// A small design space (6 g-levels × 4 cuts of the last turn × 4 phases × 2 azimuths = 192 candidates), so that
// a whole design runs in a few seconds.
inline const std::string kSmallDesignSpace = R"(
[design]
g_step = "5 g"
turn_fractions = 4
phase_step = "90 deg"
azimuth_step = "180 deg"
starts = 2
)";

}  // namespace ccal::test
