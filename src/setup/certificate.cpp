#include "ccal/setup/certificate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <iterator>

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

std::vector<TraceabilityLine> traceability_lines(const Certificate& c, const std::vector<TracedInput>& inputs) {
  std::vector<TraceabilityLine> lines;
  const auto state = [&](const std::string& key, const std::string& standard) {
    if (!standard.empty()) lines.push_back({key, standard, {}});
  };
  state("radius", c.radius_standard);
  state("rate", c.rate_standard);
  for (const auto& [key, standard] : c.traceability) state(key, standard);
  if (std::ranges::none_of(lines, [](const TraceabilityLine& l) { return l.key == "fixed_terms"; }))
    state("fixed_terms", c.fixed_terms_source);
  const auto line_of = [&](const std::string& key) {
    return std::ranges::find_if(lines, [&](const TraceabilityLine& l) { return l.key == key; });
  };
  for (const TracedInput& in : inputs) {
    auto line = line_of(in.id);
    if (line == lines.end()) line = line_of(in.kind);
    if (line == lines.end()) {
      lines.push_back({in.kind, "", {}});
      line = std::prev(lines.end());
    }
    line->inputs.push_back(in.id);
  }
  return lines;
}

std::string traceability_gaps_text(const std::vector<TraceabilityLine>& lines) {
  std::string kinds, keys;
  for (const TraceabilityLine& l : lines) {
    if (!l.standard.empty()) continue;
    std::string inputs;
    for (std::size_t i = 0; i < l.inputs.size() && i < 4; ++i) inputs += (i ? ", " : "") + l.inputs[i];
    if (l.inputs.size() > 4) inputs += fmt::format(" and {} more", l.inputs.size() - 4);
    kinds += fmt::format("{}{} ({})", kinds.empty() ? "" : "; ", traceability_label(l.key), inputs);
    keys += fmt::format("{}{}", keys.empty() ? "" : ", ", l.key);
  }
  if (kinds.empty()) return "";
  return fmt::format("the certificate states no traceability for {}; it shows them as not stated (state them "
                     "in [certificate.traceability]: {})",
                     kinds, keys);
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
