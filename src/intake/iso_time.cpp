#include "ccal/intake/iso_time.hpp"

#include <fmt/format.h>

namespace ccal {

namespace {

// Days from 1970-01-01 to y-m-d of the proleptic Gregorian calendar (H. Hinnant's days_from_civil).
std::int64_t days_from_civil(std::int64_t y, unsigned m, unsigned d) {
  y -= m <= 2;
  const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
  const auto yoe = unsigned(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + std::int64_t(doe) - 719468;
}

bool leap(std::int64_t y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

unsigned days_in_month(std::int64_t y, unsigned m) {
  constexpr unsigned kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  return m == 2 && leap(y) ? 29 : kDays[m - 1];
}

// `count` digits at p as a number; false if any is not a digit.
bool digits(std::string_view s, std::size_t p, std::size_t count, unsigned& value) {
  if (p + count > s.size()) return false;
  value = 0;
  for (std::size_t k = p; k < p + count; ++k) {
    const unsigned d = unsigned(s[k]) - unsigned('0');
    if (d > 9) return false;
    value = 10 * value + d;
  }
  return true;
}

}  // namespace

std::optional<IsoTimestamp> parse_iso8601(std::string_view s, std::string* problem) {
  const auto refuse = [&](std::string why) -> std::optional<IsoTimestamp> {
    if (problem) *problem = std::move(why);
    return std::nullopt;
  };
  unsigned year = 0, month = 0, day = 0, hour = 0, minute = 0, second = 0;
  if (!digits(s, 0, 4, year) || s.size() < 5 || s[4] != '-' || !digits(s, 5, 2, month) || s.size() < 8 ||
      s[7] != '-' || !digits(s, 8, 2, day))
    return refuse("no date YYYY-MM-DD at its start");
  if (s.size() < 19 || (s[10] != 'T' && s[10] != ' ') || !digits(s, 11, 2, hour) || s[13] != ':' ||
      !digits(s, 14, 2, minute) || s[16] != ':' || !digits(s, 17, 2, second))
    return refuse("no time of day hh:mm:ss after its date and a 'T' (or a blank)");
  if (year < 1900 || year > 2200) return refuse(fmt::format("the year {} is outside 1900 to 2200", year));
  if (month < 1 || month > 12) return refuse(fmt::format("there is no month {:02}", month));
  if (day < 1 || day > days_in_month(year, month))
    return refuse(fmt::format("{:04}-{:02} has no day {:02}", year, month, day));
  if (second == 60 && hour <= 23 && minute <= 59)
    return refuse("a leap second (:60), across which the time is not known to the second (a clock without leap "
                  "seconds, TAI or GPS, or a time unit reads it)");
  if (hour > 23 || minute > 59 || second > 59)
    return refuse(fmt::format("there is no time of day {:02}:{:02}:{:02}", hour, minute, second));
  std::size_t p = 19;
  std::int64_t fraction_ns = 0;
  if (p < s.size() && (s[p] == '.' || s[p] == ',')) {
    std::size_t n = 0;
    std::int64_t scale = 100000000;
    for (++p; p < s.size() && unsigned(s[p]) - unsigned('0') <= 9; ++p, ++n) {
      if (n == 9) return refuse("a fraction of more than 9 digits (finer than a nanosecond)");
      fraction_ns += std::int64_t(s[p] - '0') * scale;
      scale /= 10;
    }
    if (n == 0) return refuse("no digit after the seconds' decimal separator");
  }
  std::int64_t offset_s = 0;
  bool zoned = false;
  if (p < s.size() && s[p] == 'Z') {
    ++p;
    zoned = true;
  } else if (p < s.size() && (s[p] == '+' || s[p] == '-')) {
    const int sign = s[p] == '-' ? -1 : 1;
    unsigned oh = 0, om = 0;
    std::size_t q = p + 3;
    if (q < s.size() && s[q] == ':') ++q;
    if (!digits(s, p + 1, 2, oh) || !digits(s, q, 2, om) || oh > 23 || om > 59)
      return refuse(fmt::format("'{}' is no offset from UTC (±hh:mm or ±hhmm)", s.substr(p)));
    offset_s = sign * std::int64_t(oh * 3600 + om * 60);
    p = q + 2;
    zoned = true;
  }
  if (p != s.size()) return refuse(fmt::format("'{}' after the time", s.substr(p)));
  const std::int64_t seconds = days_from_civil(year, month, day) * 86400 + hour * 3600 + minute * 60 + second -
                               offset_s;
  return IsoTimestamp{seconds * 1000000000 + fraction_ns, zoned};
}

std::optional<std::int64_t> parse_iso8601_ns(std::string_view s) {
  if (const std::optional<IsoTimestamp> t = parse_iso8601(s)) return t->ns;
  return std::nullopt;
}

std::string iso8601_text(std::int64_t ns) {
  std::int64_t seconds = ns / 1000000000, rest = ns % 1000000000;
  if (rest < 0) {
    rest += 1000000000;
    --seconds;
  }
  std::int64_t days = seconds / 86400, of_day = seconds % 86400;
  if (of_day < 0) {
    of_day += 86400;
    --days;
  }
  // civil_from_days (H. Hinnant)
  days += 719468;
  const std::int64_t era = (days >= 0 ? days : days - 146096) / 146097;
  const auto doe = unsigned(days - era * 146097);
  const unsigned yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
  const unsigned doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
  const unsigned mp = (5 * doy + 2) / 153;
  const unsigned d = doy - (153 * mp + 2) / 5 + 1;
  const unsigned m = mp < 10 ? mp + 3 : mp - 9;
  const std::int64_t y = std::int64_t(yoe) + era * 400 + (m <= 2);
  return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:06}Z", y, m, d, of_day / 3600, of_day / 60 % 60,
                     of_day % 60, rest / 1000);
}

}  // namespace ccal
