#include "plain_decimal_row.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <memory>

#include "ccal/io/csv_stream.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define CCAL_VECTOR_ROW_SCAN 1
#endif

namespace ccal {

namespace detail {

// Where a line's digits, points, commas and minus signs are (bit i: byte i of the line).
struct LineClasses {
  std::uint64_t digit = 0, point = 0, comma = 0, minus = 0;
  bool operator==(const LineClasses&) const = default;
};

// The layout PlainDecimalRowReader keeps: that of the last two rows when they were laid out alike.
struct RowLayout {
  // Four cells of the layout: the byte permutation that gathers each cell's digits right-aligned into its
  // 16-byte lane (vpermb indices, the bytes not kept zero), the cells' divisors 10^fraction and sign bits.
  struct Group {
    std::uint8_t index[64] = {};
    std::uint64_t keep = 0;
    double scale[4] = {1, 1, 1, 1};
    std::uint64_t sign[4] = {};
  };
  static constexpr std::size_t kMaxCells = 32;  // one-digit cells and their commas fill 63 bytes

  std::size_t length = 0, cells = 0;  // the layout kept (length 0: none)
  LineClasses classes;
  std::size_t previous_length = 0;  // the last row read
  LineClasses previous;
  Group groups[kMaxCells / 4];
};

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

// The weights that combine right-aligned digits, most significant first: byte pairs 10·a + b, word pairs
// 100·ab + cd, word pairs 10⁴·abcd + efgh, and the two eights 10⁸·high + low (cell_value, read_laid_out).
constexpr short kPairWeights = 0x010A;     // bytes (10, 1)
constexpr int kQuadWeights = 0x00010064;   // words (100, 1)
constexpr int kEightWeights = 0x00012710;  // words (10000, 1)
constexpr std::uint32_t kHighEight = 100000000;

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
  const __m128i pairs = _mm_maddubs_epi16(gathered, _mm_set1_epi16(kPairWeights));
  const __m128i quads = _mm_madd_epi16(pairs, _mm_set1_epi32(kQuadWeights));
  const __m128i packed = _mm_packus_epi32(quads, quads);  // ≤ 9999 each
  const __m128i eights = _mm_madd_epi16(packed, _mm_set1_epi32(kEightWeights));
  const auto high = std::uint64_t(std::uint32_t(_mm_cvtsi128_si32(eights)));
  const auto low = std::uint64_t(std::uint32_t(_mm_extract_epi32(eights, 1)));
  return double(high * kHighEight + low) / kExactPowersOf10[fraction];
}

// A line of 16 to 63 bytes classified in 16-byte chunks, the last one ending at the line's end.
[[gnu::target("sse4.1,popcnt")]] inline detail::LineClasses classify_line(const char* text,
                                                                          std::size_t length) {
  detail::LineClasses line;
  for (std::size_t at = 0; at < length; at += 16) {
    const std::size_t chunk = std::min(at, length - 16);
    const ByteClasses c = classify(text + chunk);
    line.digit |= std::uint64_t(c.digit) << chunk;
    line.point |= std::uint64_t(c.point) << chunk;
    line.comma |= std::uint64_t(c.comma) << chunk;
    line.minus |= std::uint64_t(c.minus) << chunk;
  }
  return line;
}

// A cell as read: its first digit's byte, its digits before and after the point, its sign.
struct CellShape {
  unsigned first = 0, whole = 0, fraction = 0;
  bool negative = false;
};

// The n cells of a classified line of 16 to 63 bytes, each cell's shape to `shapes` when not null; false when
// the line is not n cells of at most 15 digits each (values then unspecified). The cells are read
// independently of each other (reading each from where the previous one ended would chain every cell's
// latency into the next).
[[gnu::target("sse4.1,popcnt"), gnu::always_inline]] inline bool read_cells(const char* text,
                                                                            std::size_t length,
                                                                            const detail::LineClasses& c,
                                                                            std::span<double> values,
                                                                            CellShape* shapes) {
  const std::size_t n = values.size();
  const std::uint64_t in_line = (std::uint64_t(1) << length) - 1;
  if ((c.digit | c.point | c.comma | c.minus) != in_line || std::popcount(c.comma) != int(n) - 1)
    return false;
  std::uint64_t stops = c.comma | (std::uint64_t(1) << length);  // the end of each cell
  unsigned start = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const auto stop = unsigned(std::countr_zero(stops));
    stops &= stops - 1;
    const std::uint64_t cell = ((std::uint64_t(1) << stop) - 1) & ~((std::uint64_t(1) << start) - 1);
    const std::uint64_t sign = c.minus & cell, points = c.point & cell;
    const unsigned first = start + unsigned(sign != 0);  // the first digit
    unsigned whole = stop - first, fraction = 0;
    if (points != 0) {
      const auto at = unsigned(std::countr_zero(points));
      whole = at - first;
      fraction = stop - at - 1;
    }
    if ((sign & ~(std::uint64_t(1) << start)) != 0 || (points & (points - 1)) != 0 || whole == 0 ||
        (points != 0 && fraction == 0) || whole + fraction > 15)
      return false;
    const std::size_t chunk = std::min<std::size_t>(first, length - 16);  // 16 bytes within the line
    const double magnitude = cell_value(text + chunk, unsigned(first - chunk), whole, fraction);
    values[k] = sign != 0 ? -magnitude : magnitude;
    if (shapes != nullptr) shapes[k] = {first, whole, fraction, sign != 0};
    start = stop + 1;
  }
  return true;
}

// A line of 16 to 63 bytes classified and read; any other line, and one that is not n cells of at most 15
// digits each, goes to the cell-by-cell reading, which decides it.
[[gnu::target("sse4.1,popcnt")]] bool vector_row(std::string_view line, std::span<double> values) {
  const std::size_t length = line.size();
  if (length < 16 || length > 63 || values.empty() ||
      !read_cells(line.data(), length, classify_line(line.data(), length), values, nullptr))
    return detail::scan_plain_decimal_row_portable(line, values);
  return true;
}

// Rows laid out alike, on a processor with AVX-512 VBMI.
#define CCAL_LAYOUT_TARGET "avx512f,avx512bw,avx512dq,avx512vl,avx512vbmi,popcnt"

// The layout of a row of n cells of the given shapes, kept for the rows that follow: cell 4g + j's digit k
// (most significant first, of d = whole + fraction) goes to byte 16j + 16 − d + k of group g, as
// cell_value's shuffle puts it.
void keep_layout(detail::RowLayout& layout, std::size_t length, const detail::LineClasses& classes,
                 const CellShape* shapes, std::size_t n) {
  layout.length = length;
  layout.cells = n;
  layout.classes = classes;
  for (std::size_t g = 0; 4 * g < n; ++g) {
    detail::RowLayout::Group& group = layout.groups[g];
    group = {};
    for (std::size_t j = 0; j < 4 && 4 * g + j < n; ++j) {
      const CellShape& cell = shapes[4 * g + j];
      const unsigned digits = cell.whole + cell.fraction;
      for (unsigned k = 0; k < digits; ++k) {
        const std::size_t byte = 16 * j + 16 - digits + k;
        group.index[byte] = std::uint8_t(cell.first + (k < cell.whole ? k : k + 1));
        group.keep |= std::uint64_t(1) << byte;
      }
      group.scale[j] = kExactPowersOf10[cell.fraction];
      group.sign[j] = cell.negative ? std::uint64_t(1) << 63 : 0;
    }
  }
}

// A line of at most 63 bytes classified in one 64-byte vector (a masked load: no byte past the line is read).
[[gnu::target(CCAL_LAYOUT_TARGET)]] inline detail::LineClasses classify_line_at_once(const char* text,
                                                                                     std::size_t length) {
  const __mmask64 in_line = _cvtu64_mask64((std::uint64_t(1) << length) - 1);
  const __m512i bytes = _mm512_maskz_loadu_epi8(in_line, text);
  const __m512i digits = _mm512_sub_epi8(bytes, _mm512_set1_epi8('0'));
  return {_cvtmask64_u64(_mm512_mask_cmple_epu8_mask(in_line, digits, _mm512_set1_epi8(9))),
          _cvtmask64_u64(_mm512_mask_cmpeq_epi8_mask(in_line, bytes, _mm512_set1_epi8('.'))),
          _cvtmask64_u64(_mm512_mask_cmpeq_epi8_mask(in_line, bytes, _mm512_set1_epi8(','))),
          _cvtmask64_u64(_mm512_mask_cmpeq_epi8_mask(in_line, bytes, _mm512_set1_epi8('-')))};
}

// The cells of a row laid out as `layout`, four at a time: gathered into lanes by one permutation, combined
// as cell_value combines them (the lane's first 32-bit word the high eight digits, the second the low
// eight), the mantissas < 10^15 converted exactly and divided by 10^fraction (the division scan_plain_decimal
// makes, so the same double), the signs set.
[[gnu::target(CCAL_LAYOUT_TARGET)]] inline void read_laid_out(const detail::RowLayout& layout,
                                                              const char* text, std::size_t length,
                                                              std::span<double> values) {
  const __mmask64 in_line = _cvtu64_mask64((std::uint64_t(1) << length) - 1);
  const __m512i digits = _mm512_sub_epi8(_mm512_maskz_loadu_epi8(in_line, text), _mm512_set1_epi8('0'));
  const std::size_t n = values.size();
  for (std::size_t g = 0; 4 * g < n; ++g) {
    const detail::RowLayout::Group& group = layout.groups[g];
    const __m512i gathered =
        _mm512_maskz_permutexvar_epi8(_cvtu64_mask64(group.keep), _mm512_loadu_si512(group.index), digits);
    const __m512i pairs = _mm512_maddubs_epi16(gathered, _mm512_set1_epi16(kPairWeights));
    const __m512i quads = _mm512_madd_epi16(pairs, _mm512_set1_epi32(kQuadWeights));
    const __m512i packed = _mm512_packus_epi32(quads, quads);
    const __m512i eights = _mm512_madd_epi16(packed, _mm512_set1_epi32(kEightWeights));
    // (The maskz forms: GCC 12 warns of the undefined source of the plain ones when inlined.)
    const __m512i mantissas =
        _mm512_add_epi64(_mm512_maskz_mul_epu32(0xFF, eights, _mm512_set1_epi64(kHighEight)),
                         _mm512_maskz_srli_epi64(0xFF, eights, 32));
    const __m256i four =
        _mm512_maskz_extracti64x4_epi64(0x0F, _mm512_maskz_compress_epi64(0x55, mantissas), 0);
    const __m256d magnitudes = _mm256_div_pd(_mm256_cvtepu64_pd(four), _mm256_loadu_pd(group.scale));
    const __m256d signed_values = _mm256_xor_pd(
        magnitudes, _mm256_castsi256_pd(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(group.sign))));
    // A whole group by a plain store: the reducer loads the values at once, and a masked store does not
    // forward to those loads (they would wait for it to reach the cache).
    if (const std::size_t count = n - 4 * g; count >= 4)
      _mm256_storeu_pd(values.data() + 4 * g, signed_values);
    else
      _mm256_mask_storeu_pd(values.data() + 4 * g, __mmask8((1u << count) - 1), signed_values);
  }
}

// A row read by its layout when it has the one kept, else cell by cell (a layout met in two consecutive rows
// is kept: rows of varying layout only pay the comparison).
[[gnu::target(CCAL_LAYOUT_TARGET)]] bool read_row_by_layout(detail::RowLayout& layout, std::string_view line,
                                                            std::span<double> values) {
  const std::size_t length = line.size(), n = values.size();
  if (length < 16 || length > 63 || n == 0 || n > detail::RowLayout::kMaxCells)
    return detail::scan_plain_decimal_row_portable(line, values);
  const detail::LineClasses classes = classify_line_at_once(line.data(), length);
  if (length == layout.length && n == layout.cells && classes == layout.classes) {
    read_laid_out(layout, line.data(), length, values);
    return true;
  }
  CellShape shapes[detail::RowLayout::kMaxCells];
  if (!read_cells(line.data(), length, classes, values, shapes))
    return detail::scan_plain_decimal_row_portable(line, values);
  if (length == layout.previous_length && classes == layout.previous)
    keep_layout(layout, length, classes, shapes, n);
  layout.previous_length = length;
  layout.previous = classes;
  return true;
}
#undef CCAL_LAYOUT_TARGET

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

bool detail::row_layout_reading_available() {
#ifdef CCAL_VECTOR_ROW_SCAN
  static const bool available = vector_row_scan_available() && __builtin_cpu_supports("avx512f") &&
                                __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq") &&
                                __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512vbmi");
  return available;
#else
  return false;
#endif
}

PlainDecimalRowReader::PlainDecimalRowReader() = default;
PlainDecimalRowReader::~PlainDecimalRowReader() = default;
PlainDecimalRowReader::PlainDecimalRowReader(PlainDecimalRowReader&&) noexcept = default;
PlainDecimalRowReader& PlainDecimalRowReader::operator=(PlainDecimalRowReader&&) noexcept = default;

bool PlainDecimalRowReader::read(std::string_view line, std::span<double> values) {
#ifdef CCAL_VECTOR_ROW_SCAN
  if (detail::row_layout_reading_available()) {
    if (!layout_) layout_ = std::make_unique<detail::RowLayout>();  // on first use (also after a move)
    return read_row_by_layout(*layout_, line, values);
  }
#endif
  return scan_plain_decimal_row(line, values);
}

bool scan_plain_decimal_row(std::string_view line, std::span<double> values) {
  return detail::vector_row_scan_available() ? detail::scan_plain_decimal_row_vector(line, values)
                                             : detail::scan_plain_decimal_row_portable(line, values);
}

}  // namespace ccal
