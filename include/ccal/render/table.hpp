#pragma once
// Text tables and numbers as every text report prints them: aligned columns (the first left-aligned, the
// others right-aligned), rules of dashes, and numbers with a chosen count of significant digits.

#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/format.hpp"

namespace ccal::render {

using ccal::number;

// A text table: a header row, then rows of cells; columns after the first are right-aligned.
class Table {
 public:
  explicit Table(std::vector<std::string> header) : header_(std::move(header)) {}
  void add_row(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }
  void add_rule() { rows_.emplace_back(); }  // a line of dashes
  // Each line starts with `indent`.
  std::string render(std::string_view indent = "  ") const;

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

}  // namespace ccal::render
