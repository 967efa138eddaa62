#pragma once
// A row of a run log as loggers write it, plain decimals between commas, read in one pass over its bytes: the
// row reading of `ccal reduce` (run_log_reducer.cpp), most of the reduction's parsing time.
#include <memory>
#include <span>
#include <string_view>

namespace ccal {

// True, with values[k] the k-th cell, when `line` (without its line end) is exactly values.size() plain
// decimals, [-]digits[.digits] as scan_plain_decimal (csv_stream.hpp) reads them, separated by single commas;
// false for anything else, values then unspecified (the caller splits the line and reads it the general way).
// Each cell is the double scan_plain_decimal gives, which is std::from_chars'. On an x86-64 processor with
// SSE4.1 and POPCNT a line of 16 to 63 bytes is classified in 16-byte vectors first (digits, points, commas,
// minus signs: where every cell begins and ends), then each cell of at most 15 digits is read without a loop
// over its characters: its digits gathered right-aligned by one byte shuffle and combined pairwise (2, 4, 8
// digits, two halves). Other lines go cell by cell through scan_plain_decimal.
bool scan_plain_decimal_row(std::string_view line, std::span<double> values);

namespace detail {
struct RowLayout;
}

// The rows of one log, read one after the other: scan_plain_decimal_row's verdicts and values, bit for bit,
// sooner for rows laid out alike, as loggers writing fixed decimals lay them out (the same bytes digits,
// points, commas and minus signs, row after row). On an x86-64 processor with AVX-512 VBMI a layout met in
// two consecutive rows is kept, and each row after them is classified in one 64-byte vector, compared with
// it and, when it matches, read without looking at its cells one by one: one byte permutation puts four
// cells' digits right-aligned in 16-byte lanes, combined and divided together as scan_plain_decimal_row
// combines and divides one.
class PlainDecimalRowReader {
 public:
  PlainDecimalRowReader();
  ~PlainDecimalRowReader();
  PlainDecimalRowReader(PlainDecimalRowReader&&) noexcept;
  PlainDecimalRowReader& operator=(PlainDecimalRowReader&&) noexcept;
  bool read(std::string_view line, std::span<double> values);

 private:
  std::unique_ptr<detail::RowLayout> layout_;
};

namespace detail {
// The two ways, for the tests that compare them: cell by cell with scan_plain_decimal, and the vector way
// (which must not be called unless vector_row_scan_available()).
bool scan_plain_decimal_row_portable(std::string_view line, std::span<double> values);
bool scan_plain_decimal_row_vector(std::string_view line, std::span<double> values);
bool vector_row_scan_available();
// Whether PlainDecimalRowReader reads rows by their layout here (AVX-512 VBMI).
bool row_layout_reading_available();
}  // namespace detail

}  // namespace ccal
