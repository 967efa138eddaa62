#pragma once
// The reports of `ccal force` (docs/cli.md): text tables, JSON, and CSV (the first-order breakdown of IA beside
// the exact input).
#include <string>

#include "ccal/verbs/force.hpp"

namespace ccal::render {

std::string text(const verbs::ForceResult& result);
std::string json(const verbs::ForceResult& result);
std::string csv(const verbs::ForceResult& result);

}  // namespace ccal::render
