#pragma once
// The reports of `ccal budget` (docs/cli.md): a ranked text table, JSON, and CSV (one row per source).
#include <string>

#include "ccal/verbs/budget.hpp"

namespace ccal::render {

std::string text(const verbs::BudgetResult& result);
std::string json(const verbs::BudgetResult& result);
std::string csv(const verbs::BudgetResult& result);

}  // namespace ccal::render
