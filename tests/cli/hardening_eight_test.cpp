// Hardening, round eight, through the program: what a fresh round of a careless user's wrong inputs found, each
// refused in words that say what is wrong, where, and what is accepted, and nothing left behind or lost.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

// `ccal --completion bash --completion zsh` said "'bash' is not a shell ccal completes", `--completion` alone
// said only what is accepted, `--man-page extra` only what is wrong.
TEST_F(Cli, ShellDocsSayWhatIsWrongAndWhatIsAccepted) {
  expect_bad_input(run("--completion"), {"--completion: needs the shell's name; accepted: bash, zsh or fish"});
  expect_bad_input(run("--completion bash --completion zsh"),
                   {"--completion: takes one shell, and '--completion' is a word too many; accepted: bash, zsh or "
                    "fish"});
  expect_bad_input(run("--completion bash budget"),
                   {"--completion: takes one shell, and 'budget' is a word too many; accepted: bash, zsh or fish"});
  expect_bad_input(run("--completion tcsh"), {"--completion: 'tcsh' is not a shell ccal completes; accepted: "});
  expect_bad_input(run("--man-page extra"),
                   {"--man-page: takes no argument, got 'extra'; accepted: ccal --man-page alone"});
  EXPECT_EQ(run("--completion zsh").code, 0);
}

// A JSON statement or a CSV log given for a configuration or a truth file was toml++'s syntax error alone
// ("expected keys, tables, whitespace or comments, saw '{'"), with nothing said of what the file should be.
TEST_F(Cli, AJsonOrCsvFileGivenForATomlFileIsSaidSo) {
  write("st.json", "{\n  \"coverage_probability\": 0.95\n}\n");
  write("log.csv", "time,pulses\n0,0\n1,5\n");
  expect_bad_input(run("budget st.json"),
                   {"st.json:1:1: TOML syntax error: ",
                    " (the file opens a JSON document, a statement or a result of ccal?, not TOML); accepted: a "
                    "configuration file ([site], [centrifuge], [instrument], [plan], …; docs/config.md), e.g. "
                    "examples/lab.toml"});
  expect_bad_input(run("budget log.csv"), {"log.csv:1:5: TOML syntax error: ", "; accepted: a configuration file"});
  expect_bad_input(run("simulate " + quote(kLab) + " --truth st.json -o /dev/null"),
                   {"st.json:1:1: TOML syntax error: ", "not TOML); accepted: a truth file in TOML: [errors] with "
                                                        "the values the simulated machine has"});
}

// An empty layout file (/dev/null, a file truncated to nothing) wrote the logs in ccal's own layout with exit 0,
// as an empty truth file once simulated a perfect machine.
TEST_F(Cli, AnEmptyLayoutFileIsRefused) {
  write("empty.toml", "");
  expect_bad_input(run("simulate " + quote(kLab) + " --logs-out L --log-layout empty.toml -o /dev/null"),
                   {"empty.toml:1: the layout file holds no TOML table or key (it is empty); accepted: a layout file "
                    "in TOML: a manifest's [format] and [columns] tables",
                    "(for ccal's own layout, give no layout file)"});
  EXPECT_FALSE(fs::exists(dir_ / "L"));
}

// A binary file given for a table dumped hundreds of its bytes into the message ("ragged row: 1 field, …").
TEST_F(Cli, ABinaryFileGivenForATableIsSaidToBeOne) {
  write("bin.csv", std::string("PK\x03\x04\x14\x00\x06\x00\x08\x00\x00\x00!\x00\xd5\xa1\nxx,yy\n1,2\n", 24));
  const Result r = run("identify bin.csv --terms K0,K1");
  expect_bad_input(r, {"bin.csv:1:3: the byte 0x03 is no character of a text line: the file is not a text table (a "
                       "binary file, or text in UTF-16?); accepted: a CSV text file (UTF-8)"});
  EXPECT_EQ(r.err.find("PK"), std::string::npos) << r.err;
  // UTF-16 text (NUL bytes between the characters) likewise.
  write("u16.csv", std::string("\xff\xfe" "a\0,\0b\0\n\0", 10));
  expect_bad_input(run("identify u16.csv --terms K0"), {"u16.csv:1:", "the file is not a text table"});
  // A tab is a character of a text line (a tab-separated table is said to be one, as before).
  write("tabs.csv", "a_i\toutput\n1\t2\n");
  expect_bad_input(run("identify tabs.csv --terms K0"), {"the delimiter is probably a tab"});
}

// `--top 1e3` was "1e3 is out of range; accepted: a number from 1 to 100000" (--trials 1e4 is taken); `--top 2.5`
// "is out of range" too.
TEST_F(Cli, ACountWrittenAsADecimalNumberIsTakenOrSaidToBeNoWholeNumber) {
  const Result thousand = run("budget --top 1e3 --format json");
  EXPECT_EQ(thousand.code, 0) << thousand.err;
  const Result digits = run("budget --top 1000 --format json");
  EXPECT_EQ(thousand.out, digits.out);
  EXPECT_EQ(run("budget --width 1.2e2 -o b.txt").code, 0);
  expect_bad_input(run("budget --top 2.5"),
                   {"--top: 2.5 is not a whole number; accepted: a whole number from 1 to 100000"});
  expect_bad_input(run("budget --top 1e6"), {"--top: 1000000 is out of range; accepted: a whole number from 1 to "
                                             "100000"});
}

// A number that is not one was "accepted: e.g. 0.5 or 2e-3" whatever the option's range: 2e-3 is no coverage
// probability, no --max-scale.
TEST_F(Cli, ANumberThatIsNotOneSaysTheOptionsRange) {
  expect_bad_input(run("budget --coverage-probability 95%"),
                   {"--coverage-probability: '95%' is not a finite number; accepted: a number in [0.5, 1), e.g. "
                    "0.95"});
  expect_bad_input(run("allocate --target K3=1e-3 --max-scale inf"),
                   {"--max-scale: 'inf' is not a finite number; accepted: 1e-06 to 1000000, e.g. 10"});
  expect_bad_input(run("design --tradeoff 0.5,abc"),
                   {"--tradeoff: 'abc' is not a finite number; accepted: numbers separated by single commas, e.g. "
                    "0.5,0.75,1"});
}

// `identify --fix K1=1e308` on a plain table blamed the data ("largest |y| = 8.2, largest regressor 4") and named
// neither the fixed term nor its value; an empty --input-column was "no such column (needed by the input column
// named)".
TEST_F(Cli, AFixedTermThatOverflowsAndAnEmptyColumnAreNamed) {
  write("t.csv", "a_i,output\n1,2\n2,4.1\n3,5.9\n4,8.2\n");
  expect_bad_input(run("identify t.csv --terms K0 --fix K1=1e308"),
                   {"the fixed term K1 = 1e+308, times its regressor (up to 4), is far beyond data of largest |y| = 8.2 and "
                    "overflows the arithmetic",
                    "accepted: a fixed value of the size the term has in these data's units"});
  expect_bad_input(run("identify t.csv --terms K0,K1 --input-column ''"),
                   {"--input-column: '' is empty; accepted: the name of a column of the file"});
  expect_bad_input(run("identify t.csv --terms K0,K1 --output-column ''"), {"--output-column: '' is empty"});
  EXPECT_EQ(run("identify t.csv --terms K0 --fix K1=2").code, 0);
}

// `montecarlo --max-trials 100` without --digits ran a million trials with exit 0: the option bounds the adaptive
// procedure only, and was passed over in silence (in report too).
TEST_F(Cli, MaxTrialsWithoutTheAdaptiveProcedureIsRefused) {
  const std::string message =
      "--max-trials: 100 bounds the adaptive procedure, which --digits 0 does not run (M is then --trials); "
      "accepted: --max-trials with --digits 1 to 6, or --max-trials left out";
  expect_bad_input(run("montecarlo --max-trials 100 -o m.txt"), {message});
  expect_bad_input(run("report --trials 200 --max-trials 100 -o r.html"), {message});
  EXPECT_FALSE(fs::exists(dir_ / "m.txt") || fs::exists(dir_ / "r.html"));
  EXPECT_EQ(run("montecarlo --digits 1 --max-trials 20000 -o m.txt").code, 0);
}

// reduce --statement-trials 100 (or --seed 5) without --statement ran with exit 0, the option passed over.
TEST_F(Cli, AStatementsOptionWithoutTheStatementIsRefused) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --logs-out L --observations-out obs.csv -o /dev/null").code, 0);
  expect_bad_input(run("reduce " + quote(kLab) + " --logs L --statement-trials 100 -o r.txt"),
                   {"--statement-trials: 100 is an option of the calibration statement, which is not asked for; "
                    "accepted: --statement-trials with --statement, or --statement-trials left out"});
  expect_bad_input(run("reduce " + quote(kLab) + " --logs L --seed 5 -o r.txt"), {"--seed: 5 is an option of the "
                                                                                  "calibration statement"});
  expect_bad_input(run("identify obs.csv --coverage-factor 2 -o r.txt"),
                   {"--coverage-factor: 2 is an option of the calibration statement"});
  expect_bad_input(run("identify obs.csv --mode paper -o r.txt"), {"--mode: paper is an option of the calibration "
                                                                   "statement"});
  EXPECT_FALSE(fs::exists(dir_ / "r.txt"));
  // reduce's mode is its own too; with --statement every option is taken.
  EXPECT_EQ(run("reduce " + quote(kLab) + " --logs L --mode paper -o r.txt").code, 0);
  EXPECT_EQ(run("reduce " + quote(kLab) + " --logs L --statement --statement-trials 0 --seed 5 -o s.txt").code, 0);
}

// A table whose input takes one value was refused with a centrifuge's advice ("add g-levels or runs with the IA
// reversed"); a plain table has no plan.
TEST_F(Cli, AnIllPosedTableIsAdvisedInTheTablesTerms) {
  write("same.csv", "a_i,output\n1,2\n1,2.1\n1,1.9\n");
  const Result r = run("identify same.csv --terms K0,K1");
  expect_bad_input(r, {"same.csv: the plan cannot separate K0 and K1", "; accepted: rows at more distinct values of "
                                                                       "the input column (a_i)"});
  EXPECT_EQ(r.err.find("g-levels"), std::string::npos) << r.err;
}

// `reduce --logs L/manifest.toml` was "L/manifest.toml/manifest.toml: no manifest in the folder".
TEST_F(Cli, TheManifestsPathGivenForItsFolderIsSaidSo) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --logs-out L -o /dev/null").code, 0);
  expect_bad_input(run("reduce " + quote(kLab) + " --logs L/manifest.toml"),
                   {"L/manifest.toml: a file, not the folder of the logs; accepted: the folder that holds "
                    "manifest.toml and the logs, e.g. L"});
}

// `report --statement-trials 100` without --observations ran with exit 0, the option passed over.
TEST_F(Cli, TheStatementsTrialsOfAReportWithoutObservationsAreRefused) {
  expect_bad_input(run("report --trials 200 --statement-trials 100 -o r.html"),
                   {"--statement-trials: 100 checks the statement of observations, and none are given; accepted: "
                    "--statement-trials with --observations, or --statement-trials left out"});
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
}

// A statement whose unit ccal cannot read ("furlong") was recorded; a store of one byte was "an empty file"; a
// missing statement "cannot read it"; an import into the exported file itself "damaged … restore it from a
// backup".
TEST_F(Cli, HistoryRefusesAnUnknownUnitAndSaysWhatAFileIs) {
  write("st.json", R"({"coverage_probability": 0.95, "coefficients": {"K0": {"unit": "furlong",
      "corrected_estimate": 1.5, "expanded_uncertainty": 0.2, "coverage_factor": 2}}})");
  expect_bad_input(run("history add st.json --db h.sqlite --serial S1 --date 2026-01-01"),
                   {"st.json: not a calibration statement: coefficient K0's unit 'furlong' is no unit ccal reads "
                    "(e.g. deg/s, deg/s/g^2, mA)"});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
  write("note.sqlite", "x");
  expect_bad_input(run("history list --db note.sqlite"),
                   {"note.sqlite: a file of 1 bytes that holds no SQLite database, not a history store; accepted: a "
                    "ccal history store, or a new file name"});
  EXPECT_EQ(read(dir_ / "note.sqlite"), "x");
  expect_bad_input(run("history add missing.json --db h.sqlite --serial S1 --date 2026-01-01"),
                   {"missing.json: no such file; accepted: a calibration statement's JSON file (check its spelling and "
                    "folder)"});
  write("deg.json", R"({"coverage_probability": 0.95, "coefficients": {"K0": {"unit": "deg/s",
      "corrected_estimate": 1.5, "expanded_uncertainty": 0.2, "coverage_factor": 2}}})");
  ASSERT_EQ(run("history add deg.json --db h.sqlite --serial S1 --date 2026-01-01").code, 0);
  ASSERT_EQ(run("history export S1 --db h.sqlite -o e.json").code, 0);
  const std::string exported = read(dir_ / "e.json");
  expect_bad_input(run("history import e.json --db e.json"),
                   {"--db: e.json is also the file imported; accepted: a history store other than the exported "
                    "file"});
  EXPECT_EQ(read(dir_ / "e.json"), exported);
}

// The confirming round: a negative noise density without the value and "accepted:"; a cell of 2e400 "is not a
// number"; `report --run ''` the default run with exit 0; `report --allocate-target` given twice for one
// coefficient said of --target; `design --target` given twice for one coefficient took the second in silence.
TEST_F(Cli, ConfirmingRoundValuesTargetsAndRuns) {
  std::string lab = read(kLab);
  const std::string density = "noise_density = \"0.0005";
  lab.replace(lab.find(density), density.size(), "noise_density = \"-0.0005");
  write("noise.toml", lab);
  expect_bad_input(run("budget noise.toml"),
                   {"instrument.noise_density: must not be negative, got -0.0005 deg/s/rtHz; accepted: a noise "
                    "density >= 0"});
  write("big.csv", "a_i,output\n1,2e400\n2,4\n3,6\n");
  expect_bad_input(run("identify big.csv --terms K0,K1"),
                   {"big.csv:2:2: output: '2e400' is out of range of double; accepted: a finite number"});
  expect_bad_input(run("report --trials 200 --run '' -o r.html"),
                   {"--run: '' names no run; accepted: a run name or a 1-based index, or --run left out"});
  expect_bad_input(run("report --trials 200 --allocate-target K3=1e-3 --allocate-target K3=2e-3 -o r.html"),
                   {"--allocate-target: K3 has two targets; accepted: one target per coefficient"});
  expect_bad_input(run("report --trials 200 --design-target K3=1e-3 --design-target K3=2e-3 -o r.html"),
                   {"--design-target: K3 has two targets"});
  expect_bad_input(run("design --target K3=1e-4 --target K3=1e-5 -o d.txt"),
                   {"--target: K3 has two targets; accepted: one target per coefficient"});
  EXPECT_FALSE(fs::exists(dir_ / "r.html") || fs::exists(dir_ / "d.txt"));
}

// The second confirming round: a count in hexadecimal taken (--top 0x10 listed 16 rows), a count of 1e400 "not a
// whole number", a blank column name shown as " : no such column", a JSON file with a byte-order mark not said to
// be one, and the JSON parser's "[json.exception.parse_error.101]" tag in the history's messages.
TEST_F(Cli, SecondConfirmingRoundCountsNamesAndJson) {
  expect_bad_input(run("budget --top 0x10"),
                   {"--top: '0x10' is not a decimal number; accepted: a whole number in decimal digits"});
  expect_bad_input(run("budget --width 1e400"), {"--width: 1e400 is out of range; accepted: a whole number from 40 "
                                                 "to 10000"});
  write("t.csv", "a_i,output\n1,2\n2,4.1\n3,5.9\n");
  expect_bad_input(run("identify t.csv --terms K0,K1 --output-column ' '"),
                   {"--output-column: ' ' is blank; accepted: the name of a column of the file"});
  write("bom.toml", "\xEF\xBB\xBF{\"a\": 1}");
  expect_bad_input(run("budget bom.toml"), {"(the file opens a JSON document, a statement or a result of ccal?, not "
                                            "TOML)"});
  write("tiny.txt", "ab");
  const Result r = run("history import tiny.txt --db h.sqlite");
  expect_bad_input(r, {"tiny.txt: not an exported calibration history: not JSON (parse error at line 1, column 1: "});
  EXPECT_EQ(r.err.find("json.exception"), std::string::npos) << r.err;
}

// The third confirming round: `identify --weight-column ''` fitted unweighted with exit 0; `design
// --verify-trials 5` named --trials, an option design does not have (and, with a stated coverage factor, a
// coverage probability not given).
TEST_F(Cli, ThirdConfirmingRoundAWeightColumnAndTheVerificationsTrials) {
  write("t.csv", "a_i,output,s\n1,2,0.1\n2,4.1,0.1\n3,5.9,0.1\n");
  expect_bad_input(run("identify t.csv --terms K0,K1 --weight-column ''"),
                   {"--weight-column: '' names no column; accepted: the column of the standard deviations of y, or "
                    "--weight-column left out for an unweighted fit"});
  const Result r = run("design --verify-trials 5 --starts 0 -o d.txt");
  expect_bad_input(r, {"--coverage-probability: 0.95 with --verify-trials = 5: ", "accepted: --verify-trials at least "
                                                                                 "11 for this p"});
  EXPECT_EQ(r.err.find("--trials"), std::string::npos) << r.err;
  expect_bad_input(run("design --verify-trials 20 --coverage-factor 3 --starts 0 -o d.txt"),
                   {"--verify-trials: 20 are too few for the coverage interval of the stated coverage factor 3 (p = "
                    "0.9973 of a normal quantity)",
                    "accepted: --verify-trials at least 186, or 0 (none)"});
  EXPECT_FALSE(fs::exists(dir_ / "d.txt"));
}

// The last round: a serial number typed with blanks around it (" SN 0815 ") was recorded as another instrument's
// history than SN 0815's; a blank --weight-column was " : no such column".
TEST_F(Cli, LastRoundASerialWithBlanksAroundItAndABlankWeightColumn) {
  write("st.json", R"({"coverage_probability": 0.95, "coefficients": {"K0": {"unit": "deg/s",
      "corrected_estimate": 1.5, "expanded_uncertainty": 0.2, "coverage_factor": 2}}})");
  expect_bad_input(run("history add st.json --db h.sqlite --serial ' SN 0815 ' --date 2026-01-01"),
                   {"--serial: ' SN 0815 ' begins or ends with a blank, which would make it another serial number "
                    "than the one without; accepted: the instrument's serial number, printable characters and not "
                    "blank, without blanks around it"});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
  EXPECT_EQ(run("history add st.json --db h.sqlite --serial 'SN 0815' --date 2026-01-01").code, 0);
  write("t.csv", "a_i,output,s\n1,2,0.1\n2,4.1,0.1\n3,5.9,0.1\n");
  expect_bad_input(run("identify t.csv --terms K0,K1 --weight-column ' '"),
                   {"--weight-column: ' ' is blank; accepted: the name of a column of the file"});
}

}  // namespace
