// ISO 8601 timestamps of a log's time column (intake/iso_time.hpp): read to the nanosecond with their zone, written
// back to the microsecond; anything else refused (nullopt).
#include "ccal/intake/iso_time.hpp"

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

TEST(IsoTime, ARefusalSaysWhatIsWrong) {
  const auto problem = [](std::string_view text) {
    std::string why;
    EXPECT_FALSE(parse_iso8601(text, &why).has_value()) << text;
    return why;
  };
  EXPECT_EQ(problem("72.5"), "no date YYYY-MM-DD at its start");
  EXPECT_EQ(problem("2026-11-30"), "no time of day hh:mm:ss after its date and a 'T' (or a blank)");
  EXPECT_EQ(problem("1850-01-01T00:00:00Z"), "the year 1850 is outside 1900 to 2200");
  EXPECT_EQ(problem("2026-13-01T00:00:00Z"), "there is no month 13");
  EXPECT_EQ(problem("2026-02-29T00:00:00Z"), "2026-02 has no day 29");
  EXPECT_EQ(problem("2026-11-30T24:00:00Z"), "there is no time of day 24:00:00");
  EXPECT_EQ(problem("2016-12-31T23:59:60.5Z"), "a leap second (:60), across which the time is not known to the second (a "
                                                "clock without leap seconds, TAI or GPS, or a time unit reads it)");
  EXPECT_EQ(problem("2026-11-30T10:15:00.Z"), "no digit after the seconds' decimal separator");
  EXPECT_EQ(problem("2026-11-30T10:15:00.1234567890Z"), "a fraction of more than 9 digits (finer than a nanosecond)");
  EXPECT_EQ(problem("2026-11-30T10:15:00+1"), "'+1' is no offset from UTC (±hh:mm or ±hhmm)");
  EXPECT_EQ(problem("2026-11-30T10:15:00Zx"), "'x' after the time");
  // Whether a timestamp states its zone (a log's must all, or none).
  EXPECT_TRUE(parse_iso8601("2026-11-30T10:15:00Z")->zoned);
  EXPECT_TRUE(parse_iso8601("2026-11-30T10:15:00-0500")->zoned);
  EXPECT_FALSE(parse_iso8601("2026-11-30 10:15:00")->zoned);
}

TEST(IsoTime, WrittenToTheMicrosecondAndReadBack) {
  EXPECT_EQ(iso8601_text(kOrigin + 2125000999), "2026-11-30T10:15:02.125000Z");
  EXPECT_EQ(iso8601_text(0), "1970-01-01T00:00:00.000000Z");
  const std::int64_t t = kOrigin + 86400LL * 1000000000 * 40 + 123456000;
  EXPECT_EQ(parse_iso8601_ns(iso8601_text(t)), t);
}

}  // namespace
}  // namespace ccal
