// ISO 8601 timestamps of a log's time column (io/iso_time.hpp): read to the nanosecond with their zone, written
// back to the microsecond; anything else refused (nullopt).
#include "ccal/io/iso_time.hpp"

#include <gtest/gtest.h>

namespace ccal {
namespace {

// 2026-11-30T10:15:00Z: 20787 days after 1970-01-01 (checked with Python's datetime), 36900 s into the day.
constexpr std::int64_t kOrigin = (20787LL * 86400 + 36900) * 1000000000;

TEST(IsoTime, TimestampsAreReadToTheNanosecondInTheirZone) {
  EXPECT_EQ(parse_iso8601_ns("2026-11-30T10:15:00Z"), kOrigin);
  EXPECT_EQ(parse_iso8601_ns("2026-11-30T10:15:02.125Z"), kOrigin + 2125000000);
  EXPECT_EQ(parse_iso8601_ns("2026-11-30T11:15:02.125+01:00"), kOrigin + 2125000000);
  EXPECT_EQ(parse_iso8601_ns("2026-11-30T05:15:02,125-0500"), kOrigin + 2125000000);
  EXPECT_EQ(parse_iso8601_ns("2026-11-30 10:15:02.000000001"), kOrigin + 2000000001);  // no zone: as written
  EXPECT_EQ(parse_iso8601_ns("1970-01-01T00:00:00Z"), 0);
  EXPECT_EQ(parse_iso8601_ns("2024-02-29T00:00:00Z"), (19782LL * 86400) * 1000000000);  // a leap day
  // Across midnight and a month's end, the difference is the elapsed time.
  EXPECT_EQ(*parse_iso8601_ns("2026-12-01T00:00:01Z") - *parse_iso8601_ns("2026-11-30T23:59:59.5Z"), 1500000000);
}

TEST(IsoTime, AnythingElseIsRefused) {
  for (const char* bad : {"", "2026-11-30", "2026-11-30T10:15", "2026-13-01T00:00:00Z", "2026-02-29T00:00:00Z",
                          "2026-11-30T24:00:00Z", "2026-11-30T10:15:60Z", "2026-11-30T10:15:00.Z",
                          "2026-11-30T10:15:00.1234567890Z", "2026-11-30T10:15:00+1", "2026-11-30T10:15:00Zx",
                          "2026/11/30T10:15:00Z", "1850-01-01T00:00:00Z", "72.5"})
    EXPECT_FALSE(parse_iso8601_ns(bad).has_value()) << bad;
}

TEST(IsoTime, WrittenToTheMicrosecondAndReadBack) {
  EXPECT_EQ(iso8601_text(kOrigin + 2125000999), "2026-11-30T10:15:02.125000Z");
  EXPECT_EQ(iso8601_text(0), "1970-01-01T00:00:00.000000Z");
  const std::int64_t t = kOrigin + 86400LL * 1000000000 * 40 + 123456000;
  EXPECT_EQ(parse_iso8601_ns(iso8601_text(t)), t);
}

}  // namespace
}  // namespace ccal
