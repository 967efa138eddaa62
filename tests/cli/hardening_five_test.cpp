// Hardening, a fresh round over every surface, through the program: what a careless user's wrong inputs
// found, each refused in words that say what is wrong, where, and what is accepted, and nothing left behind.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <csignal>
#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

// A refused simulate removed the folder it had made for the logs only when it was refused before the folder
// was made: an -o that names an input, two outputs naming one file, each left an empty folder behind.
TEST_F(Cli, ARefusedSimulateLeavesNoEmptyFolderOfLogs) {
  write("lab.toml", read(kLab));
  const fs::path logs = dir_ / "L";
  expect_bad_input(run("simulate lab.toml --logs-out L -o lab.toml"), {"-o: cannot write 'lab.toml'"});
  EXPECT_FALSE(fs::exists(logs));
  expect_bad_input(run("simulate lab.toml --logs-out L --observations-out L/5g.csv -o /dev/null"),
                   {"--logs-out: cannot write 'L/5g.csv': it is also the --observations-out file"});
  EXPECT_FALSE(fs::exists(logs));
  expect_bad_input(run("simulate lab.toml --logs-out L -o L/manifest.toml"), {"it is also the -o file"});
  EXPECT_FALSE(fs::exists(logs));
  // A folder that was there stays, with what it held.
  fs::create_directories(logs);
  write("L/notes.txt", "kept");
  expect_bad_input(run("simulate lab.toml --logs-out L -o lab.toml"), {"-o: cannot write 'lab.toml'"});
  EXPECT_EQ(read(logs / "notes.txt"), "kept");
  // A file where the folder would be: what is accepted is said.
  expect_bad_input(run("simulate lab.toml --logs-out lab.toml -o /dev/null"),
                   {"--logs-out: cannot create the folder 'lab.toml'", "accepted: a folder"});
  // Written, the folder and its logs are there.
  ASSERT_EQ(run("simulate lab.toml --logs-out M -o /dev/null").code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "M" / "manifest.toml"));
}

// A serial number with a control character (TOML's \u0000) was printed into the certificate and refused only
// later by the history; the configuration refuses it, at its line.
TEST_F(Cli, AConfigurationsSerialNumberWithAControlCharacterIsRefusedAtItsLine) {
  std::string lab = read(kLab);
  const std::string serial = "serial_number = \"SN 0815\"";
  lab.replace(lab.find(serial), serial.size(), "serial_number = \"SN\\u00000815\"");
  write("lab.toml", lab);
  const int line = line_of(lab, "serial_number = ");
  for (const char* verb : {"budget", "report -o r.html"})
    expect_bad_input(run(fmt::format("{} lab.toml", verb)),
                     {fmt::format("lab.toml:{}:17: certificate.serial_number: 'SN\\x000815' holds a control "
                                  "character; accepted: printable text on one line",
                                  line)});
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
}

// "'gamma' names two columns" blamed the key the user had not changed and did not say which other one named
// the column; each is said now, also between two instruments of a manifest's [instruments].
TEST_F(Cli, AColumnNamedForTwoRolesOfAManifestIsSaidOfBoth) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --logs-out L -o /dev/null").code, 0);
  std::string manifest = read(dir_ / "L" / "manifest.toml");
  manifest.replace(manifest.find("theta1 = 'theta1'"), 17, "theta1 = 'gamma'");
  manifest.replace(manifest.find("gamma = 'gamma'"), 15, "");
  write("L/manifest.toml", manifest);
  expect_bad_input(run("reduce " + quote(kLab) + " --logs L"),
                   {"L/manifest.toml:2:1: columns.gamma: 'gamma' (its default) is also the column of columns.theta1; "
                    "accepted: a column of its own for each of time, pulses, output, theta1 and gamma"});
  fs::copy(CCAL_SOURCE_DIR + "/examples/daq/two_instruments", dir_ / "T");
  std::string two = read(dir_ / "T" / "manifest.toml");
  two.replace(two.find("B = { pulses = 'pulses_B' }"), 27, "B = { pulses = 'pulses_A' }");
  write("T/manifest.toml", two);
  expect_bad_input(run("reduce " + quote(CCAL_SOURCE_DIR + "/examples/daq/two_short.toml") + " --logs T"),
                   {"T/manifest.toml:", "instruments.B.pulses: 'pulses_A' is also the column of "
                                        "instruments.A.pulses; accepted: a column of its own for each instrument's"});
}

}  // namespace
