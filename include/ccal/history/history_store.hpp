#pragma once
// The calibration history of instruments (docs/cli.md, `ccal history`): every calibration statement of a
// serial number kept in one SQLite file, so that drift and agreement between calibrations can be judged
// (uncertainty/history_trend.hpp).
//
// The store. One file (SQLite 3), schema version kHistorySchemaVersion, recorded in its `meta` table with the
// application's name; a file of an older schema is migrated forward on opening for writing, one of a newer
// schema is refused, as is any file that is not a ccal history store or fails SQLite's quick_check. Tables:
//     meta(key, value)                                   schema_version, application
//     calibration(id, serial, date, instrument, ccal_version, config, statement_sha256 UNIQUE, added_at,
//                 statement,                            the statement's JSON text, whole
//                 setup_sha256, certificate_number,     schema 2: the set-up's fingerprint, the certificate's
//                 shared)                               number, what it shares with others on its set-up
//                                                       (uncertainty/history_shared.hpp) as JSON: the
//                                                       statement's setup_sha256, inputs[] {id, measured,
//                                                       group, effect}, input_correlations and covariance
//                                                       {order, type_b}. NULL: not known (a record of
//                                                       schema 1, or a statement that did not state it),
//                                                       treated as independent of every other
//     coefficient(calibration, name, unit, value, expanded, coverage_factor, coverage_probability,
//                 effective_dof)                        one row per coefficient: the corrected estimate, U,
//                 k, p,
//                                                       ν_eff (NULL: ∞), in the statement's units
//     supersession(calibration, by, reason, at)         a record replaced, never changed
// Schema 1 → 2 adds the three columns, NULL in every record already there (records stay as they were).
// A record is never changed or deleted: triggers refuse UPDATE and DELETE on every table (calibration,
// coefficient, supersession, and meta, whose two triggers an opening for writing adds to a store made before
// them); a record is only superseded, with a reason. Every
// write is one transaction (BEGIN IMMEDIATE, waiting up to kHistoryBusyMillis for another writer), so two
// processes adding at once lose nothing, and a process killed mid-add leaves the store as it was before the
// add.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/uncertainty/history_shared.hpp"

struct sqlite3;  // the SQLite connection (sqlite3.h), kept out of this header

namespace ccal {

inline constexpr int kHistorySchemaVersion = 2;
inline constexpr int kHistoryBusyMillis = 10000;

// One coefficient of a recorded calibration, in the statement's units.
struct HistoryCoefficient {
  std::string name, unit;
  double value = 0;                 // the corrected estimate K̂ + b
  double expanded = 0;              // U
  double coverage_factor = 0;       // k
  double coverage_probability = 0;  // p
  double effective_dof = 0;         // ν_eff; +∞ where infinite
  double standard_uncertainty() const { return coverage_factor > 0 ? expanded / coverage_factor : 0.0; }
};

// One recorded calibration.
struct HistoryRecord {
  std::int64_t id = 0;
  std::string serial;
  std::string date;  // YYYY-MM-DD, the date of calibration
  std::string instrument;
  std::string ccal_version;  // of the ccal that wrote the statement
  std::string config;        // the configuration the statement names
  std::string statement_sha256;
  std::string added_at;  // UTC, ISO 8601
  std::string certificate_number;    // the statement's certificate number; "": none (or a schema-1 record)
  std::optional<SharedPart> shared;  // what it shares with others on its set-up; none: not known
  std::vector<HistoryCoefficient> coefficients;
  std::optional<std::int64_t> superseded_by;  // the record that replaces it, if one does
  std::string superseded_reason;              // not empty: superseded (excluded from drift and E_n)
  std::string statement_json;                 // the statement as recorded
};

// What `add` records from a statement's JSON text: the coefficients and the provenance it carries, with
// serial, date and instrument given or taken from its certificate fields.
struct HistoryEntry {
  std::string serial, date, instrument, ccal_version, config;
  std::string
      statement_json;  // the statement itself (a reduce/identify output's "statement", or the file whole)
  std::vector<HistoryCoefficient> coefficients;
  std::string certificate_number;    // the statement's certificate.number; "": none
  std::string replaces;              // its certificate.replaces: the number of the certificate it replaces
  std::optional<SharedPart> shared;  // none: the statement does not state it (no setup_sha256)
};

// Reads a statement from the JSON text of `ccal reduce --statement-out FILE` (or of a whole `ccal reduce` /
// `ccal identify --statement` JSON output, whose "statement" is taken); `source` names it in messages.
// serial, date: given (empty: from the statement's certificate fields, serial_number and
// date_of_calibration). InputError for text that is no statement (the statement's CSV form said so), a
// missing serial or date, a serial that is blank or holds control characters, a date not YYYY-MM-DD, a
// coverage probability not in (0, 1), or a shared part (setup_sha256 stated) whose inputs or correlations are
// malformed. The certificate's number and replaces are read from its "certificate" object.
HistoryEntry history_entry(const std::string& json_text, const std::string& source, const std::string& serial,
                           const std::string& date);

// Days from 1970-01-01 of a YYYY-MM-DD date (proleptic Gregorian), or none for text that is no such date: the
// one reader of the history's dates.
std::optional<std::int64_t> calendar_day(std::string_view date);

// The default store: $CCAL_HISTORY if set, else $XDG_DATA_HOME/ccal/history.sqlite, else
// ~/.local/share/ccal/history.sqlite.
std::string default_history_path();

// The store, opened for one use. Every failure is an InputError naming the file and what would be accepted.
class HistoryStore {
 public:
  // read: opened read-only (nothing is ever written; a missing file is refused); write: read and write, a
  // missing file refused; create: make the file (and its folder) if missing. An older schema is migrated
  // forward when writing (none exists yet: version 1 is the first). busy_millis: how long to wait for another
  // process's lock before refusing.
  enum class Access { read, write, create };
  // shown: the name the store's messages and path() give it (empty: `path`), for a new store built in a
  // temporary file before it is put in place.
  static HistoryStore open(const std::string& path, Access access, int busy_millis = kHistoryBusyMillis,
                           const std::string& shown = {});
  HistoryStore(HistoryStore&& other) noexcept;
  HistoryStore& operator=(HistoryStore&& other) noexcept;
  HistoryStore(const HistoryStore&) = delete;
  HistoryStore& operator=(const HistoryStore&) = delete;
  ~HistoryStore();

  // Records a calibration in one transaction; returns its id. InputError for a statement already recorded
  // (the same SHA-256 of its text), naming the record, and for a coefficient in another unit than the
  // serial's records have it in. An entry that replaces a certificate number supersedes the serial's records
  // of that number not yet superseded by the new record, in the same transaction (reason "replaced by
  // certificate <number>"); InputError, nothing written, when no such record is in force. before_commit, when
  // given, runs with the new id after the rows are written and before COMMIT (the store's reads on this
  // connection already see them); an exception from it rolls the transaction back, so that nothing is
  // recorded, and is passed on.
  std::int64_t add(const HistoryEntry& entry, const std::function<void(std::int64_t id)>& before_commit = {});
  // Runs `body` as one transaction (BEGIN IMMEDIATE … COMMIT): the adds and supersessions it makes are
  // recorded together or, when it throws, not at all (ROLLBACK, the exception passed on). Nested calls, and
  // add or supersede within it, join the outer transaction.
  void transaction(const std::function<void()>& body);
  // Marks record `id` superseded, by record `by` of the same serial if given, for `reason` (not blank), in
  // one transaction. InputError for an unknown id, a record already superseded, `by` unknown, of another
  // serial, itself superseded, or the record itself.
  void supersede(std::int64_t id, std::optional<std::int64_t> by, const std::string& reason);
  // The id of the record of this statement text (history_entry's statement_json), if recorded.
  std::optional<std::int64_t> id_of_statement(const std::string& statement_json) const;
  // Every calibration of a serial number, oldest first (by date, then id), superseded ones included.
  // InputError naming the record for one no ccal writes (a store edited by hand: a date that is no date, a
  // coefficient without a finite value, U, k or p, what it shares not JSON).
  std::vector<HistoryRecord> records(const std::string& serial) const;
  // The serial numbers in the store, sorted.
  std::vector<std::string> serials() const;
  // Per serial number (sorted): its calibrations, how many of them are superseded, and the last date.
  struct SerialSummary {
    std::string serial;
    std::size_t calibrations = 0, superseded = 0;
    std::string last_date;  // of the latest calibration, superseded ones included
  };
  std::vector<SerialSummary> summaries() const;
  // The file's schema version (older files opened read-only are not migrated).
  int schema() const { return schema_; }
  const std::string& path() const { return path_; }

 private:
  HistoryStore() = default;
  void check_units(const HistoryEntry& entry) const;
  [[noreturn]] void refuse_stored(const HistoryRecord& record, const std::string& what) const;
  std::vector<std::int64_t> replaced_records(const HistoryEntry& entry) const;
  ::sqlite3* db_ = nullptr;
  std::string path_;
  int schema_ = kHistorySchemaVersion;
  int depth_ = 0;  // 1 within transaction()
};

}  // namespace ccal
