// Hardening, round seven, through the program: what round six left open and what a fresh round of a careless
// user's wrong inputs found, each refused in words that say what is wrong, where, and what is accepted, and
// nothing left behind or lost.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

// A statement of one coefficient K0 [deg/s] with U and k = 2 (unique names: unity builds join the test files).
std::string seven_statement(const std::string& certificate = "") {
  return fmt::format(R"({{"coverage_probability": 0.95, {}"coefficients": {{"K0": {{"unit": "deg/s",
      "corrected_estimate": 1.5, "expanded_uncertainty": 0.2, "coverage_factor": 2}}}}}})",
                     certificate);
}

// A coverage probability given beside a stated coverage factor was taken when it was the default's value
// (0.95), which the options could not tell from none given: every command that takes both refuses both.
TEST_F(Cli, TwoCoveragesAreRefusedAlsoAtTheDefaultProbability) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --observations-out obs.csv --logs-out L -o /dev/null").code, 0);
  const std::string both = " --coverage-probability 0.95 --coverage-factor 2";
  for (const std::string& command :
       {"identify obs.csv --config " + quote(kLab) + " --statement" + both + " -o out.txt",
        "reduce " + quote(kLab) + " --logs L --statement" + both + " -o out.txt", "budget" + both + " -o out.txt",
        "design" + both + " -o out.txt", "report" + both + " -o out.html"}) {
    SCOPED_TRACE(command);
    expect_bad_input(run(command), {"--coverage-factor: 2 and --coverage-probability 0.95 are two coverages; "
                                    "accepted: one of them (a stated coverage factor, or a coverage "
                                    "probability)"});
    EXPECT_FALSE(fs::exists(dir_ / "out.txt") || fs::exists(dir_ / "out.html"));
  }
  // Either alone is taken; the help still states the default p.
  EXPECT_EQ(run("budget --coverage-probability 0.95 -o a.txt").code, 0);
  EXPECT_EQ(run("budget --coverage-factor 2 -o b.txt").code, 0);
  for (const char* verb : {"budget", "identify", "reduce", "design", "report", "montecarlo"}) {
    const Result help = run(std::string(verb) + " --help");
    EXPECT_NE(help.out.find("(default: 0.95)"), std::string::npos) << verb << "\n" << help.out;
  }
}

// `design --plan-out plan.json` wrote TOML under a name that says JSON; the plan is a configuration, which is
// read as TOML: another extension is refused before the design, and nothing is written.
TEST_F(Cli, ThePlanIsWrittenOnlyUnderATomlName) {
  for (const char* name : {"plan.json", "plan", "plan.toml.bak"}) {
    expect_bad_input(run(fmt::format("design --plan-out {} -o d.txt", name)),
                     {fmt::format("--plan-out: '{}' has no .toml extension, and the plan is written as a TOML "
                                  "configuration; accepted: FILE.toml, e.g. designed.toml",
                                  name)});
    EXPECT_FALSE(fs::exists(dir_ / name)) << name;
  }
  EXPECT_FALSE(fs::exists(dir_ / "d.txt"));
}

// `history add --date 9999-12-31` was recorded: a date after today (UTC) is refused, given or from the
// statement's certificate, and no store is left behind.
TEST_F(Cli, ACalibrationDatedAfterTodayIsNotRecorded) {
  write("st.json", seven_statement());
  expect_bad_input(run("history add st.json --db h.sqlite --serial S1 --date 9999-12-31"),
                   {"--date: 9999-12-31 is after today (", ", UTC), and a calibration is recorded once it is done; "
                                                           "accepted: its date, YYYY-MM-DD, up to "});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
  write("future.json",
        seven_statement(R"("certificate": {"serial_number": "S1", "date_of_calibration": "9999-12-31"}, )"));
  expect_bad_input(run("history add future.json --db h.sqlite"),
                   {"future.json: date of calibration '9999-12-31' ([certificate] date_of_calibration) is after "
                    "today (",
                    "accepted: a statement of a calibration done by "});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
  // An earlier date is recorded.
  EXPECT_EQ(run("history add st.json --db h.sqlite --serial S1 --date 2020-02-29").code, 0);
}

// A write that fails for want of space said only "No space left on device": it says what is accepted.
TEST_F(Cli, AFullDeviceSaysWhatIsAccepted) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  expect_bad_input(run("budget -o /dev/full"),
                   {"-o: cannot write '/dev/full': No space left on device; accepted: a path on a device with "
                    "space for the output (or free some space)"});
}

// A mistyped option was "'--coverage-probabilty': not expected (a word too many)", and a value outside a
// choice CLI11's "yaml not in {text,json,csv}": the option is named as unknown with the nearest one, the choice
// with what is accepted.
TEST_F(Cli, AMistypedOptionIsNamedWithTheNearestAndAChoiceWithItsValues) {
  expect_bad_input(run("budget --coverage-probabilty 0.9"),
                   {"--coverage-probabilty: no such option; did you mean '--coverage-probability'? accepted: "
                    "--help, --instrument, --mode, --coverage-probability, --coverage-factor, --derivatives, --top, ",
                    "run 'ccal budget --help'"});
  expect_bad_input(run("report --format json -o r.html"), {"--format: no such option; accepted: --help, "});
  write("st.json", seven_statement());
  expect_bad_input(run("history add st.json --db h.sqlite --instrument X"),
                   {"--instrument: no such option; accepted: --help, --db, --serial, --date, --format, --output"});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
  expect_bad_input(run("budget -x"), {"-x: no such option; accepted: "});
  expect_bad_input(run("budget --format yaml"),
                   {"--format: 'yaml' is not accepted; accepted: text, json, csv; run 'ccal budget --help'"});
  // A word that is no option is still a word too many.
  expect_bad_input(run("budget a.toml b.toml"), {"'b.toml': not expected (a word too many)"});
}

// A file whose name says another format than it holds was written: text or JSON under .json or .csv,
// observations (CSV) or samples under .json, the report's HTML page under .pdf, the printed PDF under .html.
TEST_F(Cli, AFileNamedForAnotherFormatIsRefused) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --logs-out L -o /dev/null").code, 0);
  const std::pair<std::string, std::string> cases[] = {
      {"budget -o b.json",
       "-o: 'b.json' names a JSON file, and -o writes text; accepted: a name that says no other format, e.g. "
       "FILE.txt, or --format json for JSON"},
      {"budget --format json -o b.CSV", "-o: 'b.CSV' names a CSV file, and -o writes JSON; accepted: FILE.json, "
                                        "or --format csv for CSV"},
      {"reduce " + quote(kLab) + " --logs L --format csv -o b.json", "-o: 'b.json' names a JSON file"},
      {"simulate " + quote(kLab) + " --observations-out b.json -o b.txt",
       "--observations-out: 'b.json' names a JSON file, and --observations-out writes CSV; accepted: FILE.csv"},
      {"montecarlo --trials 100 --samples-out b.json -o b.txt",
       "--samples-out: 'b.json' names a JSON file, and --samples-out writes CSV; accepted: FILE.csv or FILE.npy"},
      {"report --trials 200 -o b.pdf",
       "-o: 'b.pdf' names a PDF file, and -o writes HTML; accepted: FILE.html, or --pdf FILE.pdf for the page "
       "printed as PDF"},
      {"report --trials 200 --pdf b.html -o b.txt", "--pdf: 'b.html' names an HTML file, and --pdf writes PDF"},

  };
  for (const auto& [command, message] : cases) {
    SCOPED_TRACE(command);
    expect_bad_input(run(command), {message});
    for (const char* name : {"b.json", "b.CSV", "b.txt", "b.pdf", "b.html"}) EXPECT_FALSE(fs::exists(dir_ / name));
  }
  // --format is offered only where the command has it: history export writes JSON alone.
  write("st.json", seven_statement());
  ASSERT_EQ(run("history add st.json --db h.sqlite --serial S1 --date 2026-01-01").code, 0);
  const Result exported = run("history export S1 --db h.sqlite -o b.csv");
  expect_bad_input(exported, {"-o: 'b.csv' names a CSV file, and -o writes JSON; accepted: FILE.json"});
  EXPECT_EQ(exported.err.find("--format"), std::string::npos) << exported.err;
  // A name that says the format written, or none, is taken.
  EXPECT_EQ(run("budget -o b.txt").code, 0);
  EXPECT_EQ(run("budget --format json -o b.JSON").code, 0);
  EXPECT_EQ(run("budget --format csv -o budget").code, 0);
  // --statement-out's extension sets its format, in any case as every other name (S.JSON was refused).
  ASSERT_EQ(run("reduce " + quote(kLab) + " --logs L --statement --statement-trials 0 --statement-out S.JSON -o r.txt")
                .code,
            0);
  EXPECT_TRUE(read(dir_ / "S.JSON").starts_with("{")) << read(dir_ / "S.JSON").substr(0, 80);
}

// An empty file given for a configuration or a truth file was read as a configuration missing [site] (the
// message said to add it), or as a machine without errors (simulated with exit 0); a truth file given for a
// configuration likewise.
TEST_F(Cli, AnEmptyOrTruthFileGivenForAConfigurationIsSaidToBeOne) {
  write("empty.toml", "");
  expect_bad_input(run("budget empty.toml"),
                   {"empty.toml:1: the file holds no TOML table or key (it is empty); accepted: a configuration "
                    "file ([site], [centrifuge], [instrument], [plan], …; docs/config.md), e.g. examples/lab.toml"});
  expect_bad_input(run("budget " + quote(kLabTruth)),
                   {"lab_truth.toml:1: the file holds only [errors], as a truth file does", "not a configuration"});
  expect_bad_input(run("simulate " + quote(kLab) + " --truth /dev/null -o /dev/null"),
                   {"/dev/null:1: a truth file without an [errors] table (it is empty); accepted: [errors] with the "
                    "values the simulated machine has"});
  write("perfect.toml", "[errors]\n");
  EXPECT_EQ(run("simulate " + quote(kLab) + " --truth perfect.toml -o out.txt").code, 0);
}

// `identify --fix K9=1` on an observations file replaced the file's fixed K1 = 505.2097 deg/s/g, so the fit took
// K1's share into K0 (0.98 deg/s instead of 0.062) with exit 0; one column given two roles was fitted against
// itself.
TEST_F(Cli, IdentifyRefusesADroppedFixedTermAndAColumnInTwoRoles) {
  ASSERT_EQ(run("simulate " + quote(kLab) + " --observations-out obs.csv -o /dev/null").code, 0);
  expect_bad_input(run("identify obs.csv --fix K9=1"),
                   {"--fix: 'K9=1' replaces the fixed terms of obs.csv, and its K1 = 505.2097 deg/s/g would be left "
                    "out of the model; accepted: --fix naming K1 too (e.g. K1=505.2097), or K1 in --terms to fit "
                    "it"});
  const Result both = run("identify obs.csv --fix K1=505.2097,K9=0 --format json");
  ASSERT_EQ(both.code, 0) << both.err;
  const Result plain = run("identify obs.csv --format json");
  ASSERT_EQ(plain.code, 0) << plain.err;
  // K9 fixed at 0 changes nothing: the same coefficients as the file's own fixed terms give.
  const auto k0 = [](const std::string& json) {
    const std::size_t at = json.find("\"K0\"");
    return json.substr(at, json.find('}', at) - at);
  };
  EXPECT_EQ(k0(both.out), k0(plain.out));
  expect_bad_input(run("identify obs.csv --output-column a_i --input-column a_i"),
                   {"--output-column: a_i is also the --input-column; accepted: another column of the file for "
                    "each role"});
  expect_bad_input(run("identify obs.csv --weight-column output"),
                   {"--weight-column: output is also the --output-column"});
}

// Messages that said what was wrong but not what is accepted: a number that is not finite in a quantity, a
// target that is not positive, several targets in one, trials below the adaptive procedure's stage.
TEST_F(Cli, NumbersAndTargetsSayWhatIsAccepted) {
  expect_bad_input(run("force --time nan"), {"--time: 'nan': 'nan' is not a finite number; accepted: a finite "
                                             "number and its unit, e.g. '1 s'"});
  expect_bad_input(run("force --time 1e400"), {"'1e400' is out of range of double; accepted: a finite number"});
  expect_bad_input(run("allocate --target K3=-1"),
                   {"--target: K3: the target must be a positive expanded uncertainty, got '-1'; accepted: a "
                    "positive finite number, e.g. K3=1e-6 (in deg/s/g^3)"});
  expect_bad_input(run("allocate --target K3=1e-3,K2=1e-5"),
                   {"--target: 'K3=1e-3,K2=1e-5' holds more than one target; accepted: one target each"});
  expect_bad_input(run("montecarlo --digits 2 --trials 1000"),
                   {"--trials: 1000 is, with --digits 2, the size of each stage, which is at least 10000; "
                    "accepted: 10000 or more, or --trials left out (stages of 10000)"});
}

// A stated coverage factor of 1e308 gave U = 1.8e306 deg/s with exit 0: beyond 10 it is no contract's k.
TEST_F(Cli, ACoverageFactorBeyondTenIsRefused) {
  expect_bad_input(run("budget --coverage-factor 1e308"),
                   {"--coverage-factor: 1e+308 is out of range; accepted: 1 to 10, e.g. 2 (U = k u)"});
  expect_bad_input(run("budget --coverage-factor 10.5"), {"--coverage-factor: 10.5 is out of range"});
  EXPECT_EQ(run("budget --coverage-factor 10 -o b.txt").code, 0);
}

// A calibration statement (JSON) given to identify for a table was refused at its line 2 as CSV ("text after a
// closing quote; accepted: a comma"): it is said to be JSON.
TEST_F(Cli, AJsonFileGivenForATableIsSaidToBeOne) {
  write("st.json", seven_statement());
  expect_bad_input(run("identify st.json"),
                   {"st.json:1:1: the header, '{\"coverage_probability\": 0.95', opens a JSON document (a statement or "
                    "a result of ccal?), not a table's header; accepted: a CSV table whose header names its columns"});
  write("pretty.json", "{\n  \"a\": 1\n}\n");
  expect_bad_input(run("identify pretty.json"), {"pretty.json:1:1: the header, '{', opens a JSON document"});
}

// The lab's configuration with one line's text replaced (unique name: unity builds join the test files).
std::string seven_lab_with(const std::string& old_text, const std::string& new_text) {
  std::string text = read(kLab);
  const std::size_t at = text.find(old_text);
  EXPECT_NE(at, std::string::npos) << old_text;
  return at == std::string::npos ? text : text.replace(at, old_text.size(), new_text);
}

// A value that must be positive said "must be positive, got -2.5 m; the arm radius R0, e.g. ..." and a file in
// UTF-16 "Encountered invalid utf-8 sequence", neither with what is accepted.
TEST_F(Cli, ConfigurationValuesAndEncodingsSayWhatIsAccepted) {
  write("r.toml", seven_lab_with("radius = \"2.5 m\"", "radius = \"-2.5 m\""));
  expect_bad_input(run("budget r.toml"), {"centrifuge.radius: must be positive, got -2.5 m; accepted: a positive "
                                          "value, "});
  write("t.toml", seven_lab_with("dthy1t = \"1e-5 rad\"", "dthy1t = \"0 rad\""));
  expect_bad_input(run("budget t.toml"),
                   {"tolerances.dthy1t: must be positive, got 0; accepted: a positive bound, e.g."});
  write("d.toml", seven_lab_with("duration = \"450 s\"", "duration = \"0 s\""));
  expect_bad_input(run("budget d.toml"), {"plan.duration: must be positive, got 0 s; accepted: a positive run "
                                          "duration such as \"450 s\""});
  write("u16.toml", std::string("\xff\xfe[\0s\0i\0t\0e\0]\0\n\0", 16));
  expect_bad_input(run("budget u16.toml"), {"u16.toml:1:1: TOML syntax error: Encountered invalid utf-8 sequence; "
                                            "accepted: a TOML text file in UTF-8 (a binary file, or text in UTF-16 "
                                            "or Latin-1, is not one"});
}

// An imported calibration dated after today was named as the file's "serial" with two "accepted:" parts, and an
// export without calibrations made an empty store.
TEST_F(Cli, AnImportDatedAfterTodayOrWithoutCalibrationsIsRefused) {
  write("st.json", seven_statement());
  ASSERT_EQ(run("history add st.json --db h.sqlite --serial S1 --date 2026-01-01").code, 0);
  ASSERT_EQ(run("history export S1 --db h.sqlite -o e.json").code, 0);
  auto exported = nlohmann::json::parse(read(dir_ / "e.json"));
  exported["calibrations"][0]["date"] = "9999-12-31";
  write("future.json", exported.dump());
  const Result future = run("history import future.json --db new.sqlite");
  expect_bad_input(future, {"future.json: \"calibrations[0].date\" 9999-12-31 is after today ("});
  EXPECT_EQ(future.err.find("accepted"), future.err.rfind("accepted")) << future.err;  // one accepted part
  exported["calibrations"] = nlohmann::json::array();
  write("none.json", exported.dump());
  expect_bad_input(run("history import none.json --db new.sqlite"),
                   {"none.json: not an exported calibration history: no calibration in its \"calibrations\""});
  EXPECT_FALSE(fs::exists(dir_ / "new.sqlite"));
}

}  // namespace
