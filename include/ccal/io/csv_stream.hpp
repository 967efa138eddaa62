#pragma once
// A CSV file read in one pass, row by row, in blocks: memory independent of the file's length. The grammar,
// the refusals and their places are parse_csv's (observation_csv.hpp); '#' comment lines are skipped.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace ccal {

class CsvRowSink {
 public:
  virtual ~CsvRowSink() = default;
  // The header (once, before any row) and its 1-based line.
  virtual void header(const std::vector<std::string>& names, int line) = 0;
  // One row: exactly as many trimmed fields (quotes removed) as the header has names; valid until it returns.
  virtual void row(const std::string_view* fields, int line) = 0;
};

// Clinger's fast path for the plain decimals of a log, [-]digits[.digits]: a mantissa m < 2^53 and a
// fraction of at most 22 digits are exact doubles, so m / 10^f, one correctly rounded division, is the
// correctly rounded value of the text: the same double std::from_chars gives. False for anything else
// (exponents, a '+', blanks, more digits), which the caller reads the general way.
inline bool parse_plain_decimal(std::string_view text, double& value) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                      1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  constexpr std::uint64_t kExact = std::uint64_t(1) << 53;
  const char* p = text.data();
  const char* const end = p + text.size();
  const bool negative = p != end && *p == '-';
  if (negative) ++p;
  // At most 19 digits cannot overflow 64 bits (10^19 < 2^64), so the loop checks the count only, and the
  // mantissa's size once at the end.
  if (end - p > 20) return false;
  std::uint64_t m = 0;
  const char* const first = p;
  const char* dot = nullptr;
  for (; p != end; ++p) {
    const unsigned digit = unsigned(*p) - unsigned('0');
    if (digit < 10) {
      m = 10 * m + digit;
    } else if (*p == '.' && dot == nullptr) {
      dot = p;
    } else {
      return false;
    }
  }
  if (p == first || dot == first || (dot != nullptr && dot + 1 == end) || m >= kExact)
    return false;  // no digit, or none before or after the point
  // Twenty digits and no point: m may have wrapped.
  if (dot == nullptr && end - first > 19) return false;
  const std::ptrdiff_t fraction = dot == nullptr ? 0 : end - dot - 1;
  if (fraction > 22) return false;
  value = double(m) / kPow10[fraction];
  if (negative) value = -value;
  return true;
}

// Throws CsvError at the first carriage return in `line` (a line without its LF or CRLF end): the sign of a
// file with CR-only line ends, which would otherwise read as one line. Both readers apply it to the lines up
// to the header.
void check_csv_line_ends(std::string_view line, const std::string& source, int line_no);

// Streams a file to `sink`; returns the SHA-256 of its bytes (core/sha256.hpp), the fingerprint of the file
// as read, in the same pass. Throws CsvError (file unreadable, empty, no header, bad header, bad row) and
// whatever the sink throws.
std::string stream_csv_file(const std::filesystem::path& path, CsvRowSink& sink);

}  // namespace ccal
