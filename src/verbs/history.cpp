#include "ccal/verbs/history.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "ccal/core/errors.hpp"

namespace ccal::verbs {

namespace {

// The db option of every history command (default_history_path()).
constexpr std::string_view kStoreHelp =
    "The history store (default: $CCAL_HISTORY, else $XDG_DATA_HOME/ccal/history.sqlite, else "
    "~/.local/share/ccal/history.sqlite)";

constexpr OptionSpec<HistoryAddOptions> kAddRows[] = {
    {"db", &HistoryAddOptions::db, "FILE", kStoreHelp},
    {"serial", &HistoryAddOptions::serial, "S",
     "Serial number: printable characters, not blank (default, also for an empty S: the statement's "
     "[certificate] serial_number)"},
    {"date", &HistoryAddOptions::date, "YYYY-MM-DD",
     "Date of calibration (default: the statement's [certificate] date_of_calibration)"},
};

constexpr OptionSpec<HistoryShowOptions> kShowRows[] = {
    {"db", &HistoryShowOptions::db, "FILE", kStoreHelp},
    {"at", &HistoryShowOptions::at, "YYYY-MM-DD",
     "Predict each coefficient at this date from its drift line"},
};

constexpr OptionSpec<HistorySupersedeOptions> kSupersedeRows[] = {
    {"db", &HistorySupersedeOptions::db, "FILE", kStoreHelp},
    {"by", &HistorySupersedeOptions::by, "ID", "The record that replaces it (0: none)",
     OptionRange::at_least(0)},
    {"reason", &HistorySupersedeOptions::reason, "TEXT", "Why it is superseded (required)"},
};

constexpr OptionSpec<HistoryStoreOptions> kStoreRows[] = {
    {"db", &HistoryStoreOptions::db, "FILE", kStoreHelp},
};

// A statement or history file to read: refused with what it is when it is a folder or cannot be read.
std::string read_history_file(const std::string& file, std::string_view accepted) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw InputError(fmt::format("{}: it is a folder; accepted: {}", file, accepted));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read it; accepted: {}", file, accepted));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::string history_store_path(const std::string& db) { return db.empty() ? default_history_path() : db; }

OptionTable<HistoryAddOptions> options_of(std::type_identity<HistoryAddOptions>) { return kAddRows; }
OptionTable<HistoryShowOptions> options_of(std::type_identity<HistoryShowOptions>) { return kShowRows; }

OptionTable<HistorySupersedeOptions> options_of(std::type_identity<HistorySupersedeOptions>) {
  return kSupersedeRows;
}
OptionTable<HistoryStoreOptions> options_of(std::type_identity<HistoryStoreOptions>) { return kStoreRows; }

void history_supersede(std::int64_t id, const HistorySupersedeOptions& o) {
  check_options(o, option_table<HistorySupersedeOptions>());
  HistoryStore store = HistoryStore::open(history_store_path(o.db), HistoryStore::Access::write);
  store.supersede(id, o.by > 0 ? std::optional<std::int64_t>(o.by) : std::nullopt, o.reason);
}

std::string history_export(const std::string& serial, const HistoryStoreOptions& o) {
  return export_history(HistoryStore::open(history_store_path(o.db), HistoryStore::Access::read), serial);
}

HistoryImport history_import(const std::string& file, const HistoryStoreOptions& o) {
  const std::string text = read_history_file(file, "an exported history file (`ccal history export`)");
  HistoryStore store = HistoryStore::open(history_store_path(o.db), HistoryStore::Access::create);
  return import_history(store, text, file);
}

std::int64_t history_day(const std::string& date, std::string_view field) {
  if (const std::optional<std::int64_t> day = calendar_day(date)) return *day;
  throw OptionError(std::string(field), date, "is not a date; accepted: YYYY-MM-DD, e.g. 2026-11-30");
}

HistoryAddResult history_add(const std::string& statement_file, const HistoryAddOptions& o,
                             const std::function<void(const HistoryAddResult&)>& before_commit) {
  if (!o.date.empty()) history_day(o.date, "date");
  const std::string text = read_history_file(statement_file, "a calibration statement's JSON file");
  HistoryAddResult r;
  r.entry = history_entry(text, statement_file, o.serial, o.date);
  r.db = history_store_path(o.db);
  HistoryStore store = HistoryStore::open(r.db, HistoryStore::Access::create);
  store.add(r.entry, [&](std::int64_t id) {
    r.id = id;
    r.calibrations = store.records(r.entry.serial).size();  // this one included: the transaction sees it
    if (before_commit) before_commit(r);
  });
  return r;
}

HistoryShowResult history_show(const std::string& serial, const HistoryShowOptions& o) {
  HistoryShowResult r;
  r.db = history_store_path(o.db);
  r.serial = serial;
  r.at = o.at;
  const bool predicting = !o.at.empty();
  const std::int64_t at_day = predicting ? history_day(o.at, "at") : 0;
  const HistoryStore store = HistoryStore::open(r.db, HistoryStore::Access::read);
  r.records = store.records(serial);
  if (r.records.empty()) {
    const std::vector<std::string> known = store.serials();
    throw InputError(fmt::format(
        "{}: no calibration of '{}' in the history store; accepted: {}", r.db, serial,
        known.empty() ? std::string("none recorded yet") : fmt::format("one of {}", fmt::join(known, ", "))));
  }
  // Per coefficient, in the order of the first calibration that has it; time in years from the first date.
  const std::int64_t origin = history_day(r.records.front().date, "date");
  std::map<std::string, std::size_t> index;
  for (const HistoryRecord& rec : r.records) {
    if (rec.superseded_by || !rec.superseded_reason.empty()) continue;
    const double years = double(history_day(rec.date, "date") - origin) / kDaysPerYear;
    for (const HistoryCoefficient& c : rec.coefficients) {
      auto [it, fresh] = index.try_emplace(c.name, r.coefficients.size());
      if (fresh) r.coefficients.push_back({c.name, c.unit, {}, {}, {}, {}, {}});
      CoefficientHistory& h = r.coefficients[it->second];
      if (c.unit != h.unit)
        throw InputError(
            fmt::format("{}: {} of '{}' is in {} on {} but in {} on {}; the history compares values "
                        "of one unit; accepted: statements of one configuration's units",
                        r.db, c.name, serial, h.unit, h.dates.front(), c.unit, rec.date));
      h.dates.push_back(rec.date);
      h.points.push_back({years, c.value, c.expanded, c.coverage_factor});
    }
  }
  for (CoefficientHistory& h : r.coefficients) {
    h.agreement = normalised_errors(h.points);
    h.drift = drift_line(h.points);
    if (predicting && h.drift.available)
      h.prediction = predict(h.drift, double(at_day - origin) / kDaysPerYear);
  }
  return r;
}

}  // namespace ccal::verbs
