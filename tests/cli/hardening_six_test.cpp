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

// The lab example with its first line starting `from` replaced by `to`.
std::string six_lab_with(const std::string& from, const std::string& to) {
  std::string lab = read(kLab);
  const std::size_t at = lab.find("\n" + from);
  if (at == std::string::npos) return lab;
  const std::size_t end = lab.find('\n', at + 1);
  return lab.replace(at + 1, end - at - 1, to);
}

// A value refused by the configuration was echoed without its unit ("got -5", "1e+300 is implausible"): as
// written now.
TEST_F(Cli, AConfigurationsRefusedValueIsEchoedAsWritten) {
  write("lab.toml", six_lab_with("g_level = \"5 g\"", "g_level = \"-5 g\""));
  expect_bad_input(run("budget lab.toml"), {"plan.runs[1].g_level: must be positive, got -5 g;"});
  write("lab.toml", six_lab_with("radius = \"2.5 m\"", "radius = \"1e300 m\""));
  expect_bad_input(run("budget lab.toml"),
                   {"centrifuge.radius: 1e300 m is implausible; accepted: an arm radius up "
                    "to 100 m"});
  write("lab.toml", six_lab_with("dthz5 = \"1e-5 rad\"",
                                 "dthz5 = { bound = \"-1e-5 rad\", distribution = \"uniform\" }"));
  expect_bad_input(run("budget lab.toml"), {"tolerances.dthz5.bound: must be positive, got -1e-5 rad;"});
}

// A measured error of the machine far beyond any centrifuge's (1e300 arcsec, a radius error of 1e300 m) was
// simulated with exit 0, or refused as "the means of run '5g' are not finite" with no key; a coefficient of
// 1e308 the same. Each is refused at its line now, in the configuration and in a truth file.
TEST_F(Cli, AnImplausibleErrorOrCoefficientIsRefusedAtItsLine) {
  const std::string measured = "dthz5 = \"1.5 arcsec\"";
  write("lab.toml", six_lab_with(measured, "dthz5 = \"1e300 arcsec\""));
  const int line = line_of(read(kLab), measured);
  expect_bad_input(
      run("simulate lab.toml"),
      {fmt::format("lab.toml:{}:9: errors.dthz5: 1e300 arcsec is implausible for a measured error of "
                   "the machine; accepted: up to 180 deg in size",
                   line)});
  write("lab.toml", six_lab_with(measured, "dR_s = \"1e40 m\""));
  expect_bad_input(run("budget lab.toml"),
                   {"errors.dR_s: 1e40 m is implausible", "accepted: up to 1 m in size"});
  write("lab.toml", six_lab_with(measured, "domega = \"1e99 rad/s\""));
  expect_bad_input(run("budget lab.toml"), {"errors.domega: 1e99 rad/s is implausible", "up to 10 rad/s"});
  write("lab.toml", six_lab_with(measured, "arm_stretch = \"1e99 m/(rad/s)^2\""));
  expect_bad_input(run("budget lab.toml"), {"errors.arm_stretch: 1e99 m/(rad/s)^2 is implausible"});
  // A real measured error is taken.
  write("lab.toml", six_lab_with(measured, "dthz5 = \"10 arcsec\""));
  EXPECT_EQ(run("budget lab.toml -o /dev/null").code, 0);
  write("lab.toml", read(kLab));
  write("truth.toml", "[errors]\ndthz5 = \"1e300 arcsec\"\n");
  expect_bad_input(run("simulate lab.toml --truth truth.toml"),
                   {"truth.toml:2:9: errors.dthz5: 1e300 arcsec is implausible"});
  write("lab.toml", six_lab_with("K3 = \"0.003 deg/s/g^3\"", "K3 = \"1e308 deg/s/g^3\""));
  expect_bad_input(run("simulate lab.toml"),
                   {"instrument.terms.K3: 1e308 deg/s/g^3 is implausible: beyond 1e100 in "
                    "SI units the model's output overflows"});
}

// An empty path (an unset shell variable) was taken as no option: the bundled example for CONFIG, the
// default history store for --db, no observations for report --observations, each with exit 0.
TEST_F(Cli, AnEmptyInputPathIsRefused) {
  write("lab.toml", read(kLab));
  expect_bad_input(run("budget ''"),
                   {"CONFIG: the path is empty (an unset shell variable?); accepted: a "
                    "configuration file (TOML), or no CONFIG at all for the bundled example"});
  expect_bad_input(run("simulate lab.toml --truth ''"), {"--truth: the path is empty"});
  expect_bad_input(run("reduce lab.toml --logs ''"), {"--logs: the path is empty"});
  expect_bad_input(run("report lab.toml --observations '' -o r.html"), {"--observations: the path is empty"});
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
  expect_bad_input(
      run("history show 'SN 0815' --db ''"),
      {"--db: the path is empty (an unset shell variable?); accepted: a history store's path, or no "
       "--db for the default store; run 'ccal history show --help'"});
  expect_bad_input(run("history add '' --db h.sqlite"), {"FILE: the path is empty"});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
  expect_bad_input(run("identify ''"), {"FILE.csv: the path is empty"});
}

// A folder given for a file was "cannot read the file; check the path and permissions": it is said to be a
// folder; a missing file to be missing.
TEST_F(Cli, AFolderGivenForAFileIsSaidToBeOne) {
  fs::create_directories(dir_ / "dir.toml");
  expect_bad_input(run("budget dir.toml"),
                   {"dir.toml: cannot read the file: it is a folder; accepted: the path of a "
                    "file"});
  expect_bad_input(run("identify dir.toml"), {"dir.toml: cannot read the file: it is a folder"});
  expect_bad_input(run("budget none.toml"),
                   {"none.toml: cannot read the file: no such file; accepted: the path of "
                    "an existing file (check its spelling and folder)"});
}

// identify --input-column with a mistyped column was passed over in silence where every term had a column of
// its own (an observations file): exit 0.
TEST_F(Cli, AnInputColumnThatIsNotThereIsRefused) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --observations-out obs.csv -o /dev/null").code, 0);
  expect_bad_input(
      run("identify obs.csv --input-column nope"),
      {"obs.csv:2: nope: no such column (needed by the input column named); accepted: one of the "
       "columns run, a_i, output"});
  EXPECT_EQ(run("identify obs.csv --input-column a_i -o /dev/null").code, 0);
}

// Messages that named a library field or used the parser's words: "Monte Carlo: max_trials = 100 leaves …",
// "two targets on K3; give one …" (no option, nothing accepted), "--width: Value 5 not in range 40 to 10000".
TEST_F(Cli, MessagesNameTheOptionAndWhatIsAccepted) {
  expect_bad_input(run("montecarlo --digits 2 --max-trials 100"),
                   {"--max-trials: 100 leaves fewer than the 2 stages of 10000 trials the adaptive procedure "
                    "needs; accepted: at least 20000 (or fewer trials a stage)"});
  expect_bad_input(run("allocate --target K3=1e-3 --target K3=2e-3 --verify-trials 0"),
                   {"--target: K3 has two targets; accepted: one target per coefficient"});
  expect_bad_input(
      run("allocate --target K3=1e-3 --width 5 --verify-trials 0"),
      {"--width: 5 is out of range; accepted: a whole number from 40 to 10000; run 'ccal allocate --help'"});
  expect_bad_input(run("budget --width abc"),
                   {"--width: abc is not a number; accepted: a whole number from 40 to 10000"});
  expect_bad_input(
      run("budget --coverage-factor 2 --coverage-probability 0.9"),
      {"--coverage-factor: 2 and --coverage-probability 0.9 are two coverages; accepted: one of them"});
}

// A word too many was CLI11's "The following argument was not expected: lab.toml", without what is accepted.
TEST_F(Cli, AWordTooManySaysWhatTheCommandTakes) {
  expect_bad_input(
      run("budget a.toml b.toml"),
      {"'b.toml': not expected (a word too many); accepted: one CONFIG, each option with its value (a "
       "path with spaces in quotes); run 'ccal budget --help'"});
  expect_bad_input(run("history show 'SN 0815' extra"),
                   {"'extra': not expected (a word too many); accepted: one "
                    "SERIAL"});
}

// A phase or an azimuth of 1e300 deg was taken with exit 0, wrapped to whatever its lost digits gave.
TEST_F(Cli, AnAngleOfThePlanBeyondATurnIsRefused) {
  write("lab.toml", six_lab_with("terminal_phase = \"180 deg\"", "terminal_phase = \"1e300 deg\""));
  expect_bad_input(run("budget lab.toml"),
                   {"plan.terminal_phase: 1e300 deg is implausible; accepted: an angle of at "
                    "most one turn in size (-360 deg to 360 deg)"});
  write("lab.toml", six_lab_with("arm_azimuth = \"0 deg\"", "arm_azimuth = \"-400 deg\""));
  expect_bad_input(run("budget lab.toml"), {"plan.arm_azimuth: -400 deg is implausible"});
}

}  // namespace
