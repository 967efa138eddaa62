#include "ccal/render/table.hpp"

#include <algorithm>
#include <cstdint>

namespace ccal::render {
namespace {

// One decoded UTF-8 character: its code point (U+FFFD for an invalid byte) and its length in bytes.
struct Decoded {
  std::uint32_t code = 0xFFFD;
  std::size_t length = 1;
};

Decoded decode(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b = byte(i);
  if (b < 0x80) return {b, 1};
  const std::size_t n = (b & 0xE0) == 0xC0 ? 2 : (b & 0xF0) == 0xE0 ? 3 : (b & 0xF8) == 0xF0 ? 4 : 0;
  if (n == 0 || i + n > s.size()) return {};
  std::uint32_t code = b & (0x7F >> n);
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return {};
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  return {code, n};
}

// Zero-width: combining marks (the blocks most text uses) and the zero-width space and joiners.
bool zero_width(std::uint32_t c) {
  return (c >= 0x0300 && c <= 0x036F) || (c >= 0x1AB0 && c <= 0x1AFF) || (c >= 0x1DC0 && c <= 0x1DFF) ||
         (c >= 0x20D0 && c <= 0x20FF) || (c >= 0xFE20 && c <= 0xFE2F) || (c >= 0x200B && c <= 0x200F) ||
         c == 0xFE0F;
}

// East Asian wide and full-width characters (Unicode's W and F classes, in blocks), two columns each.
bool wide(std::uint32_t c) {
  return (c >= 0x1100 && c <= 0x115F) || (c >= 0x2E80 && c <= 0x303E) || (c >= 0x3041 && c <= 0x33FF) ||
         (c >= 0x3400 && c <= 0x4DBF) || (c >= 0x4E00 && c <= 0x9FFF) || (c >= 0xA000 && c <= 0xA4CF) ||
         (c >= 0xAC00 && c <= 0xD7A3) || (c >= 0xF900 && c <= 0xFAFF) || (c >= 0xFE30 && c <= 0xFE4F) ||
         (c >= 0xFF00 && c <= 0xFF60) || (c >= 0xFFE0 && c <= 0xFFE6) || (c >= 0x1F300 && c <= 0x1F64F) ||
         (c >= 0x1F900 && c <= 0x1F9FF) || (c >= 0x20000 && c <= 0x3FFFD);
}

std::size_t char_width(std::uint32_t c) { return zero_width(c) ? 0 : wide(c) ? 2 : 1; }

}  // namespace

std::size_t display_width(std::string_view text) {
  std::size_t width = 0;
  for (std::size_t i = 0; i < text.size();) {
    const Decoded d = decode(text, i);
    width += char_width(d.code);
    i += d.length;
  }
  return width;
}

std::string truncate_to_width(std::string_view text, std::size_t width) {
  if (display_width(text) <= width) return std::string(text);
  if (width == 0) return "";
  std::size_t used = 0, end = 0;
  for (std::size_t i = 0; i < text.size();) {
    const Decoded d = decode(text, i);
    const std::size_t w = char_width(d.code);
    if (used + w > width - 1) break;  // one column for the ellipsis
    used += w;
    i += d.length;
    end = i;
  }
  while (end > 0 && text[end - 1] == ' ') --end;
  return std::string(text.substr(0, end)) + "…";
}

std::string pad_to_width(std::string_view text, std::size_t width, bool align_left) {
  const std::size_t w = display_width(text);
  const std::string pad(w < width ? width - w : 0, ' ');
  return align_left ? std::string(text) + pad : pad + std::string(text);
}

std::string wrap_words(std::string_view text, std::size_t width, std::string_view indent) {
  if (width == 0) return std::string(text) + "\n";
  std::string out, line;
  bool fresh = true;  // nothing but the indent on the line yet
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t start = text.find_first_not_of(' ', i);
    if (start == std::string_view::npos) break;
    const std::size_t end = std::min(text.find(' ', start), text.size());
    const std::string_view word = text.substr(start, end - start);
    if (!fresh && display_width(line) + 1 + display_width(word) > width) {
      out += line + "\n";
      line = std::string(indent);
      fresh = true;
    }
    if (!fresh) line += ' ';
    // Leading spaces of the paragraph are kept (an indented first line).
    if (out.empty() && line.empty()) line = std::string(text.substr(0, start));
    line += word;
    fresh = false;
    i = end;
  }
  return out + line + "\n";
}

std::vector<std::size_t> Table::widths(std::size_t indent, std::size_t max_width) const {
  std::vector<std::size_t> width(header_.size(), 0);
  // A cell wider than kMaxPaddedWidth does not widen its column (it is printed whole, past the column's end):
  // one 10 MB run name would otherwise pad every row of the table to 10 MB.
  auto measure = [&](const std::vector<std::string>& row, bool span) {
    for (std::size_t c = span ? 1 : 0; c < row.size() && c + (span ? 1 : 0) < width.size(); ++c) {
      const std::size_t w = display_width(row[c]);
      if (w <= kMaxPaddedWidth) width[c + (span ? 1 : 0)] = std::max(width[c + (span ? 1 : 0)], w);
    }
  };
  for (std::size_t c = 0; c < header_.size(); ++c)
    width[c] = std::min(display_width(header_[c]), kMaxPaddedWidth);
  for (std::size_t r = 0; r < rows_.size(); ++r) measure(rows_[r], spans_[r]);
  if (max_width == 0 || shrink_ >= width.size()) return width;
  const auto total = [&] {
    std::size_t sum = indent, shown = 0;
    for (std::size_t w : width)
      if (w != kLeftOut) sum += w, ++shown;
    return sum + gap_ * (shown > 0 ? shown - 1 : 0);
  };
  if (total() <= max_width) return width;
  // Cut the shrinkable column by the excess, down to its header's width; if that is not enough, leave the
  // optional column out and cut the shrinkable one by what is still in excess.
  const std::size_t natural = width[shrink_];
  const std::size_t floor = std::max<std::size_t>(display_width(header_[shrink_]), 4);
  const auto cut = [&] {
    const std::size_t excess = total() - max_width;
    if (width[shrink_] > floor)
      width[shrink_] = width[shrink_] > floor + excess ? width[shrink_] - excess : floor;
  };
  cut();
  if (total() > max_width && optional_ > 1 && optional_ < width.size() && optional_ != shrink_) {
    width[optional_] = kLeftOut;
    width[shrink_] = natural;
    if (total() > max_width) cut();
  }
  return width;
}

std::string Table::render(std::string_view indent, std::size_t max_width) const {
  const std::vector<std::size_t> width = widths(display_width(indent), max_width);
  std::size_t total = 0, shown = 0;
  for (std::size_t w : width)
    if (w != kLeftOut) total += w, ++shown;
  total += gap_ * (shown > 0 ? shown - 1 : 0);
  const std::string gap(gap_, ' ');

  std::string out;
  auto line = [&](const std::vector<std::string>& row, bool span) {
    std::string text(indent);
    std::size_t first = 0;
    if (span && width.size() > 1) {  // the label over the first two columns
      const std::size_t w = width[0] + gap_ + width[1];
      text += pad_to_width(truncate_to_width(row.empty() ? "" : row[0], w), w, true);
      first = 2;
    }
    for (std::size_t c = first; c < width.size(); ++c) {
      if (width[c] == kLeftOut) continue;
      const std::size_t k = span && first == 2 ? c - 1 : c;  // the cell for column c
      std::string cell = k < row.size() ? row[k] : "";
      if (c == shrink_) cell = truncate_to_width(cell, width[c]);
      if (c > 0) text += gap;
      const bool left = c == 0 || std::find(left_.begin(), left_.end(), c) != left_.end();
      text += pad_to_width(cell, width[c], left);
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out += text + '\n';
  };
  line(header_, false);
  out += std::string(indent) + std::string(total, '-') + '\n';
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    if (rows_[r].empty())
      out += std::string(indent) + std::string(total, '-') + '\n';
    else
      line(rows_[r], spans_[r]);
  }
  return out;
}

}  // namespace ccal::render
