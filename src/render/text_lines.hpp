#pragma once
// Multi-line text as lines (private to the library): the notes of a result, one line each in the text and
// one array element each in the JSON.
#include <sstream>
#include <string>
#include <vector>

namespace ccal::render::detail {

// The non-empty lines of `text`, without their '\n'.
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (!l.empty()) out.push_back(l);
  return out;
}

}  // namespace ccal::render::detail
