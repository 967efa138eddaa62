#include "ccal/verbs/history.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

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
     "Serial number (default: the statement's [certificate] serial_number)"},
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

std::string store_path(const std::string& db) { return db.empty() ? default_history_path() : db; }

}  // namespace

OptionTable<HistoryAddOptions> options_of(std::type_identity<HistoryAddOptions>) { return kAddRows; }
OptionTable<HistoryShowOptions> options_of(std::type_identity<HistoryShowOptions>) { return kShowRows; }

OptionTable<HistorySupersedeOptions> options_of(std::type_identity<HistorySupersedeOptions>) {
  return kSupersedeRows;
}
OptionTable<HistoryStoreOptions> options_of(std::type_identity<HistoryStoreOptions>) { return kStoreRows; }

void history_supersede(std::int64_t id, const HistorySupersedeOptions& o) {
  check_options(o, option_table<HistorySupersedeOptions>());
  HistoryStore store = HistoryStore::open(store_path(o.db), HistoryStore::Access::write);
  store.supersede(id, o.by > 0 ? std::optional<std::int64_t>(o.by) : std::nullopt, o.reason);
}

std::string history_export(const std::string& serial, const HistoryStoreOptions& o) {
  return export_history(HistoryStore::open(store_path(o.db), HistoryStore::Access::read), serial);
}

HistoryImport history_import(const std::string& file, const HistoryStoreOptions& o) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read it; accepted: an exported history file", file));
  std::stringstream text;
  text << in.rdbuf();
  HistoryStore store = HistoryStore::open(store_path(o.db), HistoryStore::Access::create);
  return import_history(store, text.str(), file);
}

std::int64_t history_day(const std::string& date, std::string_view field) {
  if (const std::optional<std::int64_t> day = calendar_day(date)) return *day;
  throw OptionError(std::string(field), date, "is not a date; accepted: YYYY-MM-DD, e.g. 2026-11-30");
}

HistoryAddResult history_add(const std::string& statement_file, const HistoryAddOptions& o) {
  if (!o.date.empty()) history_day(o.date, "date");
  std::ifstream in(statement_file, std::ios::binary);
  if (!in)
    throw InputError(
        fmt::format("{}: cannot read it; accepted: a calibration statement's JSON file", statement_file));
  std::stringstream text;
  text << in.rdbuf();
  HistoryAddResult r;
  r.entry = history_entry(text.str(), statement_file, o.serial, o.date);
  r.db = store_path(o.db);
  HistoryStore store = HistoryStore::open(r.db, HistoryStore::Access::create);
  r.id = store.add(r.entry);
  r.calibrations = store.records(r.entry.serial).size();
  return r;
}

HistoryShowResult history_show(const std::string& serial, const HistoryShowOptions& o) {
  HistoryShowResult r;
  r.db = store_path(o.db);
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
