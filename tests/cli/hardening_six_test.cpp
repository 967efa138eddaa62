// Hardening, round six, through the program: what the last round left and what a fresh round of a careless
// user's wrong inputs found, each refused in words that say what is wrong, where, and what is accepted, and
// nothing left behind or lost.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

// The lines of a text, and a text of lines (unique names: unity builds join the test files).
std::vector<std::string> six_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}
std::string six_joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  return text;
}

// A negative pulse weight typed with its unit was echoed as a bare number ("-2.5e-05"), its unit lost: it is
// echoed as typed.
TEST_F(Cli, ANegativePulseWeightIsEchoedAsTyped) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --logs-out L -o /dev/null").code, 0);
  expect_bad_input(
      run("reduce " + quote(kLab) + " --logs L --pulse-weight '-2.5e-5 deg' -o /dev/null"),
      {"--pulse-weight: -2.5e-5 deg is not a positive weight; accepted: the integrated output per "
       "pulse, a positive number in deg/s·s or with a unit of that kind, e.g. 2.5e-5"});
  expect_bad_input(run("reduce " + quote(kLab) + " --logs L --pulse-weight '0 arcsec' -o /dev/null"),
                   {"--pulse-weight: 0 arcsec is not a positive weight"});
  expect_bad_input(run("reduce " + quote(kLab) + " --logs L --pulse-weight -2.50e-5 -o /dev/null"),
                   {"--pulse-weight: -2.50e-5 is not a positive weight"});
}

// An option given without its value was CLI11's "--trials: 1 required N missing", a missing argument "SERIAL
// is required" with the help of the parent command: each says what is missing and how it is written.
TEST_F(Cli, AnOptionWithoutItsValueSaysWhatIsMissingAndHowItIsWritten) {
  expect_bad_input(
      run("montecarlo --coverage-probability"),
      {"--coverage-probability: its value is missing (nothing follows it, or the next word is an "
       "option); accepted: --coverage-probability p (Coverage probability p of the intervals, in "
       "[0.5, 1)); run 'ccal montecarlo --help'"});
  expect_bad_input(run("budget --format"), {"--format: its value is missing",
                                            "accepted: --format FORMAT:{text,json,csv} (Output format)"});
  expect_bad_input(run("history show"),
                   {"SERIAL: missing; accepted: SERIAL (Serial number, as recorded); run "
                    "'ccal history show --help'"});
  expect_bad_input(run("history supersede --db h.sqlite"), {"ID: missing; accepted: ID",
                                                            "ccal history supersede "
                                                            "--help"});
}

// "already superseded" said why but not what is accepted.
TEST_F(Cli, SupersedingARecordTwiceSaysWhatIsAccepted) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --logs-out L -o /dev/null").code, 0);
  ASSERT_EQ(run("reduce " + quote(kLab) +
                " --logs L --statement --statement-trials 0 --statement-out s.json "
                "-o /dev/null")
                .code,
            0);
  ASSERT_EQ(run("history add s.json --db h.sqlite").code, 0);
  ASSERT_EQ(run("history supersede 1 --reason 'wrong mount' --db h.sqlite").code, 0);
  expect_bad_input(
      run("history supersede 1 --reason again --db h.sqlite"),
      {"h.sqlite: calibration 1 is already superseded (wrong mount), and a record is superseded once; "
       "accepted: a calibration of SN 0815 that is not superseded (`ccal history show`)"});
}

// A wild count in mid-log (one cell far above or below its neighbours) was reported at the line after it, as
// a counter that wraps: it is said to be a wild count, at its own line. A counter that wraps still is one.
TEST_F(Cli, AWildCountInMidLogIsReportedAtItsLine) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --logs-out L -o /dev/null").code, 0);
  const std::string others = " --log 10g=L/10g.csv --log 15g=L/15g.csv -o /dev/null";
  const std::vector<std::string> log = six_lines(read(dir_ / "L" / "5g.csv"));  // time,pulses,theta1,gamma
  const auto count_of = [&](std::size_t index) {
    const std::size_t a = log[index].find(','), b = log[index].find(',', a + 1);
    return std::stoll(log[index].substr(a + 1, b - a - 1));
  };
  const auto with_count = [&](std::size_t index, long long count) {
    std::vector<std::string> lines = log;
    const std::size_t a = lines[index].find(','), b = lines[index].find(',', a + 1);
    lines[index] = lines[index].substr(0, a + 1) + std::to_string(count) + lines[index].substr(b);
    return six_joined(lines);
  };
  const std::size_t k = 2000;  // the file's line k + 1
  for (const long long offset : {100000LL, -100000LL}) {
    write("wild.csv", with_count(k, count_of(k) + offset));
    expect_bad_input(run("reduce " + quote(kLab) + " --log 5g=wild.csv" + others),
                     {fmt::format("wild.csv:{}:2: pulses: {} is a wild count: it steps from {} by", k + 1,
                                  count_of(k) + offset, count_of(k - 1)),
                      fmt::format("and the next line steps back to {}; accepted: a count that steps steadily",
                                  count_of(k + 1))});
  }
  // A 16-bit counter that wraps, undeclared: said so where it wraps.
  std::vector<std::string> wrapped = log;
  std::size_t first_wrap = 0;
  for (std::size_t j = 1; j < wrapped.size(); ++j) {
    const std::size_t a = wrapped[j].find(','), b = wrapped[j].find(',', a + 1);
    const long long count = std::stoll(wrapped[j].substr(a + 1, b - a - 1));
    if (first_wrap == 0 && count >= 65536) first_wrap = j;
    wrapped[j] = wrapped[j].substr(0, a + 1) + std::to_string(count % 65536) + wrapped[j].substr(b);
  }
  write("wrap.csv", six_joined(wrapped));
  expect_bad_input(
      run("reduce " + quote(kLab) + " --log 5g=wrap.csv" + others),
      {fmt::format("wrap.csv:{}:2: pulses: {} follows", first_wrap + 1, count_of(first_wrap) % 65536),
       "a counter that wraps"});
}

// A refused --logs-out a/b/c removed c alone, leaving a/b behind: every folder it made is removed, and none
// it did not make.
TEST_F(Cli, ARefusedSimulateRemovesEveryFolderItMadeAndNoOther) {
  write("lab.toml", read(kLab));
  expect_bad_input(run("simulate lab.toml --logs-out a/b/c -o lab.toml"), {"-o: cannot write 'lab.toml'"});
  EXPECT_FALSE(fs::exists(dir_ / "a"));
  fs::create_directories(dir_ / "x");
  expect_bad_input(run("simulate lab.toml --logs-out x/b/./c/ -o lab.toml"), {"-o: cannot write 'lab.toml'"});
  EXPECT_TRUE(fs::is_directory(dir_ / "x"));
  EXPECT_FALSE(fs::exists(dir_ / "x" / "b"));
  ASSERT_EQ(run("simulate lab.toml --logs-out x/b/c -o /dev/null").code, 0);
  EXPECT_TRUE(fs::exists(dir_ / "x" / "b" / "c" / "manifest.toml"));
}

}  // namespace
