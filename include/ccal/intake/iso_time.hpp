#pragma once
// ISO 8601 timestamps as data acquisition systems write them (a log's time column with time_unit = "iso8601",
// intake/log_manifest.hpp): 2026-11-30T10:15:02.125Z, 2026-11-30T11:15:02.125+01:00, 2026-11-30 10:15:02.125.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace ccal {

// A timestamp read: nanoseconds since 1970-01-01T00:00:00 of its zone's UTC, and whether it states its zone
// ('Z' or an offset; one without is read as written, so a log's timestamps must all state it or none).
struct IsoTimestamp {
  std::int64_t ns = 0;
  bool zoned = false;
};

// Accepted: YYYY-MM-DD, 'T' or one blank, hh:mm:ss, optionally a fraction of 1 to 9 digits after '.' or ',',
// then optionally 'Z', ±hh:mm or ±hhmm; years 1900 to 2200. nullopt for anything else (a date or time out of
// range, 24:00:00, a leap second 60), and then `problem`, when given, says what is wrong in words.
std::optional<IsoTimestamp> parse_iso8601(std::string_view text, std::string* problem = nullptr);
// The same, its nanoseconds alone.
std::optional<std::int64_t> parse_iso8601_ns(std::string_view text);

// The form accepted, for messages.
inline constexpr std::string_view kIso8601Accepted =
    "an ISO 8601 timestamp such as 2026-11-30T10:15:02.125Z (or with an offset, +01:00; a fraction of up to 9 "
    "digits)";

// ns since 1970 as YYYY-MM-DDThh:mm:ss.ffffffZ (microseconds, rounded down), for writers of logs.
std::string iso8601_text(std::int64_t ns);

}  // namespace ccal
