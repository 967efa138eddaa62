#include "ccal/history/history_exchange.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "history_shared_json.hpp"

namespace ccal {

namespace {

constexpr const char* kFormat = "ccal calibration history";

// A file that is no export: what is wrong, and what would be accepted.
[[noreturn]] void refuse(const std::string& source, const std::string& what) {
  throw InputError(
      fmt::format("{}: not an exported calibration history: {}; accepted: a serial number's history as "
                  "exported (\"format\": \"ccal calibration history\")",
                  source, what));
}

// One calibration of the file, read.
struct Item {
  std::int64_t old_id = 0;
  HistoryEntry entry;
  const nlohmann::json* superseded = nullptr;  // its "superseded", if not absent or null
};

// Every entry, read before anything is recorded, so that a bad one adds nothing.
std::vector<Item> read_items(const nlohmann::json& j, const std::string& serial, const std::string& source) {
  std::vector<Item> items;
  for (std::size_t i = 0; i < j["calibrations"].size(); ++i) {
    const nlohmann::json& c = j["calibrations"][i];
    const std::string where = fmt::format("{}: calibrations[{}]", source, i);
    if (!c.is_object() || !c["id"].is_number_integer() || !c["date"].is_string() || !c.contains("statement"))
      refuse(source, fmt::format("calibrations[{}] has no \"id\", \"date\" and \"statement\"", i));
    Item item;
    item.old_id = c["id"].get<std::int64_t>();
    // Supersessions name calibrations by id: two entries of one id would attach one to the wrong calibration.
    for (std::size_t k = 0; k < items.size(); ++k)
      if (items[k].old_id == item.old_id)
        throw InputError(fmt::format(
            "{}: calibrations[{}] has the id {} of calibrations[{}]; accepted: each calibration's own id, as "
            "`ccal history export` writes them",
            source, i, item.old_id, k));
    try {
      item.entry = history_entry(c["statement"].dump(), where, serial, c["date"].get<std::string>());
    } catch (const OptionError& e) {  // the file's "serial" (or the entry's "date") stands for the option
      const std::string key = e.field() == "date" ? fmt::format("calibrations[{}].date", i) : "serial";
      throw InputError(fmt::format("{}: \"{}\" {} {}", source, key, e.value(), e.problem()));
    }
    item.entry.instrument = c.value("instrument", item.entry.instrument);
    item.entry.ccal_version = c.value("ccal_version", item.entry.ccal_version);
    item.entry.config = c.value("config", item.entry.config);
    item.entry.replaces.clear();  // the file carries its supersessions, recorded below
    if (c.contains("superseded") && !c["superseded"].is_null()) item.superseded = &c["superseded"];
    items.push_back(std::move(item));
  }
  return items;
}

// The supersessions of the file: per superseded record (old id) its "by", and the order to record them in.
struct Supersessions {
  std::map<std::int64_t, std::optional<std::int64_t>> by_of;
  std::vector<const Item*> order;
};

// Every "by" names a calibration of the file (not the superseded one itself). A record is superseded only by
// one in force, so the supersessions are recorded in an order where none names a record superseded before
// it (X by Y before Y's own), and refused when they go round in a circle.
Supersessions supersessions_of(const std::vector<Item>& items, const std::string& source) {
  Supersessions out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (!items[i].superseded) continue;
    const nlohmann::json& sup = *items[i].superseded;
    if (!sup.is_object() || (sup.contains("by") && !sup["by"].is_null() && !sup["by"].is_number_integer()))
      refuse(source,
             fmt::format("calibrations[{}]: \"superseded\" is not {{\"by\": id or null, \"reason\"}}", i));
    if (sup.contains("reason") &&
        !(sup["reason"].is_string() && sup["reason"].get<std::string>().find_first_not_of(" \t\n\r\f\v") !=
                                           std::string::npos))
      refuse(source, fmt::format("calibrations[{}]: \"superseded\" \"reason\" {} is not a reason (text, not "
                                 "blank)",
                                 i, sup["reason"].dump()));
    std::optional<std::int64_t> by;
    if (sup.contains("by") && sup["by"].is_number_integer()) {
      by = sup["by"].get<std::int64_t>();
      const bool known =
          std::any_of(items.begin(), items.end(), [&](const Item& x) { return x.old_id == *by; });
      if (!known || *by == items[i].old_id)
        throw InputError(fmt::format(
            "{}: calibrations[{}] (id {}) is superseded by {}, {}; accepted: the \"id\" of another "
            "calibration in the file, or null",
            source, i, items[i].old_id, *by, known ? "itself" : "which names no calibration in the file"));
    }
    out.by_of[items[i].old_id] = by;
  }
  std::map<std::int64_t, bool> placed;
  while (out.order.size() < out.by_of.size()) {
    const std::size_t before = out.order.size();
    for (const Item& item : items) {
      if (!item.superseded || placed[item.old_id]) continue;
      // Ready when no supersession still to record names this record as its "by".
      const bool named = std::any_of(out.by_of.begin(), out.by_of.end(), [&](const auto& kv) {
        return !placed[kv.first] && kv.second == item.old_id;
      });
      if (named) continue;
      out.order.push_back(&item);
      placed[item.old_id] = true;
    }
    if (out.order.size() == before)
      throw InputError(
          fmt::format("{}: the supersessions go round in a circle (each record superseded by one superseded "
                      "in turn); accepted: supersessions that end in a record in force",
                      source));
  }
  return out;
}

}  // namespace

std::string export_history(const HistoryStore& store, const std::string& serial) {
  const std::vector<HistoryRecord> records = store.records(serial);
  if (records.empty())
    throw InputError(
        fmt::format("{}: no calibration of '{}' to export; accepted: a serial number recorded in it",
                    store.path(), serial));
  nlohmann::ordered_json j;
  j["format"] = kFormat;
  j["schema"] = kHistorySchemaVersion;
  j["serial"] = serial;
  j["calibrations"] = nlohmann::ordered_json::array();
  for (const HistoryRecord& r : records) {
    nlohmann::ordered_json c{{"id", r.id},
                             {"date", r.date},
                             {"instrument", r.instrument},
                             {"ccal_version", r.ccal_version},
                             {"config", r.config},
                             {"added_at", r.added_at},
                             {"statement", nlohmann::ordered_json::parse(r.statement_json)}};
    if (!r.superseded_reason.empty())
      c["superseded"] = {{"by", r.superseded_by ? nlohmann::ordered_json(*r.superseded_by) : nullptr},
                         {"reason", r.superseded_reason}};
    j["calibrations"].push_back(c);
  }
  return j.dump(2) + "\n";
}

HistoryImport import_history(HistoryStore& store, const std::string& json_text, const std::string& source) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::exception& e) {
    refuse(source, fmt::format("not JSON ({})", detail::json_problem(e.what())));
  }
  if (!j.is_object() || j.value("format", std::string()) != kFormat)
    refuse(source, "no \"format\": \"ccal calibration history\"");
  if (!j["schema"].is_number_integer() || j["schema"].get<int>() > kHistorySchemaVersion)
    refuse(source, fmt::format("schema {} (this ccal reads {} and older)", j["schema"].dump(),
                               kHistorySchemaVersion));
  if (!j["serial"].is_string() || !j["calibrations"].is_array())
    refuse(source, "no \"serial\" and \"calibrations\"");
  // `ccal history export` writes at least one: an empty list would make an empty store, importing nothing.
  if (j["calibrations"].empty()) refuse(source, "no calibration in its \"calibrations\"");
  HistoryImport out;
  out.serial = j["serial"].get<std::string>();
  const std::vector<Item> items = read_items(j, out.serial, source);
  const Supersessions supersessions = supersessions_of(items, source);
  std::map<std::int64_t, std::int64_t> new_id;
  std::map<std::int64_t, bool> was_present;
  // One transaction: a calibration the store refuses (another unit than the serial's records) adds nothing.
  store.transaction([&] {
    for (const Item& item : items) {
      const std::optional<std::int64_t> known = store.id_of_statement(item.entry.statement_json);
      was_present[item.old_id] = known.has_value();
      new_id[item.old_id] = known ? *known : store.add(item.entry);
      ++(known ? out.present : out.added);
    }
    for (const Item* item : supersessions.order) {
      if (was_present[item->old_id]) continue;  // a record present keeps its own state
      const std::optional<std::int64_t> by = supersessions.by_of.at(item->old_id);
      store.supersede(new_id[item->old_id], by ? std::optional<std::int64_t>(new_id[*by]) : std::nullopt,
                      item->superseded->value("reason", std::string("imported")));
      ++out.superseded;
    }
  });
  return out;
}

}  // namespace ccal
