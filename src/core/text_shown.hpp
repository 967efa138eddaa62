#pragma once
// Text a user gave, shown back in a message on one line (private to the library): a run's name, a serial
// number, a reason.
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <string_view>

namespace ccal::detail {

// A control character: a line break, a tab, any other below U+0020, or DEL.
inline bool is_control(char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }
inline bool has_control_character(std::string_view text) {
  return std::any_of(text.begin(), text.end(), is_control);
}

// `text` between two `quote`s, its control characters written as \n, \t or \xNN, so the message stays one
// line.
inline std::string shown_text(std::string_view text, char quote) {
  std::string out(1, quote);
  for (const char c : text) {
    if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (is_control(c))
      out += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
    else
      out += c;
  }
  return out + quote;
}

}  // namespace ccal::detail
