#include "ccal/render/table.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace ccal::render {

std::string Table::render(std::string_view indent) const {
  std::vector<std::size_t> width(header_.size(), 0);
  auto measure = [&](const std::vector<std::string>& row) {
    for (std::size_t c = 0; c < row.size() && c < width.size(); ++c)
      width[c] = std::max(width[c], row[c].size());
  };
  measure(header_);
  for (const auto& row : rows_) measure(row);
  std::size_t total = 0;
  for (std::size_t w : width) total += w;
  total += 3 * (width.size() - 1);

  std::string out;
  auto line = [&](const std::vector<std::string>& row) {
    std::string text(indent);
    for (std::size_t c = 0; c < width.size(); ++c) {
      const std::string cell = c < row.size() ? row[c] : "";
      if (c > 0) text += "   ";
      text += c == 0 ? fmt::format("{:<{}}", cell, width[c]) : fmt::format("{:>{}}", cell, width[c]);
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out += text + '\n';
  };
  line(header_);
  out += std::string(indent) + std::string(total, '-') + '\n';
  for (const auto& row : rows_) {
    if (row.empty())
      out += std::string(indent) + std::string(total, '-') + '\n';
    else
      line(row);
  }
  return out;
}

}  // namespace ccal::render
