#pragma once
// The reports of `ccal history` (docs/cli.md): what `add` recorded, and a serial's calibrations with the
// agreement of successive ones (E_n), the drift line and its prediction, as text, JSON and CSV.
#include <string>

#include "ccal/verbs/history.hpp"

namespace ccal::render {

std::string text(const verbs::HistoryAddResult& result);
std::string json(const verbs::HistoryAddResult& result);

std::string text(const verbs::HistoryShowResult& result);
std::string json(const verbs::HistoryShowResult& result);
// One row per calibration and coefficient: date, value, U, k, p, ν_eff, and E_n against the previous one.
std::string csv(const verbs::HistoryShowResult& result);

}  // namespace ccal::render
