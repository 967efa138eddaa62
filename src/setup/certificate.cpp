#include "ccal/setup/certificate.hpp"

#include <fmt/format.h>

#include <charconv>

namespace ccal {
namespace {

bool leap(int year) { return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0; }

int days_in_month(int year, int month) {
  static constexpr int kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return month == 2 && leap(year) ? 29 : kDays[month - 1];
}

// The number written by text[from, from + n), all digits; -1 otherwise.
int digits_at(std::string_view text, std::size_t from, std::size_t n) {
  int v = 0;
  for (std::size_t i = from; i < from + n; ++i) {
    if (text[i] < '0' || text[i] > '9') return -1;
    v = 10 * v + (text[i] - '0');
  }
  return v;
}

}  // namespace

std::string_view traceability_label(std::string_view key) {
  for (const TraceabilityKind& k : kTraceabilityKinds)
    if (k.key == key) return k.label;
  return key;
}

std::string calendar_date_problem(std::string_view text) {
  const std::string accepted = "accepted: a date YYYY-MM-DD such as 2026-12-03";
  if (text.size() != 10 || text[4] != '-' || text[7] != '-')
    return fmt::format("'{}' is not written YYYY-MM-DD; {}", text, accepted);
  const int year = digits_at(text, 0, 4), month = digits_at(text, 5, 2), day = digits_at(text, 8, 2);
  if (year < 0 || month < 0 || day < 0) return fmt::format("'{}' is not written YYYY-MM-DD; {}", text, accepted);
  if (year < 1900) return fmt::format("'{}': the year {} is before 1900; {}", text, year, accepted);
  if (month < 1 || month > 12) return fmt::format("'{}': there is no month {}; {}", text, month, accepted);
  if (day < 1 || day > days_in_month(year, month))
    return fmt::format("'{}': month {} of {} has no day {}; {}", text, month, year, day, accepted);
  return {};
}

}  // namespace ccal
