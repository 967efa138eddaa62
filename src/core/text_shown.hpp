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

// The length of the well-formed UTF-8 sequence at text[i] (RFC 3629: no overlong forms, no surrogates, at
// most U+10FFFF), or 0 where the bytes there are not one.
inline std::size_t utf8_sequence(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b = byte(i);
  if (b < 0x80) return 1;
  const std::size_t n = b >= 0xc2 && b <= 0xdf ? 2 : b >= 0xe0 && b <= 0xef ? 3 : b >= 0xf0 && b <= 0xf4 ? 4 : 0;
  if (n == 0 || i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k)
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
  const unsigned char second = byte(i + 1);
  if ((b == 0xe0 && second < 0xa0) || (b == 0xed && second > 0x9f) || (b == 0xf0 && second < 0x90) ||
      (b == 0xf4 && second > 0x8f))
    return 0;  // overlong, a surrogate, or beyond U+10FFFF
  return n;
}
// Whether the text is valid UTF-8 throughout.
inline bool valid_utf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_sequence(text, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

// `text` between two `quote`s, its control characters written as \n, \t or \xNN, and each byte that is not
// part of valid UTF-8 as \xNN, so the message stays one line of text.
inline std::string shown_text(std::string_view text, char quote) {
  std::string out(1, quote);
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    const std::size_t n = utf8_sequence(text, i);
    if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (is_control(c) || n == 0)
      out += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
    else
      out.append(text.substr(i, n));
    i += n == 0 ? 1 : n;
  }
  return out + quote;
}

}  // namespace ccal::detail
