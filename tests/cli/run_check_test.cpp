// `ccal reduce` checks each run's mean against what the nominal instrument reads at that run: the lab's logs,
// pulses only (no encoder to tell the runs apart), two of them swapped in the manifest, give one warning for
// each run naming the other, and exit 0; with --strict-runs exit 2 at the manifest's line. The lab's own logs
// give no such warning.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

TEST_F(Cli, SwappedLogsAreFoundAgainstTheNominalInstrument) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --logs-out L -o /dev/null").code, 0);
  const Result whole = run("reduce " + quote(kLab) + " --logs L -o /dev/null");
  ASSERT_EQ(whole.code, 0) << whole.err;
  EXPECT_EQ(whole.err.find("nominal instrument"), std::string::npos) << whole.err;
  // The pulse logs alone (time, pulses), in a folder whose manifest names 10g's log for 5g and 5g's for 10g.
  const char* runs[] = {"5g", "10g", "15g", "20g", "25g", "30g"};
  fs::create_directories(dir_ / "P");
  for (const char* r : runs) {
    std::istringstream in(read(dir_ / "L" / (std::string(r) + ".csv")));
    std::string kept;
    for (std::string line; std::getline(in, line);) kept += line.substr(0, line.find(',', line.find(',') + 1)) + "\n";
    write(std::string("P/") + r + ".csv", kept);
  }
  write("P/manifest.toml",
        "[runs]\n5g = '10g.csv'\n10g = '5g.csv'\n15g = '15g.csv'\n20g = '20g.csv'\n25g = '25g.csv'\n30g = '30g.csv'\n");
  const Result warned = run("reduce " + quote(kLab) + " --logs P -o /dev/null");
  ASSERT_EQ(warned.code, 0) << warned.err;
  EXPECT_NE(warned.err.find("warning: run '5g': the log's mean"), std::string::npos) << warned.err;
  EXPECT_NE(warned.err.find("it is what run '10g' reads"), std::string::npos) << warned.err;
  EXPECT_NE(warned.err.find("warning: run '10g': the log's mean"), std::string::npos) << warned.err;
  EXPECT_NE(warned.err.find("it is what run '5g' reads"), std::string::npos) << warned.err;
  expect_bad_input(run("reduce " + quote(kLab) + " --logs P --strict-runs -o out.json"),
                   {"P/manifest.toml:2:1: runs.5g: run '5g': the log's mean", "nominal instrument",
                    "it is what run '10g' reads", "so are runs '10g'",
                    "accepted: each run's own log (to see the fit anyway: the runs' check as a warning, not strict)"});
  EXPECT_FALSE(fs::exists(dir_ / "out.json"));
  // Given by --log, the refusal names --log.
  std::string args;
  for (const char* r : runs) args += fmt::format(" --log {}=P/{}.csv", r, r == std::string("5g") ? "10g" : r == std::string("10g") ? "5g" : r);
  expect_bad_input(run("reduce " + quote(kLab) + args + " --strict-runs"), {"--log: run '5g': the log's mean"});
  EXPECT_EQ(run("reduce " + quote(kLab) + " --logs L --strict-runs -o /dev/null").code, 0);
}

}  // namespace
