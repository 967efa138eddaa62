#pragma once
// The reports of `ccal montecarlo` (docs/cli.md): text, JSON and CSV (one row per coefficient).
#include <string>
#include <vector>

#include "ccal/verbs/montecarlo.hpp"

namespace ccal::render {

std::string text(const verbs::MonteCarloResult& result);
std::string json(const verbs::MonteCarloResult& result);
std::string csv(const verbs::MonteCarloResult& result);
// Per coefficient: empty when the LPU was validated, else one sentence saying whether the sampling error of
// the interval ends explains the failure and what to run (the text output prints the non-empty ones).
std::vector<std::string> validation_advice_lines(const verbs::MonteCarloResult& result);

}  // namespace ccal::render
