#include "ccal/history/history_store.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <sqlite3.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <string_view>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/core/sha256.hpp"
#include "history_shared_json.hpp"
#include "history_text.hpp"

namespace ccal {

namespace {

constexpr std::string_view kApplication = "ccal calibration history";

// Schema 2 (schema 1 without the calibration's last three columns). The triggers make every record immutable:
// a calibration is only ever superseded.
constexpr const char* kSchema = R"sql(
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
  statement TEXT NOT NULL,
  setup_sha256 TEXT,
  certificate_number TEXT,
  shared TEXT);
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

// The meta table (application, schema version) is kept as the records are: made on every opening for writing,
// after any migration (a future one drops these two first, as it updates schema_version), so that a store made
// by an older ccal gets them too.
constexpr const char* kMetaKept = R"sql(
CREATE TRIGGER IF NOT EXISTS meta_kept BEFORE UPDATE ON meta
  BEGIN SELECT RAISE(ABORT, 'the store''s meta data is never changed'); END;
CREATE TRIGGER IF NOT EXISTS meta_not_deleted BEFORE DELETE ON meta
  BEGIN SELECT RAISE(ABORT, 'the store''s meta data is never deleted'); END;
)sql";

// Schema 1 → 2: what a calibration shares, NULL (not known) in the records already there; a schema change,
// not an update, so the records' triggers stay silent and their rows as they were.
constexpr const char* kMigrationTo2 = R"sql(
ALTER TABLE calibration ADD COLUMN setup_sha256 TEXT;
ALTER TABLE calibration ADD COLUMN certificate_number TEXT;
ALTER TABLE calibration ADD COLUMN shared TEXT;
UPDATE meta SET value = '2' WHERE key = 'schema_version';
)sql";

// A prepared statement, finalised on scope exit.
class Statement {
 public:
  Statement(sqlite3* db, const std::string& path, const char* sql) : db_(db), path_(path) {
    if (sqlite3_prepare_v2(db, sql, -1, &s_, nullptr) != SQLITE_OK) fail("cannot read it");
  }
  ~Statement() { sqlite3_finalize(s_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  Statement& text(int i, const std::string& v) {
    sqlite3_bind_text(s_, i, v.c_str(), int(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Statement& number(int i, double v) {
    if (std::isfinite(v))
      sqlite3_bind_double(s_, i, v);
    else
      sqlite3_bind_null(s_, i);  // ν_eff = ∞
    return *this;
  }
  Statement& integer(int i, std::int64_t v) {
    sqlite3_bind_int64(s_, i, v);
    return *this;
  }
  // true while there is a row; throws on an error.
  bool step() {
    const int rc = sqlite3_step(s_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    fail("cannot use it");
    return false;
  }
  std::string column_text(int i) const {
    const auto* t = reinterpret_cast<const char*>(sqlite3_column_text(s_, i));
    return t ? std::string(t) : std::string();
  }
  double column_number(int i) const {
    return sqlite3_column_type(s_, i) == SQLITE_NULL ? std::numeric_limits<double>::infinity()
                                                     : sqlite3_column_double(s_, i);
  }
  std::int64_t column_integer(int i) const { return sqlite3_column_int64(s_, i); }
  bool column_null(int i) const { return sqlite3_column_type(s_, i) == SQLITE_NULL; }

  [[noreturn]] void fail(const char* what) const { throw_store_error(db_, path_, what); }
  [[noreturn]] static void throw_store_error(sqlite3* db, const std::string& path, const char* what);

 private:
  sqlite3* db_;
  const std::string& path_;
  sqlite3_stmt* s_ = nullptr;
};

// What SQLite said, in the words of a history store, with what would be accepted.
void Statement::throw_store_error(sqlite3* db, const std::string& path, const char* what) {
  const int code = db ? sqlite3_errcode(db) & 0xff : SQLITE_CANTOPEN;
  const std::string said = db ? sqlite3_errmsg(db) : "cannot open";
  std::string accepted;
  switch (code) {
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      accepted = fmt::format(
          "another process holds it for more than {} s; accepted: the same command once it "
          "has finished",
          kHistoryBusyMillis / 1000);
      break;
    case SQLITE_READONLY:
    case SQLITE_PERM:
    case SQLITE_CANTOPEN:
      accepted = "accepted: a file (and folder) this user may read and write";
      break;
    case SQLITE_CORRUPT:
    case SQLITE_NOTADB:
      accepted =
          "it is damaged or not an SQLite file; accepted: a ccal history store (restore it from a "
          "backup; nothing was written to it)";
      break;
    default:
      accepted = "accepted: a ccal history store";
  }
  throw InputError(fmt::format("{}: history store: {} ({}); {}", path, what, said, accepted));
}

void execute(sqlite3* db, const std::string& path, const char* sql, const char* what) {
  if (sqlite3_exec(db, sql, nullptr, nullptr, nullptr) != SQLITE_OK)
    Statement::throw_store_error(db, path, what);
}

std::string utc_now() {
  const auto now = std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now());
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}", now);
}

// The schema version of an opened file: 0 for an empty file, -1 for an SQLite file that is no history store.
int schema_version(sqlite3* db, const std::string& path) {
  Statement tables(db, path, "SELECT count(*) FROM sqlite_master");
  tables.step();
  if (tables.column_integer(0) == 0) return 0;
  Statement meta(db, path, "SELECT count(*) FROM sqlite_master WHERE type = 'table' AND name = 'meta'");
  meta.step();
  if (meta.column_integer(0) == 0) return -1;
  Statement app(db, path, "SELECT value FROM meta WHERE key = 'application'");
  if (!app.step() || app.column_text(0) != kApplication) return -1;
  Statement version(db, path, "SELECT value FROM meta WHERE key = 'schema_version'");
  if (!version.step()) return -1;
  return std::atoi(version.column_text(0).c_str());
}

// The store's file: there, or made (its folder too) when the access creates one; a file, not a folder.
void prepare_store_path(const std::string& path, bool create) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    if (!create)
      throw InputError(
          fmt::format("{}: no history store there; accepted: an existing store, or a first statement added, "
                      "which makes one",
                      path));
    const fs::path folder = fs::path(path).parent_path();
    if (!folder.empty()) fs::create_directories(folder, ec);
  } else if (!fs::is_regular_file(path, ec)) {
    throw InputError(fmt::format("{}: not a file; accepted: a ccal history store (a file)", path));
  }
}

// The store's schema, read within the caller's transaction: refused when the file is another SQLite file or
// of a newer schema; schema 1 migrated to 2 when writing; an empty file given the schema when creating.
int checked_schema(sqlite3* db, const std::string& path, bool create, bool writing) {
  const int version = schema_version(db, path);
  if (version < 0)
    throw InputError(
        fmt::format("{}: an SQLite file that is not a ccal history store; accepted: a ccal history "
                    "store, or a new file name",
                    path));
  if (version > kHistorySchemaVersion)
    throw InputError(
        fmt::format("{}: history store of schema {}, written by a newer ccal; this ccal reads "
                    "schema {} and older; accepted: the newer ccal",
                    path, version, kHistorySchemaVersion));
  int schema = version;
  if (version == 1 && writing) {
    execute(db, path, kMigrationTo2, "cannot migrate it to schema 2");
    schema = 2;
  }
  if (version == 0) {
    schema = kHistorySchemaVersion;
    std::error_code ec;  // SQLite reads a file shorter than its header (a note, a byte) as an empty database
    if (const std::uintmax_t bytes = std::filesystem::file_size(path, ec); !create && !ec && bytes > 0)
      throw InputError(fmt::format("{}: a file of {} bytes that holds no SQLite database, not a history store; "
                                   "accepted: a ccal history store, or a new file name",
                                   path, bytes));
    if (!create)
      throw InputError(fmt::format("{}: an empty file, not a history store; accepted: a history store, or a first "
                                   "statement added to it, which makes it one",
                                   path));
    execute(db, path, kSchema, "cannot write its schema");
    Statement meta(db, path,
                   "INSERT INTO meta(key, value) VALUES ('application', ?1), ('schema_version', ?2)");
    meta.text(1, std::string(kApplication)).text(2, std::to_string(kHistorySchemaVersion)).step();
  }
  return schema;
}

// The coefficients of calibration `id`, one row each.
void insert_coefficients(sqlite3* db, const std::string& path, std::int64_t id, const HistoryEntry& entry) {
  for (const HistoryCoefficient& c : entry.coefficients) {
    Statement row(db, path,
                  "INSERT INTO coefficient(calibration, name, unit, value, expanded, coverage_factor, "
                  "coverage_probability, effective_dof) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)");
    row.integer(1, id)
        .text(2, c.name)
        .text(3, c.unit)
        .number(4, c.value)
        .number(5, c.expanded)
        .number(6, c.coverage_factor)
        .number(7, c.coverage_probability)
        .number(8, c.effective_dof)
        .step();
  }
}

// The records calibration `id` replaces (its certificate's `replaces`), each superseded by it.
void insert_supersessions(sqlite3* db, const std::string& path, std::int64_t id, const HistoryEntry& entry,
                          const std::vector<std::int64_t>& replaced) {
  for (const std::int64_t old : replaced) {
    Statement supersession(db, path,
                           "INSERT INTO supersession(calibration, by, reason, at) VALUES (?1, ?2, ?3, ?4)");
    supersession.integer(1, old)
        .integer(2, id)
        .text(3, entry.certificate_number.empty()
                     ? fmt::format("replaced by calibration {}", id)
                     : fmt::format("replaced by certificate {}", entry.certificate_number))
        .text(4, utc_now())
        .step();
  }
}

}  // namespace

std::string default_history_path() {
  if (const char* chosen = std::getenv("CCAL_HISTORY"); chosen && *chosen) return chosen;
  if (const char* data = std::getenv("XDG_DATA_HOME"); data && *data)
    return (std::filesystem::path(data) / "ccal" / "history.sqlite").string();
  const char* home = std::getenv("HOME");
  return (std::filesystem::path(home && *home ? home : ".") / ".local" / "share" / "ccal" / "history.sqlite")
      .string();
}

HistoryStore HistoryStore::open(const std::string& path, Access access, int busy_millis,
                                const std::string& shown) {
  const bool create = access == Access::create, writing = access != Access::read;
  prepare_store_path(path, create);
  HistoryStore store;
  store.path_ = shown.empty() ? path : shown;
  const int flags = create    ? SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE
                    : writing ? SQLITE_OPEN_READWRITE
                              : SQLITE_OPEN_READONLY;
  if (sqlite3_open_v2(path.c_str(), &store.db_, flags, nullptr) != SQLITE_OK)
    Statement::throw_store_error(store.db_, path, "cannot open it");
  sqlite3_busy_timeout(store.db_, busy_millis);
  execute(store.db_, path, "PRAGMA foreign_keys = ON", "cannot open it");
  {
    Statement check(store.db_, path, "PRAGMA quick_check");
    if (!check.step() || check.column_text(0) != "ok")
      throw InputError(
          fmt::format("{}: history store: damaged (SQLite's quick check: {}); accepted: a sound "
                      "store (restore it from a backup; nothing was written to it)",
                      path, check.column_text(0)));
  }
  // The schema: made in one transaction on a new file (two processes creating it at once: one waits and then
  // finds it made), refused when it is another file or newer.
  execute(store.db_, path, writing ? "BEGIN IMMEDIATE" : "BEGIN", "cannot lock it");
  try {
    store.schema_ = checked_schema(store.db_, path, create, writing);
    if (writing) execute(store.db_, path, kMetaKept, "cannot write its schema");
    execute(store.db_, path, "COMMIT", "cannot write its schema");
  } catch (...) {
    sqlite3_exec(store.db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  return store;
}

HistoryStore::HistoryStore(HistoryStore&& other) noexcept
    : db_(other.db_), path_(std::move(other.path_)), schema_(other.schema_), depth_(other.depth_) {
  other.db_ = nullptr;
}

HistoryStore& HistoryStore::operator=(HistoryStore&& other) noexcept {
  if (this != &other) {
    sqlite3_close_v2(db_);
    db_ = other.db_;
    path_ = std::move(other.path_);
    schema_ = other.schema_;
    depth_ = other.depth_;
    other.db_ = nullptr;
  }
  return *this;
}

HistoryStore::~HistoryStore() { sqlite3_close_v2(db_); }

void HistoryStore::check_units(const HistoryEntry& entry) const {
  for (const HistoryCoefficient& c : entry.coefficients) {
    Statement unit(
        db_, path_,
        "SELECT k.unit, c.date FROM coefficient k JOIN calibration c ON c.id = k.calibration WHERE "
        "c.serial = ?1 AND k.name = ?2 ORDER BY c.date, c.id LIMIT 1");
    unit.text(1, entry.serial).text(2, c.name);
    if (unit.step() && unit.column_text(0) != c.unit)
      throw InputError(
          fmt::format("{}: {} of '{}' is in '{}' in this statement but in '{}' in its calibration of {}; the "
                      "history compares "
                      "values of one unit; accepted: a statement of the configuration's units ([instrument] "
                      "output_unit as "
                      "before)",
                      path_, c.name, entry.serial, c.unit, unit.column_text(0), unit.column_text(1)));
  }
}

std::vector<std::int64_t> HistoryStore::replaced_records(const HistoryEntry& entry) const {
  std::vector<std::int64_t> out;
  if (entry.replaces.empty()) return out;
  Statement find(
      db_, path_,
      "SELECT c.id, s.calibration FROM calibration c LEFT JOIN supersession s ON s.calibration = c.id "
      "WHERE c.serial = ?1 AND c.certificate_number = ?2 ORDER BY c.id");
  find.text(1, entry.serial).text(2, entry.replaces);
  std::vector<std::int64_t> superseded;
  while (find.step()) (find.column_null(1) ? out : superseded).push_back(find.column_integer(0));
  if (out.empty())
    throw InputError(fmt::format(
        "{}: the statement's certificate replaces certificate '{}', {} of '{}'; accepted: [certificate] "
        "replaces "
        "naming the number of a recorded calibration of {} in force (`ccal history show`), or no replaces",
        path_, entry.replaces,
        superseded.empty() ? std::string("which names no calibration")
                           : fmt::format("whose calibration {} is already superseded", superseded.front()),
        entry.serial, entry.serial));
  return out;
}

std::int64_t HistoryStore::add(const HistoryEntry& entry,
                               const std::function<void(std::int64_t id)>& before_commit) {
  const std::string sha = sha256_hex(entry.statement_json);
  std::int64_t id = 0;
  transaction([&] {
    {
      Statement known(db_, path_, "SELECT id, serial, date FROM calibration WHERE statement_sha256 = ?1");
      known.text(1, sha);
      if (known.step())
        throw InputError(fmt::format(
            "{}: this statement is already recorded, as calibration {} of {} on {} "
            "(SHA-256 {}); accepted: a statement not yet recorded",
            path_, known.column_integer(0), known.column_text(1), known.column_text(2), sha.substr(0, 12)));
    }
    check_units(entry);
    const std::vector<std::int64_t> replaced = replaced_records(entry);
    Statement insert(
        db_, path_,
        "INSERT INTO calibration(serial, date, instrument, ccal_version, config, statement_sha256, "
        "added_at, statement, setup_sha256, certificate_number, shared) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, "
        "?8, ?9, ?10, ?11)");
    insert.text(1, entry.serial)
        .text(2, entry.date)
        .text(3, entry.instrument)
        .text(4, entry.ccal_version)
        .text(5, entry.config)
        .text(6, sha)
        .text(7, utc_now())
        .text(8, entry.statement_json);
    if (entry.shared)
      insert.text(9, entry.shared->setup_sha256).text(11, detail::shared_part_text(*entry.shared));
    if (!entry.certificate_number.empty()) insert.text(10, entry.certificate_number);
    insert.step();
    id = sqlite3_last_insert_rowid(db_);
    insert_coefficients(db_, path_, id, entry);
    insert_supersessions(db_, path_, id, entry, replaced);
    if (before_commit) before_commit(id);
  });
  return id;
}

void HistoryStore::transaction(const std::function<void()>& body) {
  if (depth_ > 0) {  // within an outer transaction: its COMMIT or ROLLBACK is this one's
    body();
    return;
  }
  execute(db_, path_, "BEGIN IMMEDIATE", "cannot lock it for writing");
  depth_ = 1;
  try {
    body();
    depth_ = 0;
    execute(db_, path_, "COMMIT", "cannot write it");
  } catch (...) {
    depth_ = 0;
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

void HistoryStore::supersede(std::int64_t id, std::optional<std::int64_t> by, const std::string& reason) {
  if (reason.empty())
    throw OptionError(
        "reason", "",
        fmt::format("is needed to supersede calibration {} of {}; accepted: the reason, as text", id, path_));
  if (detail::history_blank(reason))
    throw OptionError(
        "reason", detail::history_shown(reason),
        fmt::format("is blank; accepted: the reason calibration {} of {} is superseded, as text", id, path_));
  transaction([&] {
    const auto serial_of = [&](std::int64_t which) {
      Statement find(db_, path_, "SELECT serial FROM calibration WHERE id = ?1");
      find.integer(1, which);
      if (!find.step())
        throw InputError(fmt::format(
            "{}: no calibration {} in the history store; accepted: the id of a record in it", path_, which));
      return find.column_text(0);
    };
    const std::string serial = serial_of(id);
    if (by) {
      if (*by == id)
        throw InputError(fmt::format(
            "{}: calibration {} cannot supersede itself; accepted: another record's id", path_, id));
      if (serial_of(*by) != serial)
        throw InputError(
            fmt::format("{}: calibration {} is of another serial number than {} ({}); accepted: a "
                        "record of {}",
                        path_, *by, id, serial, serial));
    }
    const auto supersession_of = [&](std::int64_t which) -> std::optional<std::string> {
      Statement done(db_, path_, "SELECT reason FROM supersession WHERE calibration = ?1");
      done.integer(1, which);
      if (!done.step()) return std::nullopt;
      return done.column_text(0);
    };
    if (const auto done = supersession_of(id))
      throw InputError(fmt::format(
          "{}: calibration {} is already superseded ({}), and a record is superseded once; accepted: a "
          "calibration of {} that is not superseded (`ccal history show`)",
          path_, id, *done, serial));
    if (by)
      if (const auto done = supersession_of(*by))
        throw InputError(
            fmt::format("{}: calibration {} is itself superseded ({}), so it replaces nothing; accepted: a "
                        "record of {} that is not superseded",
                        path_, *by, *done, serial));
    Statement insert(db_, path_,
                     "INSERT INTO supersession(calibration, by, reason, at) VALUES (?1, ?2, ?3, ?4)");
    insert.integer(1, id).text(3, reason).text(4, utc_now());
    if (by) insert.integer(2, *by);
    insert.step();
  });
}

std::optional<std::int64_t> HistoryStore::id_of_statement(const std::string& statement_json) const {
  Statement find(db_, path_, "SELECT id FROM calibration WHERE statement_sha256 = ?1");
  find.text(1, sha256_hex(statement_json));
  if (!find.step()) return std::nullopt;
  return find.column_integer(0);
}

std::vector<HistoryRecord> HistoryStore::records(const std::string& serial) const {
  std::vector<HistoryRecord> out;
  // A schema-1 file opened read-only has not the columns of schema 2: nothing known, as after migrating.
  const std::string sql = fmt::format(
      "SELECT c.id, c.serial, c.date, c.instrument, c.ccal_version, c.config, c.statement_sha256, "
      "c.added_at, s.by, s.reason, c.statement, {} FROM calibration c LEFT JOIN supersession s ON "
      "s.calibration = c.id "
      "WHERE c.serial = ?1 ORDER BY c.date, c.id",
      schema_ >= 2 ? "c.certificate_number, c.shared" : "NULL, NULL");
  Statement list(db_, path_, sql.c_str());
  list.text(1, serial);
  while (list.step()) {
    HistoryRecord r;
    r.id = list.column_integer(0);
    r.serial = list.column_text(1);
    r.date = list.column_text(2);
    r.instrument = list.column_text(3);
    r.ccal_version = list.column_text(4);
    r.config = list.column_text(5);
    r.statement_sha256 = list.column_text(6);
    r.added_at = list.column_text(7);
    r.statement_json = list.column_text(10);
    r.certificate_number = list.column_text(11);
    if (!calendar_day(r.date)) refuse_stored(r, fmt::format("its date {} is not YYYY-MM-DD", detail::history_shown(r.date)));
    if (!list.column_null(12)) {
      nlohmann::json shared;
      try {
        shared = nlohmann::json::parse(list.column_text(12));
      } catch (const nlohmann::json::exception&) {
        refuse_stored(r, "what it shares is not JSON");
      }
      r.shared = detail::shared_part_of(shared, fmt::format("{}: calibration {}", path_, r.id));
    }
    if (!list.column_null(9)) {
      if (!list.column_null(8)) r.superseded_by = list.column_integer(8);
      r.superseded_reason = list.column_text(9);
    }
    out.push_back(std::move(r));
  }
  for (HistoryRecord& r : out) {
    Statement rows(db_, path_,
                   "SELECT name, unit, value, expanded, coverage_factor, coverage_probability, effective_dof "
                   "FROM coefficient WHERE calibration = ?1 ORDER BY rowid");
    rows.integer(1, r.id);
    while (rows.step()) {
      r.coefficients.push_back({rows.column_text(0), rows.column_text(1), rows.column_number(2),
                                rows.column_number(3), rows.column_number(4), rows.column_number(5),
                                rows.column_number(6)});
      const HistoryCoefficient& c = r.coefficients.back();
      if (!(std::isfinite(c.value) && std::isfinite(c.expanded) && c.expanded >= 0 &&
            std::isfinite(c.coverage_factor) && c.coverage_factor > 0 && c.coverage_probability >= 0 &&
            c.coverage_probability < 1))
        refuse_stored(r, fmt::format("its {} has no finite value, finite U ≥ 0, k > 0 and p in (0, 1) or not stated",
                                     detail::history_shown(c.name)));
    }
  }
  return out;
}

void HistoryStore::refuse_stored(const HistoryRecord& r, const std::string& what) const {
  throw InputError(fmt::format(
      "{}: history store: calibration {} as stored: {}; ccal writes no such record, so the store was changed "
      "outside ccal; accepted: a store as ccal wrote it (restore it from a backup)",
      path_, r.id, what));
}

std::vector<HistoryStore::SerialSummary> HistoryStore::summaries() const {
  std::vector<SerialSummary> out;
  Statement list(db_, path_,
                 "SELECT c.serial, count(*), count(s.calibration), max(c.date) FROM calibration c LEFT JOIN "
                 "supersession s ON s.calibration = c.id GROUP BY c.serial ORDER BY c.serial");
  while (list.step())
    out.push_back({list.column_text(0), std::size_t(list.column_integer(1)),
                   std::size_t(list.column_integer(2)), list.column_text(3)});
  return out;
}

std::vector<std::string> HistoryStore::serials() const {
  std::vector<std::string> out;
  Statement list(db_, path_, "SELECT DISTINCT serial FROM calibration ORDER BY serial");
  while (list.step()) out.push_back(list.column_text(0));
  return out;
}

}  // namespace ccal
