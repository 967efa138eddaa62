#pragma once
// Text helpers of the history store's messages (history_store.cpp, history_entry.cpp).
#include <string>

#include "../core/text_shown.hpp"

namespace ccal::detail {

// Text as a message shows it: in single quotes, on one line.
inline std::string history_shown(const std::string& text) { return shown_text(text, '\''); }

inline bool history_blank(const std::string& text) {
  return text.find_first_not_of(" \t\n\r\f\v") == std::string::npos;
}

}  // namespace ccal::detail
