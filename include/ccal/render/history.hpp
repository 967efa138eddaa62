#pragma once
// The reports of `ccal history` (docs/cli.md): what `add` recorded, and a serial's calibrations with the
// agreement of successive ones (E_n), the drift line and its prediction, which set-up each is on and where it
// changes, as text, JSON and CSV; the store's serial numbers (`list`).
#include <string>

#include "ccal/verbs/history.hpp"

namespace ccal::render {

std::string text(const verbs::HistoryAddResult& result);
std::string json(const verbs::HistoryAddResult& result);

std::string text(const verbs::HistoryShowResult& result);
std::string json(const verbs::HistoryShowResult& result);
// One row per calibration and coefficient: date, value, U, k, p, ν_eff, and E_n against the previous one.
std::string csv(const verbs::HistoryShowResult& result);

// `ccal history list`: per serial number its calibrations, superseded ones and last date.
std::string text(const verbs::HistoryListResult& result);
std::string json(const verbs::HistoryListResult& result);
std::string csv(const verbs::HistoryListResult& result);

}  // namespace ccal::render
