// A log's row of plain decimals (intake/plain_decimal_row.hpp): the vector reading and the cell-by-cell one give
// the same verdict and the same doubles, bit for bit, on rows as loggers write them, on every cell length
// and position around the 16-byte chunks (and lines too short or too long for them), and on rows that must
// be declined; and a log's reader, which reads rows laid out alike by their layout, gives what each row read
// alone gives.
#include "../src/intake/plain_decimal_row.hpp"

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

// A row of the given shape (cells of `whole` and `fraction` digits, negative where `negative`), random
// digits.
struct Shape {
  int whole, fraction;
  bool negative;
};
std::string row_of(const std::vector<Shape>& shapes, PortableUniform& u) {
  std::string line;
  for (std::size_t c = 0; c < shapes.size(); ++c) {
    if (c) line += ',';
    if (shapes[c].negative) line += '-';
    for (int k = 0; k < shapes[c].whole; ++k) line += char('0' + int(u() * 10));
    if (shapes[c].fraction > 0) line += '.';
    for (int k = 0; k < shapes[c].fraction; ++k) line += char('0' + int(u() * 10));
  }
  return line;
}

// The reader's reading of `line` is the cell-by-cell one: the same verdict and, when accepted, the same bits.
void expect_read_alone(PlainDecimalRowReader& reader, const std::string& line, std::size_t n) {
  std::vector<double> alone(n), read(n);
  const bool a = detail::scan_plain_decimal_row_portable(line, alone);
  const bool b = reader.read(line, read);
  ASSERT_EQ(a, b) << "'" << line << "' as " << n << " cells";
  if (a) {
    for (std::size_t k = 0; k < n; ++k)
      ASSERT_EQ(std::bit_cast<std::uint64_t>(alone[k]), std::bit_cast<std::uint64_t>(read[k]))
          << "'" << line << "' cell " << k;
  }
}

TEST(PlainDecimalRow, ReaderReadsRowsLaidOutAlikeAsEachAlone) {
  PortableUniform u{1969};
  PlainDecimalRowReader reader;
  for (int layout = 0; layout < 3000; ++layout) {
    // A layout of 1 to 12 cells of 1 to 15 digits (the lines 16 to 63 bytes long are the ones read by layout;
    // the others go cell by cell), then rows of it with random digits (all-zero cells, leading zeros and
    // negative zeros among them), some interrupted by a row of another kind: damaged in one byte (the same
    // length), read as another number of cells, or of another layout.
    std::vector<Shape> shapes(1 + std::size_t(u() * 12));
    for (Shape& s : shapes) {
      const int digits = 1 + int(u() * 15);
      s.fraction = u() < 0.25 ? 0 : int(u() * double(digits));
      s.whole = digits - s.fraction;
      s.negative = u() < 0.3;
    }
    const std::size_t n = shapes.size();
    const int rows = 1 + int(u() * 8);
    for (int r = 0; r < rows; ++r) {
      std::string line = row_of(shapes, u);
      if (u() < 0.1)
        for (char& c : line)
          if (c >= '1' && c <= '9') c = '0';
      const double kind = u();
      if (kind < 0.05) line[std::size_t(u() * double(line.size()))] = "x.,-e+ 7"[int(u() * 8)];
      ASSERT_NO_FATAL_FAILURE(expect_read_alone(reader, line, kind > 0.05 && kind < 0.08 ? n + 1 : n));
    }
  }
  // A reader moved from reads on, from no layout.
  PlainDecimalRowReader moved = std::move(reader);
  for (int r = 0; r < 3; ++r) {
    const std::string line = row_of({{4, 7, false}, {9, 0, true}, {1, 9, false}, {1, 9, true}}, u);
    ASSERT_NO_FATAL_FAILURE(expect_read_alone(moved, line, 4));
    ASSERT_NO_FATAL_FAILURE(expect_read_alone(reader, line, 4));  // NOLINT(bugprone-use-after-move)
  }
  // The widest layouts: 31 and 32 one-digit cells (61 and 63 bytes), eight groups of four, the last one full
  // or not.
  for (const int cells : {31, 32})
    for (int r = 0; r < 5; ++r)
      ASSERT_NO_FATAL_FAILURE(expect_read_alone(
          reader, row_of(std::vector<Shape>(std::size_t(cells), {1, 0, false}), u), std::size_t(cells)));
}

}  // namespace
}  // namespace ccal::test
