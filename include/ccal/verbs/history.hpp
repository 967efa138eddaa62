#pragma once
// `ccal history` as library calls (docs/cli.md): record a calibration statement in an instrument's history
// (history/history_store.hpp), and read a serial number's calibrations back with, per coefficient, the agreement
// of successive calibrations (E_n), the drift line and its prediction at a date
// (uncertainty/history_trend.hpp).

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ccal/core/options.hpp"
#include "ccal/history/history_exchange.hpp"
#include "ccal/history/history_store.hpp"
#include "ccal/uncertainty/history_trend.hpp"

namespace ccal::verbs {

struct HistoryAddOptions {
  std::string db;      // the store; "": default_history_path()
  std::string serial;  // "": the statement's [certificate] serial_number
  std::string date;    // YYYY-MM-DD; "": the statement's [certificate] date_of_calibration
};
OptionTable<HistoryAddOptions> options_of(std::type_identity<HistoryAddOptions>);

struct HistoryShowOptions {
  std::string db;  // the store; "": default_history_path()
  std::string at;  // YYYY-MM-DD: the drift line's prediction at that date; "": none
};
OptionTable<HistoryShowOptions> options_of(std::type_identity<HistoryShowOptions>);

struct HistorySupersedeOptions {
  std::string db;       // the store; "": default_history_path()
  std::int64_t by = 0;  // the record that replaces it; 0: none
  std::string reason;   // why (required)
};
OptionTable<HistorySupersedeOptions> options_of(std::type_identity<HistorySupersedeOptions>);

struct HistoryStoreOptions {
  std::string db;  // the store; "": default_history_path()
};
OptionTable<HistoryStoreOptions> options_of(std::type_identity<HistoryStoreOptions>);

struct HistoryAddResult {
  std::string db;
  std::int64_t id = 0;
  HistoryEntry entry;
  std::size_t calibrations = 0;  // of the serial, this one included
  std::vector<std::int64_t> replaced;  // records it superseded (its certificate replaces theirs)
};

// One coefficient over the calibrations (those not superseded), oldest first.
struct CoefficientHistory {
  std::string name, unit;
  std::vector<std::string> dates;
  std::vector<std::int64_t> ids;     // the record of each point
  std::vector<HistoryPoint> points;  // years from the first calibration's date
  // C_ij: what calibrations i and j share of this coefficient's error (uncertainty/history_shared.hpp),
  // points × points; the diagonal is each one's shared part with itself (its u_B² where nothing was
  // measured).
  Eigen::MatrixXd shared;
  std::vector<NormalisedError> agreement;
  DriftLine drift;
  std::optional<DriftPrediction> prediction;  // at options.at, when the line is available
};

// Where the set-up or its tolerances change between two successive calibrations in force.
struct SetupChange {
  std::int64_t from = 0, to = 0;  // the records
  std::string from_date, to_date;
  bool setup = false;       // another set-up fingerprint: nothing shared across it
  bool tolerances = false;  // the same set-up, other inputs charged at their tolerance (ids, groups,
                            // correlations or effects): only the inputs both charge are shared
  bool unknown = false;     // either record does not know what it shares (schema 1): treated as independent
};

struct HistoryShowResult {
  std::string db, serial, at;
  std::vector<HistoryRecord> records;  // every calibration, superseded ones included
  // The set-ups in order of first appearance (their fingerprints), and each record's: an index into setups,
  // or -1 where the record does not know its set-up.
  std::vector<std::string> setups;
  std::vector<int> setup_of;
  std::vector<SetupChange> changes;  // between successive calibrations in force
  std::vector<CoefficientHistory> coefficients;
};

// `ccal history list`: the serial numbers of a store.
struct HistoryListResult {
  std::string db;
  std::vector<HistoryStore::SerialSummary> serials;
};

// The store a history command uses for its db option: db itself, or default_history_path() when empty. The
// one resolution of the option, so that a front end can treat the store as one of the command's files.
std::string history_store_path(const std::string& db);

// Reads the statement file, records it; InputError for an unreadable or bad file (a folder, the statement's
// CSV form), a bad option or store. before_commit, when given, runs with the result once the calibration is
// written but before the store's transaction commits; an exception from it (e.g. the command's output could
// not be written) rolls the addition back, so that the store records nothing, and is passed on.
HistoryAddResult history_add(const std::string& statement_file, const HistoryAddOptions& options = {},
                             const std::function<void(const HistoryAddResult&)>& before_commit = {});
// InputError for a serial with no calibration in the store (naming those it has), a bad date or store.
HistoryShowResult history_show(const std::string& serial, const HistoryShowOptions& options = {});
// Every serial number of the store with its count of calibrations (and superseded ones) and the last date.
HistoryListResult history_list(const HistoryStoreOptions& options = {});
// The name `show` gives set-up `index` (0: "S1"), or "?" for -1 (not known).
std::string setup_label(int index);

// Marks a record superseded (never changed otherwise); InputError as HistoryStore::supersede.
void history_supersede(std::int64_t id, const HistorySupersedeOptions& options);
// A calibration's id as typed (the ID of `ccal history supersede`): a whole number ≥ 1. InputError "ID: 'abc' is
// not a calibration id; accepted: …" otherwise.
std::int64_t history_record_id(const std::string& text);
// A serial's history as JSON (history/history_exchange.hpp), and a file of it recorded in the store.
std::string history_export(const std::string& serial, const HistoryStoreOptions& options = {});
HistoryImport history_import(const std::string& file, const HistoryStoreOptions& options = {});

// Days from 1970-01-01 of a YYYY-MM-DD date (proleptic Gregorian); OptionError of `field` for a non-date.
std::int64_t history_day(const std::string& date, std::string_view field);

}  // namespace ccal::verbs
