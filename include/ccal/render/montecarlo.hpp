#pragma once
// The reports of `ccal montecarlo` (docs/cli.md): text, JSON and CSV (one row per coefficient).
#include <string>

#include "ccal/verbs/montecarlo.hpp"

namespace ccal::render {

std::string text(const verbs::MonteCarloResult& result);
std::string json(const verbs::MonteCarloResult& result);
std::string csv(const verbs::MonteCarloResult& result);

}  // namespace ccal::render
