#pragma once
// The reports of `ccal simulate` (docs/cli.md): text tables, JSON, and CSV (the observations file).
#include <string>

#include "ccal/verbs/simulate.hpp"

namespace ccal::render {

std::string text(const verbs::SimulateResult& result);
std::string json(const verbs::SimulateResult& result);
std::string csv(const verbs::SimulateResult& result);

}  // namespace ccal::render
