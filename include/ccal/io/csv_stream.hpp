#pragma once
// A CSV file read in one pass, row by row, in blocks: memory independent of the file's length. The grammar,
// the refusals and their places are parse_csv's (observation_csv.hpp); '#' comment lines are skipped. A
// CsvFormat reads a file as a data acquisition system wrote it: another delimiter, a decimal comma, another
// comment prefix, a preamble before the header, a units row under it.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace ccal {

// How a file is written (a log folder's manifest, [format]: intake/log_manifest.hpp). The default is parse_csv's
// grammar. A line of another format is read as the comma-separated line it stands for: its delimiter becomes
// the comma and a comma in it the delimiter (a comma in a cell is then no split, and a decimal comma not
// declared is refused as no number), or, with decimal = ',', the point. So every format's rows go through
// the one reading of comma-separated rows (its fast path included), and a default file is not translated.
struct CsvFormat {
  char delimiter = ',';       // ',', ';', '\t', or ' ' for whitespace: runs of blanks and tabs
  char decimal = '.';         // '.' or ',' (',' only with another delimiter than ',')
  std::string comment = "#";  // a line that begins with it (after blanks) is skipped; empty: none
  int skip_lines = 0;         // lines at the top skipped whatever they hold (a preamble)
  int header_line = 0;        // the header's 1-based line, lines before it skipped; 0: the first line after
                              // skip_lines that is neither blank nor a comment
  bool units_row = false;     // the first line after the header that is neither blank nor a comment holds
                              // the columns' units (CsvRowSink::units)
  bool is_default() const {
    return delimiter == ',' && decimal == '.' && comment == "#" && skip_lines == 0 && header_line == 0 &&
           !units_row;
  }
};
// The delimiter's name in messages and manifests: "comma", "semicolon", "tab", "whitespace".
std::string_view csv_delimiter_name(char delimiter);
// Throws the CsvError of a header line read as one name that holds another format's delimiter (the file is
// probably written with that one): parse_csv's and the streaming reader's check, in the same words.
void check_csv_delimiter(std::string_view line, const std::vector<std::string>& fields, const CsvFormat& format,
                         const std::string& source, int line_no);

class CsvRowSink {
 public:
  virtual ~CsvRowSink() = default;
  // The header (once, before any row) and its 1-based line.
  virtual void header(const std::vector<std::string>& names, int line) = 0;
  // With CsvFormat::units_row: the units row (once, after the header, before any row): one trimmed field per
  // name of the header (missing ones empty), and its line.
  virtual void units(const std::vector<std::string>& /*units*/, int /*line*/) {}
  // One row: exactly as many trimmed fields (quotes removed) as the header has names; valid until it returns.
  virtual void row(const std::string_view* fields, int line) = 0;
  // A sink's own reading of a row's line as it is (without its line end), offered before the line is split:
  // true when the sink took the row, false (having done nothing) to have it split and passed to row(). A
  // sink that reads the usual rows of its files in one pass over their bytes saves the splitting.
  virtual bool row_line(std::string_view /*line*/, int /*line*/) { return false; }
};

// Clinger's fast path for the plain decimals of a log, [-]digits[.digits]: a mantissa m < 2^53 and a
// fraction of at most 22 digits are exact doubles, so m / 10^f, one correctly rounded division, is the
// correctly rounded value of the text: the same double std::from_chars gives.
//
// scan_plain_decimal reads one from `cursor` up to the first character that cannot continue it (a comma,
// the end, anything else), moves `cursor` there and sets `value`; false, with neither changed, when what
// it read is not such a decimal (no digit, none before or after the point, more than 19 digits or 22
// fraction digits, a mantissa of 2^53 or more). parse_plain_decimal is true when the whole of `text` is one;
// false for anything else (exponents, a '+', blanks), which the caller reads the general way. (A byte at a
// time: eight-digit SWAR words measured slower on a log's short, point-split fields.)
// 10^0 … 10^22: the powers of ten that are exact doubles (5^22 < 2^53).
inline constexpr double kExactPowersOf10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                              1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                              1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
inline bool scan_plain_decimal(const char*& cursor, const char* end, double& value) {
  constexpr std::uint64_t kExact = std::uint64_t(1) << 53;
  const char* p = cursor;
  const bool negative = p != end && *p == '-';
  if (negative) ++p;
  std::uint64_t m = 0;  // wraps only past 19 digits, which are refused below
  const char* const first = p;
  const char* dot = nullptr;
  for (; p != end; ++p) {
    const unsigned digit = unsigned(*p) - unsigned('0');
    if (digit < 10) {
      m = 10 * m + digit;
    } else if (*p == '.' && dot == nullptr) {
      dot = p;
    } else {
      break;
    }
  }
  const std::ptrdiff_t length = p - first;
  if (length == 0 || dot == first || (dot != nullptr && dot + 1 == p))
    return false;  // no digit, or none before or after the point
  // At most 19 digits cannot overflow 64 bits (10^19 < 2^64).
  if (length - (dot != nullptr) > 19 || m >= kExact) return false;
  const std::ptrdiff_t fraction = dot == nullptr ? 0 : p - dot - 1;
  if (fraction > 22) return false;
  const double magnitude = double(m) / kExactPowersOf10[fraction];
  value = negative ? -magnitude : magnitude;
  cursor = p;
  return true;
}

inline bool parse_plain_decimal(std::string_view text, double& value) {
  const char* p = text.data();
  const char* const end = p + text.size();
  double read = 0;
  if (!scan_plain_decimal(p, end, read) || p != end) return false;
  value = read;
  return true;
}

// Throws CsvError at the first carriage return in `line` (a line without its LF or CRLF end): the sign of a
// file with CR-only line ends, which would otherwise read as one line; and at the first control byte (not a
// tab), the sign of a binary file or of text in UTF-16. Both readers apply it to the lines up to the header.
void check_csv_line_ends(std::string_view line, const std::string& source, int line_no);

// Streams a file to `sink`; returns the SHA-256 of its bytes (core/sha256.hpp), the fingerprint of the file
// as read, in the same pass. Throws CsvError (file unreadable, empty, no header, bad header, bad row; a
// header of one name that holds another format's delimiter, saying which delimiter it probably is; a file
// that ends before its header_line or its units row) and whatever the sink throws.
std::string stream_csv_file(const std::filesystem::path& path, CsvRowSink& sink, const CsvFormat& format = {});

}  // namespace ccal
