// The configuration file's [[instruments]]: a test of several instruments on the platform (docs/config.md),
// each entry an [instrument] table with its id, its place on the base plane and its azimuth (model.md §4.2).
#include <cctype>
#include <cmath>
#include <set>

#include "../core/text_shown.hpp"
#include "config_reader.hpp"

namespace ccal::config_reading {

namespace {

// An id names an instrument's results, its logs' column in a manifest and its files: letters, digits, '_',
// '-' and '.', as a run's name.
bool valid_instrument_id(std::string_view id) {
  if (id.empty() || id.size() > 64) return false;
  for (const char c : id)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-' && c != '.') return false;
  return true;
}

// position = ["x5", "y5"]: two lengths on the working base plane (frame 4), from the platform axis.
void read_position(const Reader& r, const toml::table& t, const std::string& p, MountedInstrument& out) {
  const toml::node* n = t.get("position");
  if (!n) return;
  const std::string kp = Reader::path(p, "position");
  const toml::array* a = n->as_array();
  if (!a || a->size() != 2)
    r.fail(*n, kp,
           fmt::format("expected two lengths [x5, y5] on the base plane, got {}; accepted: e.g. "
                       "[\"0 m\", \"0.15 m\"]",
                       a ? fmt::format("an array of {}", a->size()) : std::string(type_name(*n))));
  double* place[] = {&out.x5, &out.y5};
  for (std::size_t k = 0; k < 2; ++k) {
    *place[k] = r.quantity_node(*a->get(k), fmt::format("{}[{}]", kp, k), kind::length, nullptr, "0.15 m");
    if (std::abs(*place[k]) > 10)
      r.fail(*a->get(k), fmt::format("{}[{}]", kp, k),
             "more than 10 m from the platform axis; accepted: a place on the platform, e.g. \"0.15 m\"");
  }
}

}  // namespace

std::vector<MountedInstrument> read_instruments(const Reader& r, const toml::table& root) {
  const toml::node* n = root.get("instruments");
  if (!n) return {};
  if (root.contains("instrument"))
    r.fail(*n, "instruments",
           "both [instrument] and [[instruments]]; accepted: one [instrument], or an [[instruments]] entry for "
           "each instrument of the test");
  const toml::array* entries = n->as_array();
  if (!entries || entries->empty() || !entries->is_array_of_tables())
    r.fail(*n, "instruments",
           "expected one [[instruments]] table per instrument, each with its id, e.g. [[instruments]] id = \"A\"");
  std::vector<MountedInstrument> out;
  std::set<std::string> seen;
  for (std::size_t k = 0; k < entries->size(); ++k) {
    const toml::table& t = *entries->get(k)->as_table();
    const std::string p = fmt::format("instruments[{}]", k + 1);
    Keys keys = kInstrumentKeys;
    keys.insert(keys.end(), kMountedInstrumentKeys.begin(), kMountedInstrumentKeys.end());
    r.check_keys(t, p, keys);
    MountedInstrument m;
    const auto id = r.string(t, p, "id");
    if (!id) r.fail(where(t.source()), Reader::path(p, "id"), "missing; each instrument needs an id, e.g. id = \"A\"");
    if (!valid_instrument_id(*id))
      r.fail(*t.get("id"), Reader::path(p, "id"),
             fmt::format("'{}' is not an id; accepted: 1 to 64 letters, digits, '_', '-' or '.'", *id));
    if (!seen.insert(*id).second)
      r.fail(*t.get("id"), Reader::path(p, "id"),
             fmt::format("'{}' names an earlier instrument too; accepted: an id of its own", *id));
    m.id = *id;
    // The entry is an [instrument] table besides its own keys (checked above), read as one; its messages name
    // this entry.
    m.model = read_instrument_table(r, t, p);
    read_position(r, t, p, m);
    m.azimuth5 = r.quantity(t, p, "azimuth", kind::angle, nullptr, "90 deg").value_or(0.0);
    if (const auto serial = r.string(t, p, "serial_number")) {
      if (serial->empty() || serial->find_first_not_of(" \t") == std::string::npos)
        r.fail(*t.get("serial_number"), Reader::path(p, "serial_number"),
               "is empty; accepted: the instrument's serial number as on its label, e.g. \"PIGA-0415\"");
      if (detail::has_control_character(*serial))
        r.fail(*t.get("serial_number"), Reader::path(p, "serial_number"),
               fmt::format("{} holds a control character; accepted: the instrument's serial number as on its "
                           "label, printable text on one line, e.g. \"PIGA-0415\"",
                           detail::shown_text(*serial, '\'')));
      m.serial_number = *serial;
      m.serial_line = t.get("serial_number")->source().begin.line;
    }
    m.line = t.source().begin.line;
    out.push_back(std::move(m));
  }
  return out;
}

}  // namespace ccal::config_reading
