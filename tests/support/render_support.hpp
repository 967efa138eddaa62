#pragma once
// Shared by the in-process tests of the renderers (tests/render/): a rendered text's lines, the line holding a
// phrase, the cells of a table's row, and a CSV's rows, so that a test asserts what a reader sees.
#include <gtest/gtest.h>

#include <cstddef>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace ccal::test {

inline std::vector<std::string> rendered_lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// The first line that starts with `head` (after its indentation); nullopt when none does.
// The text's words in order, its line breaks and indents gone (renderers wrap at a width).
inline std::string words_of(const std::string& text) {
  std::string out;
  for (const std::string& l : rendered_lines(text)) {
    const auto first = l.find_first_not_of(' ');
    if (first == std::string::npos) continue;
    if (!out.empty()) out += ' ';
    out.append(l, first);
  }
  return out;
}

inline std::optional<std::string> line_starting(const std::string& text, const std::string& head) {
  for (const std::string& l : rendered_lines(text)) {
    const auto first = l.find_first_not_of(' ');
    if (first != std::string::npos && l.compare(first, head.size(), head) == 0) return l;
  }
  return std::nullopt;
}

// How many lines hold `needle`.
inline std::size_t lines_holding(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (const std::string& l : rendered_lines(text)) n += l.find(needle) != std::string::npos;
  return n;
}

// The words of a line, split at runs of two or more spaces (a text table's cells; a cell may hold one space).
inline std::vector<std::string> table_cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::size_t spaces = 0;
  for (char c : line) {
    if (c == ' ') {
      ++spaces;
      continue;
    }
    if (spaces >= 2 && !cell.empty()) {
      out.push_back(cell);
      cell.clear();
    } else if (spaces == 1 && !cell.empty()) {
      cell += ' ';
    }
    spaces = 0;
    cell += c;
  }
  if (!cell.empty()) out.push_back(cell);
  return out;
}

// The comma-separated fields of a CSV line (no quoting: the renderers' numeric rows).
inline std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  for (char c : line) {
    if (c == ',') {
      out.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  out.push_back(field);
  return out;
}

}  // namespace ccal::test
