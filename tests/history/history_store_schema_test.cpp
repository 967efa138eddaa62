// The history store's schema 2 (history/history_store.hpp): what a calibration shares kept with it and read back,
// a schema-1 store migrated forward with its records as they were (nothing known to be shared), a certificate
// that replaces another superseding it in the same transaction, a unit change and a coverage probability of 2
// refused.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/history/history_store.hpp"

namespace ccal {
namespace {

namespace fs = std::filesystem;

class HistorySchemaTwo : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() /
              fmt::format("ccal_history2_{}_{}", ::getpid(),
                          ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override { fs::remove_all(folder_); }
  std::string path(const std::string& name) const { return (folder_ / name).string(); }
  fs::path folder_;
};

// The schema of version 1, as the first ccal with a history wrote it.
constexpr const char* kSchemaOne = R"sql(
CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE calibration(
  id INTEGER PRIMARY KEY,
  serial TEXT NOT NULL,
  date TEXT NOT NULL,
  instrument TEXT NOT NULL,
  ccal_version TEXT NOT NULL,
  config TEXT NOT NULL,
  statement_sha256 TEXT NOT NULL UNIQUE,
  added_at TEXT NOT NULL,
  statement TEXT NOT NULL);
CREATE INDEX calibration_by_serial ON calibration(serial, date);
CREATE TABLE coefficient(
  calibration INTEGER NOT NULL REFERENCES calibration(id),
  name TEXT NOT NULL,
  unit TEXT NOT NULL,
  value REAL NOT NULL,
  expanded REAL NOT NULL,
  coverage_factor REAL NOT NULL,
  coverage_probability REAL NOT NULL,
  effective_dof REAL,
  PRIMARY KEY(calibration, name));
CREATE TABLE supersession(
  calibration INTEGER PRIMARY KEY REFERENCES calibration(id),
  by INTEGER REFERENCES calibration(id),
  reason TEXT NOT NULL,
  at TEXT NOT NULL);
CREATE TRIGGER calibration_kept BEFORE UPDATE ON calibration
  BEGIN SELECT RAISE(ABORT, 'a recorded calibration is never changed'); END;
CREATE TRIGGER calibration_not_deleted BEFORE DELETE ON calibration
  BEGIN SELECT RAISE(ABORT, 'a recorded calibration is never deleted'); END;
CREATE TRIGGER supersession_kept BEFORE UPDATE ON supersession
  BEGIN SELECT RAISE(ABORT, 'a supersession is never changed'); END;
CREATE TRIGGER supersession_not_deleted BEFORE DELETE ON supersession
  BEGIN SELECT RAISE(ABORT, 'a supersession is never deleted'); END;
CREATE TRIGGER coefficient_kept BEFORE UPDATE ON coefficient
  BEGIN SELECT RAISE(ABORT, 'a recorded coefficient is never changed'); END;
CREATE TRIGGER coefficient_not_deleted BEFORE DELETE ON coefficient
  BEGIN SELECT RAISE(ABORT, 'a recorded coefficient is never deleted'); END;
)sql";

// A statement of schema 2's keys: K0 and K2, two inputs charged at their tolerance (a in group "arm") and one
// measured, with a certificate of the given number and replaces ("": none).
std::string statement_two(double k2, const std::string& number = "", const std::string& replaces = "",
                          const std::string& unit = "deg/s", double p = 0.95) {
  return fmt::format(
      R"({{"budget_config": "lab.toml", "config_sha256": "c1", "setup_sha256": "machine-1",
      "certificate": {{"serial_number": "SN 5", "date_of_calibration": "2026-01-01", "number": "{}",
                       "replaces": "{}"}},
      "coverage_probability": {}, "coefficients": {{
      "K0": {{"unit": "{}", "corrected_estimate": 0.06, "expanded_uncertainty": 0.02, "coverage_factor": 2}},
      "K2": {{"unit": "deg/s/g^2", "corrected_estimate": {}, "expanded_uncertainty": 1e-4, "coverage_factor": 2}}}},
      "inputs": [
        {{"id": "a", "u_si": 1, "u": 1, "unit": "um", "measured": false, "basis": "", "effect": {{"K0": 0.004, "K2": 2e-5}}, "group": "arm"}},
        {{"id": "b", "u_si": 1, "u": 1, "unit": "um", "measured": false, "basis": "", "effect": {{"K0": -0.002, "K2": 1e-5}}, "group": ""}},
        {{"id": "domega", "u_si": 1, "u": 1, "unit": "ppm", "measured": true, "basis": "", "effect": {{"K0": 0.001}}, "group": ""}}],
      "input_correlations": [["a", "b", 0.25]],
      "covariance": {{"order": ["K0", "K2"], "type_b": [[2.1e-5, 1e-7], [1e-7, 5e-10]]}}}})",
      number, replaces, p, unit, k2);
}

TEST_F(HistorySchemaTwo, WhatACalibrationSharesIsKeptAndReadBack) {
  HistoryStore store = HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create);
  EXPECT_EQ(store.schema(), 2);
  store.add(history_entry(statement_two(0.02, "C-1"), "s.json", "", ""));
  const std::vector<HistoryRecord> r = store.records("SN 5");
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].certificate_number, "C-1");
  ASSERT_TRUE(r[0].shared.has_value());
  const SharedPart& s = *r[0].shared;
  EXPECT_EQ(s.setup_sha256, "machine-1");
  ASSERT_EQ(s.inputs.size(), 3u);
  EXPECT_EQ(s.inputs[0].group, "arm");
  EXPECT_EQ(s.inputs[1].effect.at("K0"), -0.002);
  EXPECT_TRUE(s.inputs[2].measured);
  ASSERT_EQ(s.correlations.size(), 1u);
  EXPECT_EQ(s.correlations[0].r, 0.25);
  EXPECT_EQ(s.order, (std::vector<std::string>{"K0", "K2"}));
  EXPECT_EQ(s.covariance_b(0, 1), 1e-7);
  // Its shared part with itself is its u_B² of the inputs charged at their tolerance: 0.004² + 0.002² −
  // 2·0.25·0.004·0.002 = 1.6e-5 (domega measured, not shared).
  EXPECT_NEAR(shared_covariance(r[0].shared, r[0].shared, "K0"), 1.6e-5, 1e-20);
  // A statement without setup_sha256 (an older ccal's): nothing known to be shared.
  std::string old = statement_two(0.021, "C-2");
  const std::string key = R"("setup_sha256": "machine-1",)";
  old.erase(old.find(key), key.size());
  EXPECT_FALSE(history_entry(old, "o.json", "", "").shared.has_value());
}

TEST_F(HistorySchemaTwo, ASchemaOneStoreIsMigratedWithItsRecordsAsTheyWere) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path("old.sqlite").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, kSchemaOne, nullptr, nullptr, nullptr), SQLITE_OK);
  ASSERT_EQ(
      sqlite3_exec(
          db,
          "INSERT INTO meta VALUES ('application', 'ccal calibration history'), ('schema_version', '1');"
          "INSERT INTO calibration VALUES (1, 'SN 5', '2024-01-01', 'PIGA', '0.9', 'lab.toml', 'abc', "
          "'2024-01-02T00:00:00Z', '{}');"
          "INSERT INTO coefficient VALUES (1, 'K0', 'deg/s', 0.05, 0.02, 2, 0.95, NULL);",
          nullptr, nullptr, nullptr),
      SQLITE_OK);
  sqlite3_close(db);
  {  // Read-only: read as it is, not migrated.
    const HistoryStore store = HistoryStore::open(path("old.sqlite"), HistoryStore::Access::read);
    EXPECT_EQ(store.schema(), 1);
    const std::vector<HistoryRecord> r = store.records("SN 5");
    ASSERT_EQ(r.size(), 1u);
    EXPECT_FALSE(r[0].shared.has_value());
  }
  HistoryStore store = HistoryStore::open(path("old.sqlite"), HistoryStore::Access::write);
  EXPECT_EQ(store.schema(), 2);
  store.add(history_entry(statement_two(0.02, "C-1"), "s.json", "", "2025-01-01"));
  const std::vector<HistoryRecord> r = store.records("SN 5");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].statement_sha256, "abc");  // the old record as it was
  EXPECT_EQ(r[0].coefficients[0].value, 0.05);
  EXPECT_FALSE(r[0].shared.has_value());  // nothing known to be shared
  EXPECT_TRUE(r[1].shared.has_value());
  EXPECT_EQ(shared_covariance(r[0].shared, r[1].shared, "K0"), 0.0);
  // The file now says schema 2, and its records are still immutable.
  ASSERT_EQ(sqlite3_open(path("old.sqlite").c_str(), &db), SQLITE_OK);
  EXPECT_NE(
      sqlite3_exec(db, "UPDATE calibration SET date = '2020-01-01' WHERE id = 1", nullptr, nullptr, nullptr),
      SQLITE_OK);
  sqlite3_stmt* version = nullptr;
  sqlite3_prepare_v2(db, "SELECT value FROM meta WHERE key = 'schema_version'", -1, &version, nullptr);
  ASSERT_EQ(sqlite3_step(version), SQLITE_ROW);
  EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(version, 0)), "2");
  sqlite3_finalize(version);
  sqlite3_close(db);
}

TEST_F(HistorySchemaTwo, ACertificateThatReplacesAnotherSupersedesIt) {
  HistoryStore store = HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create);
  const std::int64_t first = store.add(history_entry(statement_two(0.02, "C-1"), "s.json", "", ""));
  const std::int64_t second =
      store.add(history_entry(statement_two(0.0201, "C-1/2", "C-1"), "r.json", "", ""));
  std::vector<HistoryRecord> r = store.records("SN 5");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].superseded_by, second);
  EXPECT_EQ(r[0].superseded_reason, "replaced by certificate C-1/2");
  EXPECT_FALSE(r[1].superseded_by.has_value());
  (void)first;
  // Replacing a number no record of the serial has in force: refused, nothing written.
  const auto refused = [&](const std::string& text, const std::string& says) {
    try {
      store.add(history_entry(text, "x.json", "", ""));
      ADD_FAILURE() << "not refused: " << says;
    } catch (const InputError& x) {
      EXPECT_NE(std::string(x.what()).find(says), std::string::npos) << x.what();
    }
    EXPECT_EQ(store.records("SN 5").size(), 2u);
  };
  refused(statement_two(0.0202, "C-3", "C-9"),
          "replaces certificate 'C-9', which names no calibration of 'SN 5'");
  refused(statement_two(0.0202, "C-3", "C-1"),
          "replaces certificate 'C-1', whose calibration 1 is already superseded");
  // A coefficient in another unit than the serial's records: refused at add, so that show never breaks.
  refused(statement_two(0.0203, "C-4", "", "rad/s"),
          "K0 of 'SN 5' is in 'rad/s' in this statement but in 'deg/s'");
}

TEST_F(HistorySchemaTwo, ACoverageProbabilityOutsideZeroToOneIsRefused) {
  try {
    history_entry(statement_two(0.02, "C-1", "", "deg/s", 2), "p.json", "", "");
    FAIL() << "not refused";
  } catch (const InputError& x) {
    EXPECT_NE(
        std::string(x.what()).find("p.json: not a calibration statement: coverage_probability 2 is not a "
                                   "probability in (0, 1)"),
        std::string::npos)
        << x.what();
  }
}

// UPDATE and DELETE refused on every table of the store at `file` (raw SQL, as a hand edit would do it), each
// table holding a row so that its triggers fire; the tables are those the file has, which must be the four.
void expect_every_table_kept(const std::string& file) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  std::vector<std::string> tables;
  sqlite3_stmt* list = nullptr;
  sqlite3_prepare_v2(db, "SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name", -1, &list, nullptr);
  while (sqlite3_step(list) == SQLITE_ROW) tables.emplace_back(reinterpret_cast<const char*>(sqlite3_column_text(list, 0)));
  sqlite3_finalize(list);
  EXPECT_EQ(tables, (std::vector<std::string>{"calibration", "coefficient", "meta", "supersession"}));
  const auto rows = [&](const std::string& table) {
    sqlite3_stmt* count = nullptr;
    sqlite3_prepare_v2(db, ("SELECT count(*) FROM " + table).c_str(), -1, &count, nullptr);
    sqlite3_step(count);
    const std::int64_t n = sqlite3_column_int64(count, 0);
    sqlite3_finalize(count);
    return n;
  };
  for (const std::string& table : tables) {
    const std::int64_t before = rows(table);
    ASSERT_GT(before, 0) << table;
    for (const std::string& sql : {"UPDATE " + table + " SET rowid = rowid", "DELETE FROM " + table}) {
      char* message = nullptr;
      EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &message), SQLITE_CONSTRAINT) << sql;
      EXPECT_NE(std::string(message ? message : "").find("never"), std::string::npos) << sql;
      sqlite3_free(message);
    }
    EXPECT_EQ(rows(table), before) << table;
  }
  sqlite3_close(db);
}

TEST_F(HistorySchemaTwo, UpdateAndDeleteAreRefusedOnEveryTable) {
  {  // A store made by this version, with a supersession.
    HistoryStore store = HistoryStore::open(path("h.sqlite"), HistoryStore::Access::create);
    store.add(history_entry(statement_two(0.02, "C-1"), "s.json", "", ""));
    store.add(history_entry(statement_two(0.0201, "C-1/2", "C-1"), "r.json", "", ""));
  }
  expect_every_table_kept(path("h.sqlite"));
  // A store of schema 1 (the last schema before this one) with a superseded record, then written to by this
  // version (migrated): every table kept, meta too, which schema 1 did not keep.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path("old.sqlite").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, kSchemaOne, nullptr, nullptr, nullptr), SQLITE_OK);
  ASSERT_EQ(
      sqlite3_exec(
          db,
          "INSERT INTO meta VALUES ('application', 'ccal calibration history'), ('schema_version', '1');"
          "INSERT INTO calibration VALUES (1, 'SN 5', '2024-01-01', 'PIGA', '0.9', 'lab.toml', 'abc', "
          "'2024-01-02T00:00:00Z', '{}');"
          "INSERT INTO coefficient VALUES (1, 'K0', 'deg/s', 0.05, 0.02, 2, 0.95, NULL);"
          "INSERT INTO supersession VALUES (1, NULL, 'withdrawn', '2024-02-01T00:00:00Z');",
          nullptr, nullptr, nullptr),
      SQLITE_OK);
  sqlite3_close(db);
  {
    HistoryStore store = HistoryStore::open(path("old.sqlite"), HistoryStore::Access::write);
    store.add(history_entry(statement_two(0.02, "C-1"), "s.json", "", "2025-01-01"));
  }
  expect_every_table_kept(path("old.sqlite"));
}

}  // namespace
}  // namespace ccal
