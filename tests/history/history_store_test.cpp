// The calibration history's store (history/history_store.hpp): statements read from their JSON, records added and
// read back, a duplicate refused, records immutable; two writers at once lose nothing; a missing, damaged,
// foreign or newer-schema file refused and left byte for byte as it was.
#include "ccal/history/history_store.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "ccal/core/errors.hpp"

namespace ccal {
namespace {

namespace fs = std::filesystem;

class History : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              fmt::format("ccal_history_{}_{}", ::getpid(),
                          ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  std::string path(const std::string& name) const { return (folder_ / name).string(); }
  fs::path folder_;
};

// A statement as `ccal reduce --statement-out` writes it (the keys history_entry reads), K2 = value.
std::string stored_statement(double k2, double u2 = 1e-4, const std::string& certificate = "") {
  return fmt::format(
      R"({{"budget_config": "lab.toml", "coverage_probability": 0.95, {}"coefficients": {{
      "K0": {{"unit": "deg/s", "corrected_estimate": 0.06, "expanded_uncertainty": 0.036,
              "coverage_factor": 1.96, "effective_dof": 4112.7}},
      "K2": {{"unit": "deg/s/g^2", "corrected_estimate": {}, "expanded_uncertainty": {},
              "coverage_factor": 2.0, "effective_dof": null}}}}}})",
      certificate, k2, u2);
}

std::string bytes_of(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST_F(History, AStatementIsRecordedAndReadBack) {
  const HistoryEntry e = history_entry(stored_statement(0.02), "s.json", "SN 0815", "2025-11-30");
  ASSERT_EQ(e.coefficients.size(), 2u);
  EXPECT_EQ(e.coefficients[1].name, "K2");
  EXPECT_EQ(e.coefficients[1].value, 0.02);
  EXPECT_TRUE(std::isinf(e.coefficients[1].effective_dof));
  EXPECT_EQ(e.config, "lab.toml");
  HistoryStore store =
      HistoryStore::open(path("sub/h.sqlite"), HistoryStore::Access::create);  // the folder is made
  const std::int64_t first = store.add(e);
  store.add(history_entry(stored_statement(0.021), "t.json", "SN 0815", "2024-11-30"));
  store.add(history_entry(stored_statement(0.5), "u.json", "SN 9", "2024-01-01"));
  const std::vector<HistoryRecord> r = store.records("SN 0815");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].date, "2024-11-30");  // by date
  EXPECT_EQ(r[1].id, first);
  EXPECT_EQ(r[1].coefficients[1].value, 0.02);
  EXPECT_EQ(r[1].coefficients[1].expanded, 1e-4);
  EXPECT_EQ(r[1].coefficients[1].coverage_factor, 2.0);
  EXPECT_EQ(r[1].coefficients[0].coverage_probability, 0.95);
  EXPECT_TRUE(std::isinf(r[1].coefficients[1].effective_dof));
  EXPECT_EQ(r[1].coefficients[0].effective_dof, 4112.7);
  EXPECT_EQ(store.serials(), (std::vector<std::string>{"SN 0815", "SN 9"}));
  // The same statement twice: refused, naming the record; nothing added.
  try {
    store.add(e);
    FAIL() << "not refused";
  } catch (const InputError& x) {
    EXPECT_NE(std::string(x.what()).find("already recorded, as calibration 1 of SN 0815 on 2025-11-30"),
              std::string::npos)
        << x.what();
  }
  EXPECT_EQ(store.records("SN 0815").size(), 2u);
}

TEST_F(History, SerialAndDateComeFromTheCertificateOrAreAskedFor) {
  const std::string cert =
      R"("certificate": {"serial_number": "SN 7", "date_of_calibration": "2026-11-30", "instrument": "PIGA"}, )";
  const HistoryEntry e =
      history_entry(R"({"statement": )" + stored_statement(0.02, 1e-4, cert) + "}", "r.json", "", "");
  EXPECT_EQ(e.serial, "SN 7");
  EXPECT_EQ(e.date, "2026-11-30");
  EXPECT_EQ(e.instrument, "PIGA");
  EXPECT_EQ(history_entry(stored_statement(0.02, 1e-4, cert), "r.json", "SN 8", "").serial, "SN 8");
  const auto refused = [](const std::string& text, const std::string& serial, const std::string& date,
                          const std::string& says) {
    try {
      history_entry(text, "s.json", serial, date);
      ADD_FAILURE() << "not refused: " << says;
    } catch (const InputError& x) {
      EXPECT_NE(std::string(x.what()).find(says), std::string::npos) << x.what();
    }
  };
  // Options of the call (OptionError of the field, which each front end names with its own flag).
  refused(stored_statement(0.02), "", "2026-01-01",
          "serial: s.json names no serial number ([certificate] serial_number); accepted: the instrument's "
          "serial number");
  refused(stored_statement(0.02), "SN 1", "", "date: s.json names no date of calibration");
  refused(stored_statement(0.02), "SN 1", "2026-13-01", "date of calibration '2026-13-01' is not a date");
  refused("{", "SN 1", "2026-01-01", "s.json: not JSON");
  // The statement's CSV form (`--statement-out FILE.csv`) is named as such: history keeps the JSON form.
  refused(
      "coefficient,unit,corrected_estimate,expanded_uncertainty\nK0,deg/s,1,2\n", "SN 1", "2026-01-01",
      "s.json: the statement's CSV form; history keeps the statement's JSON form; accepted: the statement "
      "as JSON");
  // A serial number is looked up by its exact text, so one that is blank or holds a control character could
  // not be typed again or told apart: refused, given or from the certificate, with the text escaped.
  refused(
      stored_statement(0.02), "   ", "2026-01-01",
      "serial: '   ' is blank; accepted: the instrument's serial number, printable characters and not blank");
  refused(stored_statement(0.02), "a\nb", "2026-01-01", "serial: 'a\\nb' holds a control character");
  refused(stored_statement(0.02), "SN\t1", "2026-01-01", "serial: 'SN\\t1' holds a control character");
  refused(stored_statement(0.02, 1e-4,
                           R"("certificate": {"serial_number": " ", "date_of_calibration": "2026-11-30"}, )"),
          "", "", "s.json: serial number ([certificate] serial_number) ' ' is blank");
  refused(R"({"command": "budget"})", "SN 1", "2026-01-01",
          "not a calibration statement: no \"coefficients\"");
}

TEST_F(History, RecordsAreNeverChanged) {
  HistoryStore store = HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create);
  store.add(history_entry(stored_statement(0.02), "s.json", "SN 1", "2026-01-01"));
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path("h.sqlite").c_str(), &db), SQLITE_OK);
  EXPECT_NE(sqlite3_exec(db, "UPDATE coefficient SET value = 1", nullptr, nullptr, nullptr), SQLITE_OK);
  EXPECT_NE(sqlite3_exec(db, "DELETE FROM calibration", nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
  EXPECT_EQ(store.records("SN 1").at(0).coefficients.at(1).value, 0.02);
}

TEST_F(History, ARecordIsSupersededOnceWithAReason) {
  HistoryStore store = HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create);
  const std::int64_t a = store.add(history_entry(stored_statement(0.02), "a.json", "SN 1", "2026-01-01"));
  const std::int64_t b = store.add(history_entry(stored_statement(0.03), "b.json", "SN 1", "2026-01-02"));
  const std::int64_t other = store.add(history_entry(stored_statement(0.04), "c.json", "SN 2", "2026-01-03"));
  const auto refused = [&](std::int64_t id, std::optional<std::int64_t> by, const std::string& reason,
                           const std::string& says) {
    try {
      store.supersede(id, by, reason);
      ADD_FAILURE() << "not refused: " << says;
    } catch (const InputError& x) {
      EXPECT_NE(std::string(x.what()).find(says), std::string::npos) << x.what();
    }
  };
  refused(a, b, "", "reason: is needed to supersede calibration 1 of");
  refused(a, b, " \t ", "reason: ' \\t ' is blank; accepted: the reason calibration 1 of");  // as "" is
  refused(99, std::nullopt, "r", "no calibration 99 in the history store");
  refused(a, a, "r", "cannot supersede itself");
  refused(a, other, "r", "is of another serial number");
  store.supersede(a, b, "mounting screw loose");
  refused(a, std::nullopt, "again", "is already superseded (mounting screw loose)");
  // A superseded record replaces nothing: b by a would leave both superseded and the serial with no record in
  // force.
  refused(b, a, "r", "calibration 1 is itself superseded (mounting screw loose), so it replaces nothing");
  const std::vector<HistoryRecord> r = store.records("SN 1");
  EXPECT_EQ(r[0].superseded_by, b);
  EXPECT_EQ(r[0].superseded_reason, "mounting screw loose");
  EXPECT_TRUE(r[1].superseded_reason.empty());
  EXPECT_EQ(r[0].coefficients.at(1).value, 0.02);  // kept as it was
}

// add's before_commit runs inside the transaction (the store already shows the record to it) and its failure
// rolls the addition back: a command whose output cannot be written records nothing, so that the corrected
// command is not refused as "already recorded".
TEST_F(History, AFailureBeforeTheCommitRecordsNothing) {
  HistoryStore store = HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create);
  const HistoryEntry e = history_entry(stored_statement(0.02), "s.json", "SN 1", "2026-01-01");
  std::size_t seen = 0;
  EXPECT_THROW(store.add(e,
                         [&](std::int64_t) {
                           seen = store.records("SN 1").size();
                           throw InputError("-o: cannot write");
                         }),
               InputError);
  EXPECT_EQ(seen, 1u);
  EXPECT_TRUE(store.records("SN 1").empty());
  std::int64_t told = 0;
  const std::int64_t id = store.add(e, [&](std::int64_t given) { told = given; });
  EXPECT_EQ(told, id);
  EXPECT_EQ(store.records("SN 1").size(), 1u);
}

TEST_F(History, TwoWritersAtOnceLoseNothing) {
  const std::string file = path("h.sqlite");
  const auto writer = [&](int who) {
    HistoryStore store = HistoryStore::open(
        file, HistoryStore::Access::create);  // both may create it: one makes it, one finds it
    for (int i = 0; i < 100; ++i)
      store.add(
          history_entry(stored_statement(0.02 + 1e-6 * (100 * who + i)), "s.json", "SN 1", "2026-01-01"));
  };
  std::thread a(writer, 0), b(writer, 1);
  a.join();
  b.join();
  EXPECT_EQ(HistoryStore::open(file, HistoryStore::Access::read).records("SN 1").size(), 200u);
}

TEST_F(History, ALockedStoreIsRefusedAfterWaiting) {
  HistoryStore store = HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create);
  store.add(history_entry(stored_statement(0.02), "s.json", "SN 1", "2026-01-01"));
  sqlite3* other = nullptr;  // another process's connection, holding the store's write lock
  ASSERT_EQ(sqlite3_open(path("h.sqlite").c_str(), &other), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(other, "BEGIN EXCLUSIVE", nullptr, nullptr, nullptr), SQLITE_OK);
  try {
    HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create, 100)
        .add(history_entry(stored_statement(0.03), "t.json", "SN 1", "2026-01-02"));
    ADD_FAILURE() << "not refused";
  } catch (const InputError& x) {
    EXPECT_NE(std::string(x.what()).find("another process holds it for more than"), std::string::npos)
        << x.what();
  }
  sqlite3_exec(other, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(other);
  EXPECT_EQ(store.records("SN 1").size(), 1u);
}

TEST_F(History, ReadingWritesNothing) {
  {
    HistoryStore store = HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create);
    store.add(history_entry(stored_statement(0.02), "s.json", "SN 1", "2026-01-01"));
  }
  const std::string before = bytes_of(path("h.sqlite"));
  const auto modified = fs::last_write_time(path("h.sqlite"));
  const HistoryStore reader = HistoryStore::open(path("h.sqlite"), HistoryStore::Access::read);
  EXPECT_EQ(reader.records("SN 1").size(), 1u);
  EXPECT_EQ(bytes_of(path("h.sqlite")), before);
  EXPECT_EQ(fs::last_write_time(path("h.sqlite")), modified);
  EXPECT_FALSE(fs::exists(path("h.sqlite-journal")));
}

// The calibrations a store holds now (−1 while a writer holds it locked).
std::int64_t count_calibrations(const std::string& file) {
  sqlite3* db = nullptr;
  std::int64_t count = -1;
  if (sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) == SQLITE_OK) {
    sqlite3_stmt* query = nullptr;
    if (sqlite3_prepare_v2(db, "SELECT count(*) FROM calibration", -1, &query, nullptr) == SQLITE_OK &&
        sqlite3_step(query) == SQLITE_ROW)
      count = sqlite3_column_int64(query, 0);
    sqlite3_finalize(query);
  }
  sqlite3_close(db);
  return count;
}

TEST_F(History, AWriterKilledMidAddLeavesTheStoreWhole) {
  // A child process adds statements as fast as it can and is killed (SIGKILL) at a random moment; every
  // calibration left has all its coefficients, and the store passes SQLite's integrity check.
  HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create);
  for (int round = 0; round < 5; ++round) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      HistoryStore store = HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create);
      for (int i = 0;; ++i)
        store.add(history_entry(stored_statement(round + 1e-6 * i), "s.json", "SN 1", "2026-01-01"));
    }
    // Killed once it has written more than the rounds before (so that every round kills a writer at work,
    // however slow the build, e.g. under the sanitizers), then a little later, at a varying moment of an add.
    const std::int64_t start = count_calibrations(path("h.sqlite"));
    for (int wait = 0; wait < 3000 && count_calibrations(path("h.sqlite")) <= start; ++wait) ::usleep(10000);
    ::usleep(useconds_t(3000 + 7000 * round));
    ::kill(child, SIGKILL);
    int status = 0;
    ::waitpid(child, &status, 0);
    EXPECT_TRUE(WIFSIGNALED(status));
  }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path("h.sqlite").c_str(), &db), SQLITE_OK);
  sqlite3_stmt* check = nullptr;
  sqlite3_prepare_v2(db,
                     "SELECT (SELECT count(*) FROM calibration), (SELECT count(*) FROM coefficient), "
                     "(SELECT integrity_check FROM pragma_integrity_check)",
                     -1, &check, nullptr);
  ASSERT_EQ(sqlite3_step(check), SQLITE_ROW);
  const auto calibrations = sqlite3_column_int64(check, 0), coefficients = sqlite3_column_int64(check, 1);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(check, 2)), "ok");
  sqlite3_finalize(check);
  sqlite3_close(db);
  EXPECT_GT(calibrations, 0);
  EXPECT_EQ(coefficients, 2 * calibrations);  // two coefficients a statement, none half-written
  EXPECT_EQ(HistoryStore::open(path("h.sqlite"), HistoryStore::Access::read).records("SN 1").size(),
            std::size_t(calibrations));
}

TEST_F(History, BadFilesAreRefusedAndLeftAsTheyWere) {
  const auto refused = [&](const std::string& file, bool create, const std::string& says) {
    const bool existed = fs::exists(file);
    const std::string before = existed ? bytes_of(file) : "";
    try {
      HistoryStore::open(file, create ? HistoryStore::Access::create : HistoryStore::Access::read);
      ADD_FAILURE() << "not refused: " << file;
    } catch (const InputError& x) {
      EXPECT_NE(std::string(x.what()).find(says), std::string::npos) << x.what();
    }
    EXPECT_EQ(fs::exists(file), existed);
    if (existed) {
      EXPECT_EQ(bytes_of(file), before) << file;
    }
  };
  refused(path("missing.sqlite"), false, "no history store there; accepted:");
  // Not SQLite at all.
  std::ofstream(path("text.sqlite")) << "K2 = 0.02\n";
  refused(path("text.sqlite"), true, "not an SQLite file");
  // A store cut short (a copy interrupted): its first half.
  {
    HistoryStore store = HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create);
    for (int i = 0; i < 30; ++i)
      store.add(history_entry(stored_statement(0.02 + 1e-6 * i), "s.json", "SN 1", "2026-01-01"));
  }
  const std::string whole = bytes_of(path("h.sqlite"));
  std::ofstream(path("cut.sqlite"), std::ios::binary) << whole.substr(0, whole.size() / 2);
  refused(path("cut.sqlite"), true, "history store:");
  // Another application's SQLite file.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path("other.sqlite").c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "CREATE TABLE t(x)", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  refused(path("other.sqlite"), true, "an SQLite file that is not a ccal history store");
  // A store of a newer schema.
  ASSERT_EQ(sqlite3_open(path("h.sqlite").c_str(), &db), SQLITE_OK);
  // (The meta table is kept by a trigger, as the records are: a newer ccal's migration drops it first.)
  ASSERT_EQ(sqlite3_exec(db, "DROP TRIGGER meta_kept; UPDATE meta SET value = '3' WHERE key = 'schema_version'",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  refused(path("h.sqlite"), true,
          "history store of schema 3, written by a newer ccal; this ccal reads schema 2");
  // A folder.
  refused(folder_.string(), true, "not a file");
}

}  // namespace
}  // namespace ccal
