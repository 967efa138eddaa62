// A log's row of plain decimals (io/plain_decimal_row.hpp): the vector reading and the cell-by-cell one give
// the same verdict and the same doubles, bit for bit, on rows as loggers write them, on every cell length
// and position around the 16-byte chunks (and lines too short or too long for them), and on rows that must
// be declined.
#include "ccal/io/plain_decimal_row.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "portable_uniform.hpp"

namespace ccal::test {
namespace {

// Both readings of `line` into n values: the same verdict and, when accepted, the same bits; the verdict.
bool same_reading(const std::string& line, std::size_t n) {
  std::vector<double> portable(n), vector(n);
  const bool a = detail::scan_plain_decimal_row_portable(line, portable);
  const bool b = detail::scan_plain_decimal_row_vector(line, vector);
  EXPECT_EQ(a, b) << "'" << line << "'";
  if (a && b) {
    for (std::size_t k = 0; k < n; ++k)
      EXPECT_EQ(std::bit_cast<std::uint64_t>(portable[k]), std::bit_cast<std::uint64_t>(vector[k]))
          << "'" << line << "' cell " << k;
  }
  return a;
}

TEST(PlainDecimalRow, VectorReadingIsTheCellByCellOne) {
  if (!detail::vector_row_scan_available()) GTEST_SKIP() << "no SSE4.1: only the portable reading runs";
  PortableUniform u{2026};
  int accepted = 0;
  for (int r = 0; r < 200'000; ++r) {
    // 1 to 6 cells of 0 to 20 digits with 0 to 16 decimals, signs, whole numbers: every length the window
    // can meet, at every offset (the lines are 1 to ~130 bytes).
    const int cells = 1 + int(u() * 6);
    std::string line;
    for (int c = 0; c < cells; ++c) {
      if (c) line += ',';
      if (u() < 0.3) line += '-';
      const int whole = int(u() * 17), fraction = u() < 0.2 ? 0 : 1 + int(u() * 16);
      for (int k = 0; k < whole; ++k) line += char('0' + int(u() * 10));
      if (fraction > 0 || u() < 0.02) line += '.';
      for (int k = 0; k < fraction; ++k) line += char('0' + int(u() * 10));
    }
    if (u() < 0.05) line[std::size_t(u() * double(line.size()))] = "x.,-e+ "[int(u() * 7)];  // damaged
    accepted += same_reading(line, std::size_t(cells));
    if (HasFailure()) return;
  }
  EXPECT_GT(accepted, 30'000);  // enough accepted rows to compare values, not only verdicts
}

TEST(PlainDecimalRow, RowsAsLoggersWriteThemAreExact) {
  // A 2 kHz log's rows (time to 0.1 µs, pulses, two angles to 1e-9 rad): the values std::from_chars gives.
  PortableUniform u{7};
  for (int r = 0; r < 100'000; ++r) {
    const double t = 5e-4 * r, theta = 2 * 3.141592653589793 * u(), gamma = -theta;
    const std::string line = fmt::format("{:.7f},{},{:.9f},{:.9f}", t, std::llround(1.6e5 * t), theta, gamma);
    std::vector<double> got(4);
    ASSERT_TRUE(scan_plain_decimal_row(line, got)) << line;
    const char* p = line.data();
    for (std::size_t k = 0; k < 4; ++k) {
      double expected = 0;
      p = std::from_chars(p, line.data() + line.size(), expected).ptr + 1;
      ASSERT_EQ(std::bit_cast<std::uint64_t>(got[k]), std::bit_cast<std::uint64_t>(expected)) << line;
    }
  }
}

TEST(PlainDecimalRow, DeclinesWhatIsNotARowOfPlainDecimals) {
  // Each is declined by both readings; the cells sit where the vector reading's window meets them.
  for (const std::string line :
       {"12345678901234567,1", "1.,2222222222222222", "12345678901234,.5", "12345678901234,-",
        "1234567890.12345,1,", ",1234567890.123456", "1234567890.123456,1e3", "1234567890.123456,,1",
        "1234567890.123456,1 ", "1234567890.123456,1.2.3", "-1234567890.123456,--1", "12345678901234567890"})
    EXPECT_FALSE(same_reading(line, 2)) << line;
  // ...and these are read, by both, to the same bits: 15 digits in the window, 16 and more past it.
  for (const std::string line :
       {"123456789012345,1", "1234567890123456,12345678.9012345", "-0.000000000000001,-0", "1,2",
        "99999999999999.9,1.000000000000001", "1234567,0.1234567890123456"})
    EXPECT_TRUE(same_reading(line, 2)) << line;
}

}  // namespace
}  // namespace ccal::test
