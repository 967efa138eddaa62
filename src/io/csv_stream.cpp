#include "ccal/io/csv_stream.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <cstdio>
#include <cstring>
#include <memory>
#include <system_error>

#include "../core/text_trim.hpp"
#include "ccal/core/sha256.hpp"
#include "ccal/io/observation_csv.hpp"

namespace ccal {

namespace {

using detail::trim_csv;

// The comma-separated line a line of `format` stands for (CsvFormat): its delimiter as the comma, and a comma
// as the delimiter (whitespace: a blank), or, in the rows of a file with decimal commas, as the point.
void translate(std::string_view line, const CsvFormat& format, bool names, std::string& out) {
  const char comma = format.decimal == ',' && !names ? '.' : format.delimiter == ' ' ? ' ' : format.delimiter;
  out.clear();
  if (format.delimiter == ' ') {  // runs of blanks between fields, none around them
    bool gap = false;
    for (const char c : line) {
      if (detail::blank(c)) {
        gap = !out.empty();
        continue;
      }
      if (gap) out += ',';
      gap = false;
      out += c == ',' ? comma : c;
    }
    return;
  }
  out.resize(line.size());
  for (std::size_t k = 0; k < line.size(); ++k) {
    const char c = line[k];
    out[k] = c == format.delimiter ? ',' : c == ',' ? comma : c;
  }
}

// Lines to rows, with parse_csv's line numbers and checks. Lines without a quote (all of a numeric log's)
// are split in place into views; others through parse_csv's field splitter. A file of another format
// (CsvFormat) is read line by line as the comma-separated lines it stands for.
class LineReader {
 public:
  LineReader(std::string source, CsvRowSink& sink, const CsvFormat& format)
      : source_(std::move(source)), sink_(sink), format_(format), translate_(format.delimiter != ',') {}

  void line(std::string_view line) {
    ++line_no_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (rows_as_written_) {  // the usual row: ccal's own format, past the header (and units)
      if (sink_.row_line(line, line_no_)) return;
    } else if (!header_.empty() && !want_units_) {
      if (translate_) {  // blanks and comments as written; the rest as its comma-separated line
        const std::string_view content = trim_csv(line);
        if (content.empty() || comment(content)) return;
        translate(line, format_, false, translated_);
        line = translated_;
      }
      // A row the sink reads itself (one that is neither blank nor a comment, or the sink would not take it).
      if (sink_.row_line(line, line_no_)) return;
    }
    if (header_.empty()) check_csv_line_ends(line, source_, line_no_);  // rows: a CR is a bad cell there
    if (header_.empty() && (line_no_ <= format_.skip_lines || line_no_ < format_.header_line)) return;
    const std::string_view content = trim_csv(line);
    const bool the_header_line = header_.empty() && line_no_ == format_.header_line;
    if (the_header_line && (content.empty() || comment(content))) refuse_header_line(content);
    if (!the_header_line && (content.empty() || comment(content))) return;
    if (header_.empty() || want_units_) return header_or_units(line);
    split_row(line);
    sink_.row(views_.data(), line_no_);
  }

 private:
  // The header_line of the [format] table must be the column names' line, not a blank or a comment.
  [[noreturn]] void refuse_header_line(std::string_view content) const {
    throw CsvError(
        source_, line_no_, 1, "",
        fmt::format("line {}, the header_line of the [format] table, is {}; accepted: the line of the "
                    "column names as header_line{}",
                    line_no_, content.empty() ? "blank" : fmt::format("a comment ('{}')", content),
                    content.empty() ? ""
                                    : fmt::format(", or comment = \"\" for a header that begins with "
                                                  "'{}'",
                                                  format_.comment)));
  }

  // The header, then the units row when the format has one: checked and handed to the sink.
  void header_or_units(std::string_view line) {
    CsvFieldProblem bad;
    std::vector<std::string> fields;
    if (translate_) {
      translate(line, format_, true, translated_);
      fields = split_csv_fields(translated_, bad);
    } else {
      fields = split_csv_fields(line, bad);
    }
    if (want_units_) {
      check_csv_row(fields.size() <= header_.size() ? header_.size() : fields.size(), bad, header_, source_,
                    line_no_);
      fields.resize(header_.size());
      want_units_ = false;
      rows_as_written_ = !translate_;
      sink_.units(fields, line_no_);
      return;
    }
    check_csv_delimiter(line, fields, format_, source_, line_no_);
    check_csv_header(fields, bad, source_, line_no_);
    header_ = std::move(fields);
    views_.resize(header_.size());
    want_units_ = format_.units_row;
    rows_as_written_ = !translate_ && !want_units_;
    sink_.header(header_, line_no_);
  }

  // A row's cells into views_: a line with a quote through parse_csv's splitter, the others (all of a numeric
  // log's) cut at the commas in place (memchr: the library's vectorised byte search).
  void split_row(std::string_view line) {
    if (std::memchr(line.data(), '"', line.size()) != nullptr) {
      CsvFieldProblem bad;
      quoted_ = split_csv_fields(line, bad);
      check_csv_row(quoted_.size(), bad, header_, source_, line_no_);
      for (std::size_t k = 0; k < quoted_.size(); ++k) views_[k] = quoted_[k];
    } else {
      std::size_t count = 0;
      const char* start = line.data();
      const char* const end = start + line.size();
      while (true) {
        const void* comma = std::memchr(start, ',', std::size_t(end - start));
        const char* stop = comma != nullptr ? static_cast<const char*>(comma) : end;
        if (count < views_.size())
          views_[count] = trim_csv(std::string_view(start, std::size_t(stop - start)));
        ++count;
        if (stop == end) break;
        start = stop + 1;
      }
      if (count != header_.size()) check_csv_row(count, CsvFieldProblem{}, header_, source_, line_no_);
    }
  }

 public:
  void finish() const {
    if (header_.empty() && format_.header_line > line_no_)
      throw CsvError(source_, line_no_, 0, "",
                     fmt::format("the file ends at line {}, before its header at line {}; accepted: the header's "
                                 "line as header_line of the [format] table",
                                 line_no_, format_.header_line));
    if (header_.empty() && format_.skip_lines > 0 && format_.skip_lines >= line_no_)
      throw CsvError(source_, line_no_, 0, "",
                     fmt::format("the file ends at line {}, within its skip_lines = {} lines skipped; accepted: "
                                 "the count of lines before the header as skip_lines of the [format] table",
                                 line_no_, format_.skip_lines));
    if (header_.empty()) throw no_csv_header(source_, line_no_);
    if (want_units_)
      throw CsvError(source_, line_no_, 0, "",
                     "no units row after the header; accepted: a line of the columns' units under the header, or "
                     "units_row = false in the [format] table");
  }

 private:
  bool comment(std::string_view content) const {
    return !format_.comment.empty() && content.starts_with(format_.comment);
  }

  std::string source_;
  CsvRowSink& sink_;
  const CsvFormat& format_;
  bool translate_;
  bool want_units_ = false;
  bool rows_as_written_ = false;  // past the header and units, in a format read as written
  int line_no_ = 0;
  std::vector<std::string> header_;
  std::vector<std::string_view> views_;
  std::vector<std::string> quoted_;
  std::string translated_;
};

constexpr std::string_view kBom = "\xEF\xBB\xBF";

// The complete lines of `text` to the reader; returns where the incomplete last line starts.
std::size_t feed_lines(std::string_view text, LineReader& reader) {
  std::size_t start = 0;
  while (true) {
    const void* nl = std::memchr(text.data() + start, '\n', text.size() - start);
    if (nl == nullptr) return start;
    const std::size_t end = std::size_t(static_cast<const char*>(nl) - text.data());
    reader.line(text.substr(start, end - start));
    start = end + 1;
  }
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

void check_csv_line_ends(std::string_view line, const std::string& source, int line_no) {
  // A binary file (or text in UTF-16) given for a table: a control byte that no text line holds, shown by its
  // code rather than dumped into the message.
  const auto control = std::find_if(line.begin(), line.end(), [](char c) {
    const auto byte = static_cast<unsigned char>(c);
    return (byte < 0x20 && c != '\t' && c != '\r') || byte == 0x7f;
  });
  if (control != line.end())
    throw CsvError(source, line_no, int(control - line.begin()) + 1, "",
                   fmt::format("the byte 0x{:02x} is no character of a text line: the file is not a text table "
                               "(a binary file, or text in UTF-16?); accepted: a CSV text file (UTF-8), e.g. a "
                               "spreadsheet saved as CSV",
                               static_cast<unsigned char>(*control)));
  const void* cr = std::memchr(line.data(), '\r', line.size());
  if (cr == nullptr) return;
  const auto column = int(static_cast<const char*>(cr) - line.data()) + 1;
  throw CsvError(source, line_no, column, "",
                 "a carriage return inside the line: the file uses CR-only line ends (classic Mac OS), which "
                 "are not read; accepted: LF or CRLF line ends (convert it, e.g. tr '\\r' '\\n' < in.csv > "
                 "out.csv)");
}

std::string_view csv_delimiter_name(char delimiter) {
  switch (delimiter) {
    case ',': return "comma";
    case ';': return "semicolon";
    case '\t': return "tab";
    default: return "whitespace";
  }
}

void check_csv_delimiter(std::string_view line, const std::vector<std::string>& fields, const CsvFormat& format,
                         const std::string& source, int line_no) {
  if (fields.size() != 1) return;
  // A TOML file given for a table (a configuration for the observations, a manifest for a log): a `key = …`
  // line or a `[table]` header where the column names should be.
  const std::string_view text = trim_csv(line);
  const std::size_t equals = text.find('=');
  const bool toml_key =
      equals != std::string_view::npos && equals > 0 &&
      trim_csv(text.substr(0, equals)).find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                                         "0123456789_-.\"'") == std::string_view::npos;
  // A JSON document (a calibration statement, a result of ccal) given for a table: its opening brace.
  if (text == "{" || text == "[" || (text.starts_with('{') && text.find('"') != std::string_view::npos))
    throw CsvError(source, line_no, 1, "",
                   fmt::format("the header, '{}', opens a JSON document (a statement or a result of ccal?), not a "
                               "table's header; accepted: a CSV table whose header names its columns, e.g. "
                               "time,pulses",
                               fields[0]));
  if (toml_key || (text.starts_with('[') && text.ends_with(']')))
    throw CsvError(source, line_no, 1, "",
                   fmt::format("the header, '{}', is a line of TOML (a configuration or a manifest?), not a table's "
                               "header; accepted: a CSV table whose header names its columns, e.g. time,pulses",
                               fields[0]));
  std::optional<char> other;
  for (const char c : {';', '\t', ','})
    if (c != format.delimiter && line.find(c) != std::string_view::npos) {
      other = c;
      break;
    }
  if (!other && format.delimiter != ' ' && trim_csv(line).find_first_of(" \t") != std::string_view::npos)
    other = ' ';
  if (!other) return;
  const std::string_view name = csv_delimiter_name(*other);
  throw CsvError(source, line_no, 1, "",
                 fmt::format("the header is one name, '{}', which holds {} between names: the delimiter is "
                             "probably {} (the file is read with {}); accepted: {}delimiter = \"{}\" in the [format] "
                             "table of the manifest or of the layout file",
                             fields[0], *other == '\t' ? "tabs" : *other == ' ' ? "blanks"
                                                               : fmt::format("'{}'", *other),
                             *other == '\t' ? "a tab" : *other == ' ' ? "whitespace" : fmt::format("'{}'", *other),
                             csv_delimiter_name(format.delimiter),
                             // Only a run log has a [format]; other tables are comma-separated.
                             format.delimiter == ',' ? "names separated by commas, or, in a run log, " : "",
                             name));
}

std::string stream_csv_file(const std::filesystem::path& path, CsvRowSink& sink, const CsvFormat& format) {
  const std::string name = path.string();
  const FileNotFound<CsvError> unreadable(name, 0, 0, "", unreadable_file_problem(path));
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw unreadable;
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(name.c_str(), "rb"));
  if (!file) throw unreadable;
  LineReader reader{name, sink, format};
  // Blocks of 4 MiB; the incomplete line at a block's end moves to the front of the next. A smaller file (its
  // size known) gets a buffer of its size and one byte, to see its end in the same read.
  constexpr std::size_t kBlock = std::size_t(1) << 22;
  std::error_code size_error;
  const std::uintmax_t size = std::filesystem::file_size(path, size_error);
  std::vector<char> buffer(size_error ? kBlock : std::size_t(std::min<std::uintmax_t>(kBlock, size + 1)));
  std::size_t held = 0;
  bool first = true;
  Sha256 fingerprint;
  while (true) {
    if (held == buffer.size()) buffer.resize(2 * buffer.size());  // a line longer than a block
    const std::size_t got = std::fread(buffer.data() + held, 1, buffer.size() - held, file.get());
    if (std::ferror(file.get())) throw unreadable;
    fingerprint.update(std::string_view(buffer.data() + held, got));
    std::string_view text(buffer.data(), held + got);
    std::size_t skip = 0;
    if (first && (text.size() >= kBom.size() || got == 0)) {
      if (text.starts_with(kBom)) skip = kBom.size();
      first = false;
    }
    if (got == 0) {  // end of file: the lines held (a file of less than three bytes, "\nx", has not been
                     // split yet), then the last line, if it has no newline
      const std::size_t rest = skip + feed_lines(text.substr(skip), reader);
      if (rest < text.size()) reader.line(text.substr(rest));
      break;
    }
    if (first) {  // fewer than three bytes so far: the mark cannot be told yet
      held = text.size();
      continue;
    }
    const std::size_t rest = skip + feed_lines(text.substr(skip), reader);
    held = text.size() - rest;
    std::memmove(buffer.data(), buffer.data() + rest, held);
  }
  reader.finish();
  return fingerprint.hex();
}

}  // namespace ccal
