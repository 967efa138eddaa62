#pragma once
// Lists of names in the library's messages (private to the library).
#include <cstddef>
#include <string>
#include <vector>

namespace ccal::detail {

// "A", "A and B", "A, B and C"; "" for none.
inline std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += (i + 1 == names.size()) ? " and " : ", ";
    out += names[i];
  }
  return out;
}

}  // namespace ccal::detail
