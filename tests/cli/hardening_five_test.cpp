// Hardening, a fresh round over every surface, through the program: what a careless user's wrong inputs
// found, each refused in words that say what is wrong, where, and what is accepted, and nothing left behind.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <csignal>
#include <sstream>
#include <string>
#include <vector>

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

// A reduction of two instruments given to history add was "not a calibration statement: no coefficients",
// though it holds two: which one is recorded is said to be the user's choice; no store is left behind.
TEST_F(Cli, HistoryAddOfTheReductionOfSeveralInstrumentsSaysWhichItHolds) {
  const std::string two = quote(CCAL_SOURCE_DIR + "/examples/daq/two_short.toml");
  const std::string logs = quote(CCAL_SOURCE_DIR + "/examples/daq/two_instruments");
  ASSERT_EQ(run("reduce " + two + " --logs " + logs + " --statement --statement-trials 0 --format json -o r.json")
                .code,
            0);
  expect_bad_input(run("history add r.json --db h.sqlite"),
                   {"r.json: holds the statements of 2 instruments (A, B) of a test of several; accepted: one "
                    "instrument's statement alone"});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
  ASSERT_EQ(run("reduce " + two + " --logs " + logs +
                " --instrument B --statement --statement-trials 0 --statement-out b.json -o /dev/null")
                .code,
            0);
  const Result added = run("history add b.json --db h.sqlite");
  EXPECT_EQ(added.code, 0) << added.err;
  EXPECT_NE(added.out.find("of SN 0816"), std::string::npos) << added.out;
}

// design --plan-out of a job wrote its `setup = "../lab.toml"` as it was, which names no file from another
// folder: the plan written could not be read. The set-up is named from the written file's folder now.
TEST_F(Cli, ThePlanOfAJobWrittenElsewhereNamesItsSetUpFromThere) {
  const std::string job = quote(CCAL_SOURCE_DIR + "/examples/daq/two_short.toml");
  const Result designed =
      run("design " + job + " --instrument A --verify-trials 0 --plan-out sub/plan.toml --format json -o d.json");
  ASSERT_EQ(designed.code, 2) << designed.err;  // the folder sub does not exist: refused, nothing written
  fs::create_directories(dir_ / "sub");
  ASSERT_EQ(run("design " + job + " --instrument A --verify-trials 0 --plan-out sub/plan.toml -o /dev/null").code, 0);
  const std::string plan = read(dir_ / "sub" / "plan.toml");
  const fs::path setup = fs::weakly_canonical(fs::path(CCAL_SOURCE_DIR) / "examples" / "lab.toml");
  EXPECT_NE(plan.find(fmt::format("setup = \"{}\"", setup.lexically_relative(fs::weakly_canonical(dir_ / "sub"))
                                                         .string())),
            std::string::npos)
      << plan.substr(0, 1200);
  const Result budget = run("budget sub/plan.toml --instrument A --format json");
  EXPECT_EQ(budget.code, 0) << budget.err;
  // Beside the job, the line is kept as written.
  fs::copy(CCAL_SOURCE_DIR + "/examples/daq/two_short.toml", dir_ / "sub" / "job.toml");
  fs::copy(CCAL_SOURCE_DIR + "/examples/lab.toml", dir_ / "lab.toml");
  ASSERT_EQ(run("design sub/job.toml --instrument A --verify-trials 0 --plan-out sub/again.toml -o /dev/null").code,
            0);
  EXPECT_NE(read(dir_ / "sub" / "again.toml").find("\nsetup = \"../lab.toml\"\n"), std::string::npos);
}

// A configuration given where a table is read (identify lab.toml, a manifest as a run's log) was "the header
// is one name … the delimiter is probably whitespace": it is said to be TOML.
TEST_F(Cli, ATomlFileGivenForATableIsSaidToBeOne) {
  write("lab.toml", read(kLab));
  expect_bad_input(run("identify lab.toml"),
                   {fmt::format("lab.toml:{}:1: the header, '[site]', is a line of TOML (a configuration or a "
                                "manifest?), not a table's header; accepted: a CSV table whose header names its "
                                "columns",
                                line_of(read(kLab), "[site]"))});
  ASSERT_EQ(run("simulate lab.toml --logs-out L -o /dev/null").code, 0);
  expect_bad_input(run("reduce lab.toml --log 5g=L/manifest.toml --log 10g=L/10g.csv --log 15g=L/15g.csv"),
                   {"L/manifest.toml:2:1: the header, '[columns]', is a line of TOML"});
  expect_bad_input(run("identify " + quote(CCAL_SOURCE_DIR + "/examples/lab_job.toml")),
                   {"lab_job.toml:10:1: the header, 'setup = \"lab.toml\"', is a line of TOML"});
}

// design --tradeoff of a test of several instruments is refused naming the option as each front end spells
// it: the library wrote "--tradeoff", which Python does not know.
TEST_F(Cli, TheTradeoffOfSeveralInstrumentsIsRefusedInTheProgramsWords) {
  expect_bad_input(run("design " + quote(CCAL_SOURCE_DIR + "/examples/daq/two_short.toml") +
                       " --tradeoff 0.5,1 --verify-trials 0"),
                   {"--tradeoff: 0.5 is not taken for a test of 2 instruments", "accepted: --tradeoff with a "
                                                                                "configuration of one instrument"});
}

// The lines of a file, and a file of lines.
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}
std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  return text;
}

// One wild cell of a log's output moved the run's mean with exit 0: a count's last cell 539 counts high
// (K0 moved), its first cell a glitch (the mean 7.6 % off), a sampled output's decimal point lost (0.8796 read
// as 87.96: the mean 1.6 % off). Each is refused at its line now; a counter that wraps is still said so.
TEST_F(Cli, AWildCellOfALogsOutputIsRefusedAtItsLine) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --logs-out L -o /dev/null").code, 0);
  const std::string others = " --log 10g=L/10g.csv --log 15g=L/15g.csv -o /dev/null";
  const std::vector<std::string> log = lines_of(read(dir_ / "L" / "5g.csv"));  // time,pulses,theta1,gamma
  ASSERT_EQ(run("reduce " + quote(kLab) + " --log 5g=L/5g.csv" + others).code, 0);
  const auto with_count = [&](std::size_t index, const std::string& count) {
    std::vector<std::string> lines = log;
    const std::size_t a = lines[index].find(','), b = lines[index].find(',', a + 1);
    lines[index] = lines[index].substr(0, a + 1) + count + lines[index].substr(b);
    return joined(lines);
  };
  const std::string last = log.back().substr(log.back().find(',') + 1);
  const long long last_count = std::stoll(last.substr(0, last.find(',')));
  write("last.csv", with_count(log.size() - 1, std::to_string(last_count + 539)));
  expect_bad_input(run("reduce " + quote(kLab) + " --log 5g=last.csv" + others),
                   {fmt::format("last.csv:{}:2: pulses: the count's step to this line", log.size()),
                    "departs from the log's other steps", "a wild count in this line or the one before"});
  write("first.csv", with_count(1, "-300000"));
  expect_bad_input(run("reduce " + quote(kLab) + " --log 5g=first.csv" + others),
                   {"first.csv:3:2: pulses: the count's step to this line", "accepted: within 20 of their "
                                                                            "standard deviations or 10 counts"});
  // A 16-bit counter that wraps, undeclared: said so, not a wild count.
  std::vector<std::string> wrapped = log;
  for (std::size_t k = 1; k < wrapped.size(); ++k) {
    const std::size_t a = wrapped[k].find(','), b = wrapped[k].find(',', a + 1);
    const long long count = std::stoll(wrapped[k].substr(a + 1, b - a - 1)) % 65536;
    wrapped[k] = wrapped[k].substr(0, a + 1) + std::to_string(count) + wrapped[k].substr(b);
  }
  write("wrap.csv", joined(wrapped));
  expect_bad_input(run("reduce " + quote(kLab) + " --log 5g=wrap.csv" + others), {"a counter that wraps"});
  // The output sampled: the count's rate over each step, in deg/s (a pulse of 1e-4 deg); one lost digit.
  std::vector<std::string> sampled{"time,output"};
  double t0 = 0, p0 = 0;
  for (std::size_t k = 1; k < log.size(); ++k) {
    const std::size_t a = log[k].find(','), b = log[k].find(',', a + 1);
    const double t = std::stod(log[k].substr(0, a)), p = std::stod(log[k].substr(a + 1, b - a - 1));
    if (k > 1) sampled.push_back(fmt::format("{},{}", t0, (p - p0) * 1e-4 / (t - t0)));
    t0 = t;
    p0 = p;
  }
  write("sampled.csv", joined(sampled));
  ASSERT_EQ(run("reduce " + quote(kLab) + " --log 5g=sampled.csv" + others).code, 0);
  sampled[100] = sampled[100].substr(0, sampled[100].find(',')) + ",87.96";
  write("sampled.csv", joined(sampled));
  expect_bad_input(run("reduce " + quote(kLab) + " --log 5g=sampled.csv" + others),
                   {"sampled.csv:101:2: output: 87.96 departs from the log's other samples (0.879594, standard deviation",
                    "a wild reading: a glitch, a lost digit, a cell edited by hand"});
}

}  // namespace
