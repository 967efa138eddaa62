#include "ccal/verbs/history.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "ccal/core/errors.hpp"
#include "../history/history_text.hpp"

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
  // A JSON text given for its file's path (history_export's returned text passed on): said so, not echoed whole
  // as a path that does not exist.
  const std::size_t first = file.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && (file[first] == '{' || file[first] == '[') &&
      file.find('\n') != std::string::npos)
    throw InputError(fmt::format("'{}…' ({} characters): the text of a JSON document, not a file's path; accepted: "
                                 "the path of {} (the text written to a file first)",
                                 file[first], file.size(), accepted));
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw InputError(fmt::format("{}: it is a folder; accepted: {}", file, accepted));
  if (!std::filesystem::exists(file, ec))
    throw InputError(fmt::format("{}: no such file; accepted: {} (check its spelling and folder)", file, accepted));
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read it; accepted: {}", file, accepted));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Runs `write` on the store at `path`. A store that does not exist yet is built in a temporary file beside it
// and linked into place (a hard link: it fails rather than replace a store another process made meanwhile)
// only once `write` has succeeded, so that a refused first add or import leaves no file behind; when another
// process made the store meanwhile, `write` runs again on that one.
void write_store(const std::string& path, const std::function<void(HistoryStore&)>& write) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(path, ec)) {
    HistoryStore store = HistoryStore::open(path, HistoryStore::Access::write);
    write(store);
    return;
  }
  const fs::path folder = fs::path(path).parent_path();
  if (!folder.empty()) fs::create_directories(folder, ec);
  const std::string temporary = fmt::format("{}.{:016x}.new", path, std::random_device()() * 0x9e3779b97f4a7c15ULL);
  const auto remove_temporary = [&] {
    for (const char* suffix : {"", "-journal", "-wal", "-shm"}) fs::remove(temporary + suffix, ec);
  };
  try {
    HistoryStore store = HistoryStore::open(temporary, HistoryStore::Access::create, kHistoryBusyMillis, path);
    write(store);
  } catch (...) {
    remove_temporary();
    throw;
  }
  fs::create_hard_link(temporary, path, ec);
  const bool placed = !ec;
  if (ec && !fs::exists(path)) {  // a file system without hard links: renamed, as nothing is there to replace
    fs::rename(temporary, path, ec);
    if (ec) {
      remove_temporary();
      throw InputError(fmt::format("{}: cannot create the history store ({}); accepted: a file (and folder) "
                                   "this user may write",
                                   path, ec.message()));
    }
    return;
  }
  remove_temporary();
  if (placed) return;
  HistoryStore store = HistoryStore::open(path, HistoryStore::Access::write);  // made meanwhile by another
  write(store);
}

bool superseded(const HistoryRecord& r) { return r.superseded_by || !r.superseded_reason.empty(); }

// The inputs a calibration charged at their tolerance, as far as sharing goes: ids, groups, correlations and
// effects (to 1e-9 of the largest: the same configuration's budget gives them bit for bit).
bool same_tolerances(const SharedPart& a, const SharedPart& b) {
  const auto charged = [](const SharedPart& p) {
    std::vector<const SharedInput*> out;
    for (const SharedInput& s : p.inputs)
      if (!s.measured) out.push_back(&s);
    return out;
  };
  const auto x = charged(a), y = charged(b);
  if (x.size() != y.size() || a.correlations.size() != b.correlations.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i]->id != y[i]->id || x[i]->group != y[i]->group || x[i]->effect.size() != y[i]->effect.size())
      return false;
    for (const auto& [k, e] : x[i]->effect) {
      const auto other = y[i]->effect.find(k);
      if (other == y[i]->effect.end() ||
          std::abs(other->second - e) > 1e-9 * std::max(std::abs(e), std::abs(other->second)))
        return false;
    }
  }
  for (std::size_t i = 0; i < a.correlations.size(); ++i)
    if (a.correlations[i].first != b.correlations[i].first ||
        a.correlations[i].second != b.correlations[i].second || a.correlations[i].r != b.correlations[i].r)
      return false;
  return true;
}

// Which set-up each record is on, and where it changes between successive calibrations in force.
void describe_setups(HistoryShowResult& r) {
  const HistoryRecord* previous = nullptr;
  for (const HistoryRecord& rec : r.records) {
    int index = -1;
    if (rec.shared) {
      const auto it = std::find(r.setups.begin(), r.setups.end(), rec.shared->setup_sha256);
      index = int(it - r.setups.begin());
      if (it == r.setups.end()) r.setups.push_back(rec.shared->setup_sha256);
    }
    r.setup_of.push_back(index);
    if (superseded(rec)) continue;
    if (previous) {
      SetupChange c{previous->id, rec.id, previous->date, rec.date, false, false, false};
      c.unknown = !previous->shared || !rec.shared;
      c.setup = !c.unknown && previous->shared->setup_sha256 != rec.shared->setup_sha256;
      c.tolerances = !c.unknown && !c.setup && !same_tolerances(*previous->shared, *rec.shared);
      if (c.unknown || c.setup || c.tolerances) r.changes.push_back(c);
    }
    previous = &rec;
  }
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

std::int64_t history_record_id(const std::string& text) {
  std::int64_t id = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, id);
  if (ec == std::errc() && ptr == end && id >= 1) return id;
  throw InputError(fmt::format("ID: {} is not a calibration id; accepted: a whole number from 1, as `ccal "
                               "history show SERIAL` lists them (#3 is 3)",
                               detail::history_shown(text)));
}

std::string history_export(const std::string& serial, const HistoryStoreOptions& o) {
  return export_history(HistoryStore::open(history_store_path(o.db), HistoryStore::Access::read), serial);
}

HistoryImport history_import(const std::string& file, const HistoryStoreOptions& o) {
  const std::string text = read_history_file(file, "an exported history file (`ccal history export`)");
  std::error_code ec;
  if (std::filesystem::equivalent(file, history_store_path(o.db), ec))
    throw OptionError("db", history_store_path(o.db),
                      "is also the file imported; accepted: a history store other than the exported file");
  HistoryImport out;
  write_store(history_store_path(o.db), [&](HistoryStore& store) { out = import_history(store, text, file); });
  return out;
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
  write_store(r.db, [&](HistoryStore& store) {
    r.replaced.clear();
    store.add(r.entry, [&](std::int64_t id) {
      r.id = id;
      const std::vector<HistoryRecord> records = store.records(r.entry.serial);  // the transaction sees it
      r.calibrations = records.size();
      for (const HistoryRecord& rec : records)
        if (rec.superseded_by == id) r.replaced.push_back(rec.id);
      if (before_commit) before_commit(r);
    });
  });
  return r;
}

std::string setup_label(int index) { return index < 0 ? "?" : fmt::format("S{}", index + 1); }

HistoryListResult history_list(const HistoryStoreOptions& o) {
  HistoryListResult r;
  r.db = history_store_path(o.db);
  r.serials = HistoryStore::open(r.db, HistoryStore::Access::read).summaries();
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
  describe_setups(r);
  // Per coefficient, in the order of the first calibration that has it; time in years from the first date.
  const std::int64_t origin = history_day(r.records.front().date, "date");
  std::map<std::string, std::size_t> index;
  std::map<std::string, std::vector<const std::optional<SharedPart>*>> shared_of;
  for (const HistoryRecord& rec : r.records) {
    if (superseded(rec)) continue;
    const double years = double(history_day(rec.date, "date") - origin) / kDaysPerYear;
    for (const HistoryCoefficient& c : rec.coefficients) {
      auto [it, fresh] = index.try_emplace(c.name, r.coefficients.size());
      if (fresh) r.coefficients.push_back({c.name, c.unit, {}, {}, {}, {}, {}, {}, {}});
      CoefficientHistory& h = r.coefficients[it->second];
      if (c.unit != h.unit)
        throw InputError(
            fmt::format("{}: {} of '{}' is in {} on {} but in {} on {}; the history compares values "
                        "of one unit; accepted: statements of one configuration's units",
                        r.db, c.name, serial, h.unit, h.dates.front(), c.unit, rec.date));
      h.dates.push_back(rec.date);
      h.ids.push_back(rec.id);
      h.points.push_back({years, c.value, c.expanded, c.coverage_factor});
      shared_of[c.name].push_back(&rec.shared);
    }
  }
  for (CoefficientHistory& h : r.coefficients) {
    h.shared = shared_covariance_matrix(shared_of[h.name], h.name);
    h.agreement = normalised_errors(h.points, h.shared);
    h.drift = drift_line(h.points, h.shared);
    if (predicting && h.drift.available)
      h.prediction = predict(h.drift, double(at_day - origin) / kDaysPerYear);
  }
  return r;
}

}  // namespace ccal::verbs
