#pragma once
// Trimming of text read from files and options (private to the library): the CSV readers' fields and lines
// (observation_csv.cpp, csv_stream.cpp), a term's value (split_term_assignment) and an allocation target.
#include <string_view>

namespace ccal::detail {

// A blank: space or tab.
inline bool blank(char c) { return c == ' ' || c == '\t'; }

// `s` without the blanks around it.
inline std::string_view trim_blanks(std::string_view s) {
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

// parse_csv's trimming: blanks around, and carriage returns among the trailing blanks (a CRLF line end).
inline std::string_view trim_csv(std::string_view s) {
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && (blank(s.back()) || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

}  // namespace ccal::detail
