#include "ccal/csv_stream.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <system_error>

#include "ccal/observation_csv.hpp"

namespace ccal {

namespace {

bool blank(char c) { return c == ' ' || c == '\t'; }

// parse_csv's trimming: blanks around, and a carriage return at the end.
std::string_view trim(std::string_view s) {
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && (blank(s.back()) || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Lines to rows, with parse_csv's line numbers and checks. Lines without a quote (all of a numeric log's)
// are split in place into views; others through parse_csv's field splitter.
class LineReader {
 public:
  LineReader(std::string source, CsvRowSink& sink) : source_(std::move(source)), sink_(sink) {}

  void line(std::string_view line) {
    ++line_no_;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::string_view content = trim(line);
    if (content.empty() || content.front() == '#') return;
    if (header_.empty()) {
      CsvFieldProblem bad;
      std::vector<std::string> fields = split_csv_fields(line, bad);
      check_csv_header(fields, bad, source_, line_no_);
      header_ = std::move(fields);
      views_.resize(header_.size());
      sink_.header(header_, line_no_);
      return;
    }
    if (line.find('"') == std::string_view::npos) {
      std::size_t count = 0, start = 0;
      while (true) {
        const std::size_t comma = line.find(',', start);
        const std::string_view field = trim(
            line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
        if (count < views_.size()) views_[count] = field;
        ++count;
        if (comma == std::string_view::npos) break;
        start = comma + 1;
      }
      if (count != header_.size()) check_csv_row(count, CsvFieldProblem{}, header_, source_, line_no_);
    } else {
      CsvFieldProblem bad;
      quoted_ = split_csv_fields(line, bad);
      check_csv_row(quoted_.size(), bad, header_, source_, line_no_);
      for (std::size_t k = 0; k < quoted_.size(); ++k) views_[k] = quoted_[k];
    }
    sink_.row(views_.data(), line_no_);
  }

  void finish() const {
    if (header_.empty()) throw no_csv_header(source_, line_no_);
  }

 private:
  std::string source_;
  CsvRowSink& sink_;
  int line_no_ = 0;
  std::vector<std::string> header_;
  std::vector<std::string_view> views_;
  std::vector<std::string> quoted_;
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

bool parse_plain_decimal(std::string_view text, double& value) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                      1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  constexpr std::uint64_t kExact = std::uint64_t(1) << 53;
  const char* p = text.data();
  const char* const end = p + text.size();
  const bool negative = p != end && *p == '-';
  if (negative) ++p;
  std::uint64_t m = 0;
  const char* const first = p;
  const char* dot = nullptr;
  for (; p != end; ++p) {
    const unsigned digit = unsigned(*p) - unsigned('0');
    if (digit < 10) {
      if (m >= kExact) return false;
      m = 10 * m + digit;
    } else if (*p == '.' && dot == nullptr) {
      dot = p;
    } else {
      return false;
    }
  }
  if (p == first || dot == first || (dot != nullptr && dot + 1 == end) || m >= kExact)
    return false;  // no digit, or none before or after the point
  const std::ptrdiff_t fraction = dot == nullptr ? 0 : end - dot - 1;
  if (fraction > 22) return false;
  value = double(m) / kPow10[fraction];
  if (negative) value = -value;
  return true;
}

void stream_csv_text(std::string_view text, std::string_view source, CsvRowSink& sink) {
  LineReader reader{std::string(source), sink};
  if (text.starts_with(kBom)) text.remove_prefix(kBom.size());
  const std::size_t rest = feed_lines(text, reader);
  if (rest < text.size()) reader.line(text.substr(rest));
  reader.finish();
}

void stream_csv_file(const std::filesystem::path& path, CsvRowSink& sink) {
  const std::string name = path.string();
  const CsvError unreadable(name, 0, 0, "", "cannot read the file; check the path and permissions");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw unreadable;
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(name.c_str(), "rb"));
  if (!file) throw unreadable;
  LineReader reader{name, sink};
  // Blocks of 4 MiB; the incomplete line at a block's end moves to the front of the next.
  constexpr std::size_t kBlock = std::size_t(1) << 22;
  std::vector<char> buffer(kBlock);
  std::size_t held = 0;
  bool first = true;
  while (true) {
    if (held == buffer.size()) buffer.resize(2 * buffer.size());  // a line longer than a block
    const std::size_t got = std::fread(buffer.data() + held, 1, buffer.size() - held, file.get());
    if (std::ferror(file.get())) throw unreadable;
    std::string_view text(buffer.data(), held + got);
    std::size_t skip = 0;
    if (first && (text.size() >= kBom.size() || got == 0)) {
      if (text.starts_with(kBom)) skip = kBom.size();
      first = false;
    }
    if (got == 0) {  // end of file: the last line, if it has no newline
      if (!first && skip < text.size()) reader.line(text.substr(skip));
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
}

}  // namespace ccal
