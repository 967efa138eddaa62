#pragma once
// A serial number's calibration history as one JSON file, to move it between stores (`ccal history export`,
// `ccal history import`; docs/cli.md):
//     {"format": "ccal calibration history", "schema": 1, "serial": S,
//      "calibrations": [{"id", "date", "instrument", "ccal_version", "config", "added_at", "statement": {…},
//                        "superseded": {"by": id or null, "reason"} (only where superseded)}, …]}
// ids are those of the exporting store; importing maps them to the new store's. A statement already in the
// store (the same text) is not added again, so importing a file twice changes nothing.

#include <cstddef>
#include <string>

#include "ccal/history/history_store.hpp"

namespace ccal {

// The JSON text of every calibration of `serial` in the store (InputError if it has none).
std::string export_history(const HistoryStore& store, const std::string& serial);

struct HistoryImport {
  std::string serial;
  std::size_t added = 0;       // calibrations recorded
  std::size_t present = 0;     // already in the store
  std::size_t superseded = 0;  // supersessions recorded
};

// Records the calibrations of an exported file (`source` names it in messages); InputError for text that is
// no such file (naming what is wrong and what would be accepted).
HistoryImport import_history(HistoryStore& store, const std::string& json_text, const std::string& source);

}  // namespace ccal
