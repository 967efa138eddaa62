#pragma once
// Text tables and numbers as every text report prints them: aligned columns (the first left-aligned, the
// others right-aligned unless told), rules of dashes, and numbers with a chosen count of significant digits.
// Widths are measured in displayed characters (UTF-8 code points; combining marks take none, East Asian wide
// characters two), so that "µm" or a run named "Läufe" keeps its column.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/format.hpp"

namespace ccal::render {

using ccal::number;

// Columns a UTF-8 text takes on a terminal (invalid bytes count one each).
std::size_t display_width(std::string_view text);
// The longest prefix of text of at most `width` displayed characters, ending in "…" when text was cut.
std::string truncate_to_width(std::string_view text, std::size_t width);
// text padded with spaces to `width` displayed characters, on the right (left-aligned) or on the left.
std::string pad_to_width(std::string_view text, std::size_t width, bool align_left);

// A paragraph broken at spaces into lines of at most `width` displayed characters (a word longer than that
// stays whole), the lines after the first starting with `indent`; each line ends in a newline. width 0: one
// line.
std::string wrap_words(std::string_view text, std::size_t width, std::string_view indent = "");

// The widest a column is padded to: a cell (or header) wider than this is printed whole but does not widen
// its column, so that one huge cell (a run named with megabytes of text) does not pad every other row.
inline constexpr std::size_t kMaxPaddedWidth = 80;

// A text table: a header row, then rows of cells; columns after the first are right-aligned.
class Table {
 public:
  explicit Table(std::vector<std::string> header) : header_(std::move(header)) {}
  void add_row(std::vector<std::string> cells) {
    rows_.push_back(std::move(cells));
    spans_.push_back(false);
  }
  // A row whose first cell spans the first two columns (a label such as "u: combined standard
  // uncertainty"), cut to their width; the other cells fill columns 2, 3, …
  void add_spanning_row(std::vector<std::string> cells) {
    rows_.push_back(std::move(cells));
    spans_.push_back(true);
  }
  void add_rule() {  // a line of dashes
    rows_.emplace_back();
    spans_.push_back(false);
  }
  // Cells of this column are left-aligned (the first column always is).
  void align_left(std::size_t column) { left_.push_back(column); }
  // This column gives way when the table is wider than render's max_width: its cells are cut (ending in
  // "…") down to the width of its header, at the least.
  void shrink(std::size_t column) { shrink_ = column; }
  // This column is left out (header, cells and its gap) when the table, its shrinkable column cut down, is
  // still wider than render's max_width: for a column the others imply (a budget's divisor). Not one of the
  // first two columns (a spanning row's label covers them).
  void optional(std::size_t column) { optional_ = column; }
  // Spaces between columns (default 3).
  void gap(std::size_t spaces) { gap_ = spaces; }
  // Each line starts with `indent`; max_width > 0 bounds the lines (in displayed characters) by cutting the
  // shrinkable column, if there is one.
  std::string render(std::string_view indent = "  ", std::size_t max_width = 0) const;

 private:
  // Each column's width; kLeftOut for an optional column left out.
  static constexpr std::size_t kLeftOut = std::size_t(-1);
  std::vector<std::size_t> widths(std::size_t indent, std::size_t max_width) const;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
  std::vector<bool> spans_;  // per row: its first cell spans two columns
  std::vector<std::size_t> left_;
  std::size_t shrink_ = std::size_t(-1);
  std::size_t optional_ = std::size_t(-1);
  std::size_t gap_ = 3;
};

}  // namespace ccal::render
