#include "ccal/io/history_exchange.hpp"

#include <fmt/format.h>

#include <map>
#include <nlohmann/json.hpp>

#include "ccal/core/errors.hpp"

namespace ccal {

namespace {
constexpr const char* kFormat = "ccal calibration history";
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
  const auto refuse = [&](const std::string& what) {
    throw InputError(
        fmt::format("{}: not an exported calibration history: {}; accepted: a serial number's history as "
                    "exported (\"format\": \"ccal calibration history\")",
                    source, what));
  };
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::exception& e) {
    refuse(fmt::format("not JSON ({})", e.what()));
  }
  if (!j.is_object() || j.value("format", std::string()) != kFormat)
    refuse("no \"format\": \"ccal calibration history\"");
  if (!j["schema"].is_number_integer() || j["schema"].get<int>() > kHistorySchemaVersion)
    refuse(
        fmt::format("schema {} (this ccal reads {} and older)", j["schema"].dump(), kHistorySchemaVersion));
  if (!j["serial"].is_string() || !j["calibrations"].is_array()) refuse("no \"serial\" and \"calibrations\"");
  HistoryImport out;
  out.serial = j["serial"].get<std::string>();
  // Every entry read first, so that a bad one adds nothing.
  struct Item {
    std::int64_t old_id = 0;
    HistoryEntry entry;
    const nlohmann::json* superseded = nullptr;
  };
  std::vector<Item> items;
  for (std::size_t i = 0; i < j["calibrations"].size(); ++i) {
    const nlohmann::json& c = j["calibrations"][i];
    const std::string where = fmt::format("{}: calibrations[{}]", source, i);
    if (!c.is_object() || !c["id"].is_number_integer() || !c["date"].is_string() || !c.contains("statement"))
      refuse(fmt::format("calibrations[{}] has no \"id\", \"date\" and \"statement\"", i));
    Item item;
    item.old_id = c["id"].get<std::int64_t>();
    item.entry = history_entry(c["statement"].dump(), where, out.serial, c["date"].get<std::string>());
    item.entry.instrument = c.value("instrument", item.entry.instrument);
    item.entry.ccal_version = c.value("ccal_version", item.entry.ccal_version);
    item.entry.config = c.value("config", item.entry.config);
    if (c.contains("superseded")) item.superseded = &c["superseded"];
    items.push_back(std::move(item));
  }
  std::map<std::int64_t, std::int64_t> new_id;
  std::map<std::int64_t, bool> was_present;
  for (const Item& item : items) {
    const std::optional<std::int64_t> known = store.id_of_statement(item.entry.statement_json);
    was_present[item.old_id] = known.has_value();
    new_id[item.old_id] = known ? *known : store.add(item.entry);
    ++(known ? out.present : out.added);
  }
  for (const Item& item : items) {
    if (!item.superseded || was_present[item.old_id]) continue;  // a record present keeps its own state
    std::optional<std::int64_t> by;
    if ((*item.superseded)["by"].is_number_integer()) {
      const auto found = new_id.find((*item.superseded)["by"].get<std::int64_t>());
      if (found != new_id.end()) by = found->second;
    }
    store.supersede(new_id[item.old_id], by, item.superseded->value("reason", std::string("imported")));
    ++out.superseded;
  }
  return out;
}

}  // namespace ccal
