#include "ccal/io/plain_decimal_row.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>

#include "ccal/io/csv_stream.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define CCAL_VECTOR_ROW_SCAN 1
#endif

namespace ccal {

namespace detail {

bool scan_plain_decimal_row_portable(std::string_view line, std::span<double> values) {
  const char* p = line.data();
  const char* const end = p + line.size();
  const std::size_t n = values.size();
  for (std::size_t k = 0; k < n; ++k) {
    if (!scan_plain_decimal(p, end, values[k])) return false;
    if (k + 1 < n) {
      if (p == end || *p != ',') return false;
      ++p;
    }
  }
  return p == end;
}

}  // namespace detail

#ifdef CCAL_VECTOR_ROW_SCAN
namespace {

// The byte shuffle (pshufb) that gathers a cell's digits: for a cell of `whole` digits, a point when
// `fraction` > 0, and `fraction` digits, starting at byte 0 of a vector, output byte i takes the cell's
// digit k = i − (16 − n), n = whole + fraction (so the digits end right-aligned, the most significant first),
// or zero (index 0x80) for i < 16 − n. Digit k is at byte k before the point and k + 1 after it.
// [whole][fraction]; entries with n > 15 are never used.
struct DigitGather {
  alignas(16) std::uint8_t control[16][16][16];
  constexpr DigitGather() : control{} {
    for (int whole = 0; whole < 16; ++whole)
      for (int fraction = 0; fraction < 16; ++fraction)
        for (int i = 0; i < 16; ++i) {
          const int n = whole + fraction, k = i - (16 - n);
          control[whole][fraction][i] = k < 0 || n > 15 ? 0x80 : std::uint8_t(k < whole ? k : k + 1);
        }
  }
};
constexpr DigitGather kDigitGather;

// The bytes of the 16 at `chunk` that are digits, points, commas and minus signs (bit i: byte i).
struct ByteClasses {
  unsigned digit, point, comma, minus;
};
[[gnu::target("sse4.1,popcnt")]] inline ByteClasses classify(const char* chunk) {
  const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(chunk));
  const __m128i digits = _mm_sub_epi8(bytes, _mm_set1_epi8('0'));
  const auto mask = [](__m128i hit) { return unsigned(_mm_movemask_epi8(hit)); };
  return {mask(_mm_cmpeq_epi8(_mm_min_epu8(digits, _mm_set1_epi8(9)), digits)),  // 0 ≤ byte − '0' ≤ 9
          mask(_mm_cmpeq_epi8(bytes, _mm_set1_epi8('.'))), mask(_mm_cmpeq_epi8(bytes, _mm_set1_epi8(','))),
          mask(_mm_cmpeq_epi8(bytes, _mm_set1_epi8('-')))};
}

// The value of `whole` digits, a point when `fraction` > 0, and `fraction` digits at byte `offset` of the 16
// at `chunk`, whole + fraction ≤ 15: the digits gathered right-aligned, then combined in pairs 10·a + b,
// quads 100·ab + cd, eights 10⁴·abcd + efgh, and the two eights. m < 10^15 < 2^53 is an exact double, so
// m / 10^f is scan_plain_decimal's division.
[[gnu::target("sse4.1,popcnt")]] inline double cell_value(const char* chunk, unsigned offset, unsigned whole,
                                                          unsigned fraction) {
  const __m128i digits =
      _mm_sub_epi8(_mm_loadu_si128(reinterpret_cast<const __m128i*>(chunk)), _mm_set1_epi8('0'));
  const __m128i control =
      _mm_add_epi8(_mm_load_si128(reinterpret_cast<const __m128i*>(kDigitGather.control[whole][fraction])),
                   _mm_set1_epi8(char(offset)));  // 0x80 + offset still selects a zero
  const __m128i gathered = _mm_shuffle_epi8(digits, control);
  const __m128i pairs = _mm_maddubs_epi16(gathered, _mm_set1_epi16(0x010A));  // bytes (10, 1)
  const __m128i quads = _mm_madd_epi16(pairs, _mm_set1_epi32(0x00010064));    // words (100, 1)
  const __m128i packed = _mm_packus_epi32(quads, quads);                      // ≤ 9999 each
  const __m128i eights = _mm_madd_epi16(packed, _mm_set1_epi32(0x00012710));  // words (10000, 1)
  const auto high = std::uint64_t(std::uint32_t(_mm_cvtsi128_si32(eights)));
  const auto low = std::uint64_t(std::uint32_t(_mm_extract_epi32(eights, 1)));
  return double(high * 100000000u + low) / kExactPowersOf10[fraction];
}

// A line of 16 to 63 bytes: the positions of its digits, points, commas and minus signs found first, for the
// whole line at once (16-byte chunks, the last one ending at the line's end), so that the cells are then read
// independently of each other (reading each from where the previous one ended chains every cell's latency
// into the next). Any other line, and one that is not n cells of at most 15 digits each, goes to the
// cell-by-cell reading, which decides it.
[[gnu::target("sse4.1,popcnt")]] bool vector_row(std::string_view line, std::span<double> values) {
  const std::size_t length = line.size(), n = values.size();
  if (length < 16 || length > 63 || n == 0) return detail::scan_plain_decimal_row_portable(line, values);
  const char* const text = line.data();
  std::uint64_t digit = 0, point = 0, comma = 0, minus = 0;
  for (std::size_t at = 0; at < length; at += 16) {
    const std::size_t chunk = std::min(at, length - 16);
    const ByteClasses c = classify(text + chunk);
    digit |= std::uint64_t(c.digit) << chunk;
    point |= std::uint64_t(c.point) << chunk;
    comma |= std::uint64_t(c.comma) << chunk;
    minus |= std::uint64_t(c.minus) << chunk;
  }
  const std::uint64_t in_line = (std::uint64_t(1) << length) - 1;
  if ((digit | point | comma | minus) != in_line || std::popcount(comma) != int(n) - 1)
    return detail::scan_plain_decimal_row_portable(line, values);
  std::uint64_t stops = comma | (std::uint64_t(1) << length);  // the end of each cell
  unsigned start = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const auto stop = unsigned(std::countr_zero(stops));
    stops &= stops - 1;
    const std::uint64_t cell = ((std::uint64_t(1) << stop) - 1) & ~((std::uint64_t(1) << start) - 1);
    const std::uint64_t sign = minus & cell, points = point & cell;
    const unsigned first = start + unsigned(sign != 0);  // the first digit
    unsigned whole = stop - first, fraction = 0;
    if (points != 0) {
      const auto at = unsigned(std::countr_zero(points));
      whole = at - first;
      fraction = stop - at - 1;
    }
    if ((sign & ~(std::uint64_t(1) << start)) != 0 || (points & (points - 1)) != 0 || whole == 0 ||
        (points != 0 && fraction == 0) || whole + fraction > 15)
      return detail::scan_plain_decimal_row_portable(line, values);
    const std::size_t chunk = std::min<std::size_t>(first, length - 16);  // 16 bytes within the line
    const double magnitude = cell_value(text + chunk, unsigned(first - chunk), whole, fraction);
    values[k] = sign != 0 ? -magnitude : magnitude;
    start = stop + 1;
  }
  return true;
}

}  // namespace
#endif

namespace detail {

bool vector_row_scan_available() {
#ifdef CCAL_VECTOR_ROW_SCAN
  static const bool available = __builtin_cpu_supports("sse4.1") && __builtin_cpu_supports("popcnt");
  return available;
#else
  return false;
#endif
}

bool scan_plain_decimal_row_vector(std::string_view line, std::span<double> values) {
#ifdef CCAL_VECTOR_ROW_SCAN
  return vector_row(line, values);
#else
  return scan_plain_decimal_row_portable(line, values);
#endif
}

}  // namespace detail

bool scan_plain_decimal_row(std::string_view line, std::span<double> values) {
  return detail::vector_row_scan_available() ? detail::scan_plain_decimal_row_vector(line, values)
                                             : detail::scan_plain_decimal_row_portable(line, values);
}

}  // namespace ccal
