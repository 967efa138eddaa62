#pragma once
// The reports of `ccal budget` (docs/cli.md): text (the answer per coefficient, then a JCGM 100 table per
// coefficient), JSON, and CSV (one row per source, then the totals).
#include <cstddef>
#include <string>

#include "ccal/verbs/budget.hpp"

namespace ccal::render {

// How the text is laid out. The defaults are those of `ccal budget` writing to a file or a pipe.
struct BudgetTextOptions {
  std::size_t width = 100;       // no line wider than this (displayed characters), where a name can give way
  std::size_t top = 0;           // sources listed per coefficient, the rest summed in one row; 0: what fits
  std::size_t screen_rows = 60;  // the screen `top = 0` fills
  bool wide = false;  // every source, uncut names, exact-vs-paper flags, paths, compensation, observability
};

std::string text(const verbs::BudgetResult& result, const BudgetTextOptions& options = {});
std::string json(const verbs::BudgetResult& result);
std::string csv(const verbs::BudgetResult& result);

}  // namespace ccal::render
