#pragma once
// A CSV file read in one pass, row by row, in blocks: memory independent of the file's length. The grammar,
// the refusals and their places are parse_csv's (observation_csv.hpp); '#' comment lines are skipped.
#include <cstddef>
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
bool parse_plain_decimal(std::string_view text, double& value);

// Streams a file to `sink`. Throws CsvError (file unreadable, empty, no header, bad header, bad row) and
// whatever the sink throws.
void stream_csv_file(const std::filesystem::path& path, CsvRowSink& sink);
// The same for text in memory; `source` names it in messages.
void stream_csv_text(std::string_view text, std::string_view source, CsvRowSink& sink);

}  // namespace ccal
