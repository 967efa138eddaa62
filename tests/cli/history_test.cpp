// `ccal history` through the program: three yearly calibrations of one instrument whose K2 drifts by a known
// amount (the lab example simulated with K2 = 0.02 + 0.0002 t deg/s/g², reduced with the statement, each
// recorded under the serial and date of its [certificate]) give back the drift within its stated uncertainty
// and E_n equal to a hand computation from the statements; two processes adding 100 statements each at once
// lose none; a damaged store is refused and left as it was.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_support.hpp"

namespace {

using namespace ccal::test;

const std::string kTruth = CCAL_SOURCE_DIR + "/examples/lab_truth.toml";
constexpr double kDrift = 2e-4;  // deg/s/g² per year

// The lab's configuration with the instrument's true K2 of year `year` and that year's date of calibration.
std::string lab_of_year(int year) {
  std::string text = read(kLab);
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  };
  replace("K2 = \"0.02 deg/s/g^2\"", "K2 = \"" + std::to_string(0.02 + kDrift * year) + " deg/s/g^2\"");
  replace("date_of_receipt = 2026-11-23", "date_of_receipt = " + std::to_string(2024 + year) + "-11-23");
  replace("date_of_calibration = 2026-11-30",
          "date_of_calibration = " + std::to_string(2024 + year) + "-11-30");
  replace("date_of_issue = 2026-12-03", "date_of_issue = " + std::to_string(2024 + year) + "-12-03");
  return text;
}

TEST_F(Cli, ThreeCalibrationsGiveTheDriftAndTheAgreement) {
  std::vector<nlohmann::json> statements;
  for (int year = 0; year < 3; ++year) {
    const std::string config = write("lab" + std::to_string(year) + ".toml", lab_of_year(year));
    const std::string logs = "logs" + std::to_string(year);
    ASSERT_EQ(
        run("simulate " + config + " --truth " + quote(kTruth) + " --logs-out " + logs + " -o /dev/null")
            .code,
        0);
    std::string args;
    for (const char* r : {"5g", "10g", "15g", "20g", "25g", "30g"})
      args += std::string(" --log ") + r + "=" + logs + "/" + r + ".csv";
    const std::string out = "statement" + std::to_string(year) + ".json";
    const Result reduced = run("reduce " + config + args +
                               " --statement --statement-trials 0 --statement-out " + out + " -o /dev/null");
    ASSERT_EQ(reduced.code, 0) << reduced.err;
    const Result added = run("history add " + out + " --db h.sqlite");
    ASSERT_EQ(added.code, 0) << added.err;
    EXPECT_NE(added.out.find("SN 0815 on " + std::to_string(2024 + year) + "-11-30"), std::string::npos)
        << added.out;
    statements.push_back(nlohmann::json::parse(read(dir_ / out)));
  }
  const Result shown = run("history show 'SN 0815' --db h.sqlite --at 2027-11-30 --format json");
  ASSERT_EQ(shown.code, 0) << shown.err;
  const auto j = nlohmann::json::parse(shown.out);
  ASSERT_EQ(j["calibrations"].size(), 3u);
  const auto& k2 = j["coefficients"]["K2"];
  // The drift: the true one within the slope's stated standard uncertainty.
  const double slope = k2["drift"]["slope_per_year"].get<double>(),
               u = k2["drift"]["std_slope"].get<double>();
  EXPECT_LT(std::abs(slope - kDrift), u) << slope << " ± " << u;
  EXPECT_GT(u, 0);
  // E_n of successive calibrations by hand from the statements: (x₂ − x₁)/√(U₁² + U₂² − 2 k₁ k₂ C), C the
  // covariance the two share (one set-up: the K2 of the instrument changed, not the machine; C itself is checked
  // against its sum over the inputs in tests/cli/history_shared_test.cpp); the store keeps the numbers bit for
  // bit, so they agree to round-off of the same expression. The shared Type B is most of U here: E_n is far
  // beyond what the independent form gives.
  EXPECT_EQ(j["calibrations"][0]["setup"], j["calibrations"][2]["setup"]);
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& a = statements[i]["coefficients"]["K2"];
    const auto& b = statements[i + 1]["coefficients"]["K2"];
    const double Ua = a["expanded_uncertainty"].get<double>(), Ub = b["expanded_uncertainty"].get<double>();
    const double ka = a["coverage_factor"].get<double>(), kb = b["coverage_factor"].get<double>();
    const double C = k2["normalised_errors"][i]["shared_covariance"].get<double>();
    EXPECT_GT(C, 0);
    const double difference = b["corrected_estimate"].get<double>() - a["corrected_estimate"].get<double>();
    const double en = difference / std::sqrt(Ua * Ua + Ub * Ub - 2 * ka * kb * C);
    EXPECT_NEAR(k2["normalised_errors"][i]["en"].get<double>(), en, 1e-12 * std::abs(en));
    EXPECT_GT(std::abs(en), 3 * std::abs(difference / std::hypot(Ua, Ub)));
  }
  // The prediction a year after the last.
  EXPECT_EQ(k2["prediction"]["date"], "2027-11-30");
  const Result text = run("history show 'SN 0815' --db h.sqlite");
  EXPECT_NE(text.out.find("drift:"), std::string::npos) << text.out;
  const Result csv = run("history show 'SN 0815' --db h.sqlite --format csv");
  EXPECT_EQ(std::count(csv.out.begin(), csv.out.end(), '\n'), 1 + 3 * 3) << csv.out;
}

TEST_F(Cli, ASupersededRecordIsKeptButLeftOutAndTheHistoryMoves) {
  for (int i = 0; i < 3; ++i) {
    write(fmt::format("s{}.json", i),
          fmt::format(R"({{"coverage_probability": 0.95, "coefficients": {{"K0": {{"unit": "deg/s",
              "corrected_estimate": {}, "expanded_uncertainty": 0.5, "coverage_factor": 2}}}}}})",
                      1 + i));
    ASSERT_EQ(
        run(fmt::format("history add s{}.json --db h.sqlite --serial S1 --date 202{}-06-01", i, 4 + i)).code,
        0);
  }
  const Result done = run("history supersede 2 --by 3 --reason 'fixture loose' --db h.sqlite");
  ASSERT_EQ(done.code, 0) << done.err;
  expect_bad_input(run("history supersede 2 --reason again --db h.sqlite"),
                   {"already superseded (fixture loose)"});
  expect_bad_input(
      run("history supersede 1 --db h.sqlite"),
      {"--reason: is needed to supersede calibration 1 of h.sqlite; accepted: the reason, as text"});
  const auto j = nlohmann::json::parse(run("history show S1 --db h.sqlite --format json").out);
  EXPECT_EQ(j["calibrations"][1]["superseded"]["reason"], "fixture loose");
  EXPECT_EQ(j["calibrations"][1]["superseded"]["by"], 3);
  EXPECT_EQ(j["coefficients"]["K0"]["dates"].size(), 2u);  // left out of E_n and the drift
  // (3 − 1)/√(0.5² + 0.5²) = 2.83: the two that remain disagree.
  EXPECT_NEAR(j["coefficients"]["K0"]["normalised_errors"][0]["en"].get<double>(), 2 / std::sqrt(0.5), 1e-15);
  EXPECT_TRUE(j["coefficients"]["K0"]["normalised_errors"][0]["disagree"].get<bool>());
  // Exported, imported elsewhere: the same show.
  ASSERT_EQ(run("history export S1 --db h.sqlite -o s1.json").code, 0);
  const Result imported = run("history import s1.json --db other.sqlite");
  ASSERT_EQ(imported.code, 0) << imported.err;
  EXPECT_NE(imported.out.find("3 calibrations added, 0 already there, 1 supersession recorded"),
            std::string::npos)
      << imported.out;
  auto moved = nlohmann::json::parse(run("history show S1 --db other.sqlite --format json").out);
  auto here = j;
  for (auto* doc : {&moved, &here}) {
    (*doc).erase("db");
    for (auto& c : (*doc)["calibrations"]) c.erase("added_at");
  }
  EXPECT_EQ(moved, here);
}

TEST_F(Cli, TwoProcessesAddingAtOnceLoseNothing) {
  // 2 × 100 different statements (K0 differs), added by two shell loops at once.
  for (int who = 0; who < 2; ++who)
    for (int i = 0; i < 100; ++i)
      write(
          std::to_string(who) + "_" + std::to_string(i) + ".json",
          R"({"coverage_probability": 0.95, "coefficients": {"K0": {"unit": "deg/s", "corrected_estimate": )" +
              std::to_string(who * 1000 + i) +
              R"(, "expanded_uncertainty": 0.1, "coverage_factor": 2, "effective_dof": null}}})");
  const std::string loop =
      "for f in {}_*.json; do " + quote(kProgram) +
      " history add $f --db h.sqlite --serial S1 --date 2026-01-01 >/dev/null || echo FAILED $f; done";
  std::string both;
  for (const char* who : {"0", "1"}) {
    std::string l = loop;
    l.replace(l.find("{}"), 2, who);
    both += "(" + l + ") & ";
  }
  ASSERT_EQ(std::system(("cd " + quote(dir_.string()) + " && { " + both + "wait; }").c_str()), 0);
  const Result shown = run("history show S1 --db h.sqlite --format json");
  ASSERT_EQ(shown.code, 0) << shown.err;
  EXPECT_EQ(nlohmann::json::parse(shown.out)["calibrations"].size(), 200u);
}

TEST_F(Cli, AStoreTheUserMayOnlyReadServesShowAndRefusesAdd) {
  // As root (which ignores permissions) the commands run as the user nobody (setpriv); else the file is made
  // read-only.
  write("s.json", R"({"coverage_probability": 0.95, "coefficients": {"K0": {"unit": "deg/s",
      "corrected_estimate": 1, "expanded_uncertainty": 0.1, "coverage_factor": 2}}})");
  write("t.json", R"({"coverage_probability": 0.95, "coefficients": {"K0": {"unit": "deg/s",
      "corrected_estimate": 2, "expanded_uncertainty": 0.1, "coverage_factor": 2}}})");
  ASSERT_EQ(run("history add s.json --db h.sqlite --serial S1 --date 2026-01-01").code, 0);
  std::string as_reader;
  if (::geteuid() == 0) {
    if (std::system("command -v setpriv >/dev/null") != 0)
      GTEST_SKIP() << "no setpriv to run as another user";
    as_reader = "setpriv --reuid=nobody --regid=nogroup --clear-groups ";
    if (std::system((as_reader + quote(kProgram) + " --version >/dev/null 2>&1").c_str()) != 0)
      GTEST_SKIP() << "the user nobody cannot run " << kProgram << " (a folder above it is private)";
    fs::permissions(dir_, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                              fs::perms::others_read | fs::perms::others_exec);
    fs::permissions(dir_ / "h.sqlite", fs::perms::owner_read | fs::perms::owner_write |
                                           fs::perms::group_read | fs::perms::others_read);
  } else {
    fs::permissions(dir_ / "h.sqlite",
                    fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  }
  const std::string before = read(dir_ / "h.sqlite");
  const auto as = [&](const std::string& args) {
    const fs::path out = dir_ / "out.txt", err = dir_ / "err.txt";
    const int status = std::system(("cd " + quote(dir_.string()) + " && " + as_reader + quote(kProgram) +
                                    " " + args + " >" + quote(out.string()) + " 2>" + quote(err.string()))
                                       .c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = read(out);
    r.err = read(err);
    return r;
  };
  const Result shown = as("history show S1 --db h.sqlite --format json");
  ASSERT_EQ(shown.code, 0) << shown.err;
  EXPECT_EQ(nlohmann::json::parse(shown.out)["calibrations"].size(), 1u);
  ASSERT_EQ(as("history export S1 --db h.sqlite").code, 0);
  expect_bad_input(
      as("history add t.json --db h.sqlite --serial S1 --date 2026-01-02"),
      {"h.sqlite: history store:", "readonly", "accepted: a file (and folder) this user may read and write"});
  EXPECT_EQ(read(dir_ / "h.sqlite"), before);
}

TEST_F(Cli, ADamagedStoreIsRefusedAndKept) {
  write("s.json", R"({"coverage_probability": 0.95, "coefficients": {"K0": {"unit": "deg/s",
      "corrected_estimate": 1, "expanded_uncertainty": 0.1, "coverage_factor": 2}}})");
  ASSERT_EQ(run("history add s.json --db h.sqlite --serial S1 --date 2026-01-01").code, 0);
  const std::string whole = read(dir_ / "h.sqlite");
  write("cut.sqlite", whole.substr(0, whole.size() / 2));
  expect_bad_input(run("history show S1 --db cut.sqlite"), {"cut.sqlite: history store:"});
  expect_bad_input(run("history add s.json --db cut.sqlite --serial S2 --date 2026-01-02"),
                   {"cut.sqlite: history store:"});
  EXPECT_EQ(read(dir_ / "cut.sqlite"), whole.substr(0, whole.size() / 2));
  expect_bad_input(run("history show S9 --db h.sqlite"), {"no calibration of 'S9'", "accepted: one of S1"});
  expect_bad_input(run("history show S1 --db h.sqlite --at 2026-02-30"), {"--at", "is not a date"});
  expect_bad_input(run("history add s.json --db h.sqlite --serial S1"),
                   {"--date: s.json names no date of calibration"});
  expect_bad_input(run("history add s.json --db h.sqlite --date 2026-01-01"),
                   {"--serial: s.json names no serial number"});
  expect_bad_input(run("history add s.json --db h.sqlite --serial S1 --date 01/02/2026"),
                   {"--date: 01/02/2026 is not a date; accepted: YYYY-MM-DD"});
  // import: a file that is no export; supersede: an unknown id; the report: a history without a serial
  // number, and a store that is not there.
  expect_bad_input(
      run("history import s.json --db h.sqlite"),
      {"s.json: not an exported calibration history", "accepted: a serial number's history as exported"});
  expect_bad_input(run("history supersede 42 --reason r --db h.sqlite"),
                   {"no calibration 42 in the history store; accepted: the id of a record in it"});
  expect_bad_input(run("report --history-db h.sqlite -o r.html"),
                   {"--history-db: h.sqlite needs the serial number whose history to show",
                    "[certificate] serial_number"});
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
  const std::string lab = write("lab.toml", read(kLab));
  expect_bad_input(run("report " + lab + " --history-db none.sqlite --trials 100 -o r.html"),
                   {"none.sqlite: no history store there"});
  EXPECT_FALSE(fs::exists(dir_ / "r.html"));
}

// A small statement, K0 = value, for the history commands (serial and date given on the command line).
std::string small_statement(int value) {
  return fmt::format(R"({{"coverage_probability": 0.95, "coefficients": {{"K0": {{"unit": "deg/s",
      "corrected_estimate": {}, "expanded_uncertainty": 0.5, "coverage_factor": 2}}}}}})",
                     value);
}

// The history store is an input of every command that reads it: an -o naming it (by --db, by the default
// path of $CCAL_HISTORY, or report's --history-db) is refused and the store kept byte for byte, also when add
// would make it.
TEST_F(Cli, TheHistoryStoreIsNeverReplacedByAnOutput) {
  write("s.json", small_statement(1));
  write("t.json", small_statement(2));
  ASSERT_EQ(run("history add s.json --db h.sqlite --serial 'SN 0815' --date 2026-01-01").code, 0);
  const std::string store = read(dir_ / "h.sqlite");
  const std::string input = "it is also an input of the command; accepted: a file the command does not read";
  expect_bad_input(run("history show 'SN 0815' --db h.sqlite -o h.sqlite"),
                   {"-o: cannot write 'h.sqlite'", input});
  expect_bad_input(run("history export 'SN 0815' --db h.sqlite -o ./h.sqlite"), {input});
  expect_bad_input(run("history add t.json --db h.sqlite --serial 'SN 0815' --date 2026-02-01 -o h.sqlite"),
                   {input});
  const std::string lab = write("lab.toml", read(kLab));
  expect_bad_input(run("report " + lab + " --trials 100 --history-db h.sqlite -o h.sqlite"), {input});
  ::setenv("CCAL_HISTORY", "h.sqlite", 1);  // the default store, resolved as the commands resolve it
  const Result by_default = run("history show 'SN 0815' -o h.sqlite");
  ::unsetenv("CCAL_HISTORY");
  expect_bad_input(by_default, {input});
  EXPECT_EQ(read(dir_ / "h.sqlite"), store);
  // A store add would make: not made, as the output is not written.
  expect_bad_input(run("history add t.json --db new.sqlite --serial S2 --date 2026-02-01 -o new.sqlite"),
                   {input});
  EXPECT_FALSE(fs::exists(dir_ / "new.sqlite"));
}

// add records the calibration only when its output is written too: an -o refused before the store is touched
// (a folder, the statement itself, a missing folder) or failing while written (/dev/full) leaves the store as
// it was, so that the corrected command is not refused as "already recorded".
TEST_F(Cli, AddRecordsNothingWhenItsOutputFails) {
  write("s.json", small_statement(1));
  write("t.json", small_statement(2));
  ASSERT_EQ(run("history add s.json --db h.sqlite --serial S1 --date 2026-01-01").code, 0);
  fs::create_directory(dir_ / "adir");
  const std::string add = "history add t.json --db h.sqlite --serial S1 --date 2026-02-01 -o ";
  expect_bad_input(run(add + "adir"), {"-o: cannot write 'adir': it is a folder"});
  expect_bad_input(run(add + "t.json"), {"-o: cannot write 't.json': it is also an input"});
  expect_bad_input(
      run(add + "nodir/x.txt"),
      {"-o: cannot write 'nodir/x.txt': its folder 'nodir' does not exist; accepted: a file in an "
       "existing folder"});
  if (fs::exists("/dev/full")) expect_bad_input(run(add + "/dev/full"), {"-o: cannot write '/dev/full'"});
  const auto count = [&] {
    return nlohmann::json::parse(run("history show S1 --db h.sqlite --format json").out)["calibrations"]
        .size();
  };
  EXPECT_EQ(count(), 1u);
  const Result corrected = run(add + "added.txt");
  ASSERT_EQ(corrected.code, 0) << corrected.err;
  EXPECT_NE(read(dir_ / "added.txt").find("Recorded calibration 2 of S1"), std::string::npos);
  EXPECT_EQ(count(), 2u);
}

// What history refuses, each saying what is wrong and what is accepted: a serial that is blank or holds a
// control character (looked up by its exact text, it could not be typed again); a blank reason (as an empty
// one); a --by record itself superseded (every record would end superseded); an import whose "by" names no
// calibration of the file (it was dropped); a folder or the statement's CSV form as STATEMENT.
TEST_F(Cli, HistoryRefusesWhatItCouldNotKeepOrFindAgain) {
  for (int i = 0; i < 3; ++i) write(fmt::format("s{}.json", i), small_statement(i));
  expect_bad_input(
      run("history add s0.json --db h.sqlite --serial '   ' --date 2026-01-01"),
      {"--serial: '   ' is blank; accepted: the instrument's serial number, printable characters"});
  expect_bad_input(run("history add s0.json --db h.sqlite --serial " + quote("a\nb") + " --date 2026-01-01"),
                   {"--serial: 'a\\nb' holds a control character"});
  EXPECT_FALSE(fs::exists(dir_ / "h.sqlite"));
  for (int i = 0; i < 3; ++i)
    ASSERT_EQ(
        run(fmt::format("history add s{}.json --db h.sqlite --serial S1 --date 202{}-01-01", i, 4 + i)).code,
        0);
  expect_bad_input(run("history supersede 1 --reason '   ' --db h.sqlite"), {"--reason: '   ' is blank"});
  ASSERT_EQ(run("history supersede 1 --by 2 --reason r --db h.sqlite").code, 0);
  expect_bad_input(
      run("history supersede 2 --by 1 --reason r --db h.sqlite"),
      {"calibration 1 is itself superseded (r)", "accepted: a record of S1 that is not superseded"});
  ASSERT_EQ(run("history export S1 --db h.sqlite -o e.json").code, 0);
  auto exported = nlohmann::json::parse(read(dir_ / "e.json"));
  exported["calibrations"][0]["superseded"]["by"] = 999;
  write("e999.json", exported.dump());
  expect_bad_input(run("history import e999.json --db other.sqlite"),
                   {"is superseded by 999, which names no calibration in the file"});
  fs::create_directory(dir_ / "adir");
  expect_bad_input(run("history add adir --db h.sqlite"),
                   {"adir: it is a folder; accepted: a calibration statement's JSON file"});
  write("st.csv", "coefficient,unit,corrected_estimate,expanded_uncertainty\nK0,deg/s,1,0.5\n");
  expect_bad_input(run("history add st.csv --db h.sqlite --serial S1 --date 2026-01-01"),
                   {"st.csv: the statement's CSV form", "accepted: the statement as JSON"});
  // The help names the JSON form, and what an empty --serial means.
  const Result help = run("history add --help");
  EXPECT_NE(help.out.find("The calibration statement's JSON file"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("also for an empty S"), std::string::npos) << help.out;
}

}  // namespace
