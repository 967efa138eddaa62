// The observations file's header comments (io/observation_csv.hpp, ObservationsHeader): the
// "# ccal observations v1; …" line that says what the columns are, and the "# ccal log v1; …" lines of the logs
// the observations were reduced from.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "../core/text_trim.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/model/instrument.hpp"

namespace ccal {
namespace {

using detail::trim_csv;

constexpr std::string_view kHeaderKey = "ccal observations header";
constexpr std::string_view kLogMark = "ccal log";  // a reduced log's line (ObservationsHeader::logs)
constexpr std::string_view kMeasuredMark = "ccal measured";  // a measured input's (ObservationsHeader::measured)

// The pieces of `text` between separators, each trimmed.
std::vector<std::string> split(std::string_view text, char separator) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = text.find(separator, start);
    out.emplace_back(trim_csv(text.substr(start, end == std::string_view::npos ? text.npos : end - start)));
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return out;
}

}  // namespace

std::string format_observations_header(const ObservationsHeader& h) {
  std::vector<std::string> terms, fixed;
  for (const auto& t : h.terms) terms.push_back(t.id + ":" + t.column);
  for (const auto& f : h.fixed) {
    std::string entry = fmt::format("{}:{}={}", f.term.id, f.term.column, f.value);
    if (!f.unit.empty()) entry += " " + f.unit;
    fixed.push_back(std::move(entry));
  }
  std::string out = fmt::format("# ccal observations v1; terms={}; fixed={}; known={}; output_unit={}",
                                fmt::join(terms, ","), fmt::join(fixed, ","), fmt::join(h.known, ","),
                                h.output_unit);
  if (!h.config_sha256.empty()) out += "; config_sha256=" + h.config_sha256;
  // A line end in a name (possible in a file name) would end the comment: written as '?'.
  const auto one_line = [](std::string text) {
    std::replace_if(text.begin(), text.end(), [](char c) { return c == '\n' || c == '\r'; }, '?');
    return text;
  };
  for (const ObservationsHeader::Log& log : h.logs)
    out += fmt::format("\n# {} v1; run={}; sha256={}{}; file={}", kLogMark, one_line(log.run), log.sha256,
                       log.duration > 0 ? fmt::format("; duration={}", log.duration) : std::string(),
                       one_line(log.file));
  for (const MeasuredInput& m : h.measured)
    out += fmt::format("\n# {} v1; id={}; u={}; resolved={}; how={}", kMeasuredMark, m.id, m.standard_uncertainty,
                       m.resolved, one_line(m.how));
  return out;
}

namespace {

bool is_sha256(std::string_view value) {
  return value.size() == 64 && value.find_first_not_of("0123456789abcdef") == std::string_view::npos;
}

// A "# ccal log v1; run=…; sha256=…; file=…" comment (the file name is the rest of the line).
ObservationsHeader::Log read_log_line(const CsvTable& table, const CsvTable::Comment& comment) {
  auto fail = [&](std::string problem) {
    return CsvError(table.source, comment.line, 0, std::string(kHeaderKey), std::move(problem));
  };
  const std::string accepted =
      "accepted: # ccal log v1; run=<run>; sha256=<64 hex digits>[; duration=<s>]; file=<file>";
  std::string_view rest = std::string_view(comment.text).substr(kLogMark.size());
  constexpr std::string_view kVersion = " v1; ";
  if (!rest.starts_with(kVersion)) throw fail(fmt::format("unsupported log line; {}", accepted));
  rest.remove_prefix(kVersion.size());
  // run=<run>; sha256=<hex>; file=<file>: the run may hold ';' (a hex digest never does), the file anything.
  constexpr std::string_view kRun = "run=", kSha = "; sha256=", kFile = "; file=";
  const std::size_t sha = rest.find(kSha);
  if (!rest.starts_with(kRun) || sha == std::string_view::npos) throw fail(fmt::format("bad log line; {}", accepted));
  ObservationsHeader::Log log;
  log.run = std::string(trim_csv(rest.substr(kRun.size(), sha - kRun.size())));
  rest.remove_prefix(sha + kSha.size());
  const std::size_t file = rest.find(kFile);
  if (file == std::string_view::npos) throw fail(fmt::format("bad log line; {}", accepted));
  log.sha256 = std::string(trim_csv(rest.substr(0, file)));
  log.file = std::string(rest.substr(file + kFile.size()));
  constexpr std::string_view kDuration = "; duration=";  // optional, between the digest and the file
  if (const std::size_t d = log.sha256.find(kDuration); d != std::string::npos) {
    const std::string text = log.sha256.substr(d + kDuration.size());
    log.sha256.resize(d);
    const std::optional<double> value = parse_number(text);
    if (!value || !(*value > 0) || !std::isfinite(*value))
      throw fail(fmt::format("log duration '{}' is not a positive number of seconds; {}", text, accepted));
    log.duration = *value;
  }
  if (!is_sha256(log.sha256))
    throw fail(fmt::format("log sha256 '{}' is not a SHA-256; accepted: 64 lower-case hex digits", log.sha256));
  if (log.run.empty() || log.file.empty()) throw fail(fmt::format("a log line names no run or no file; {}", accepted));
  return log;
}

// A "# ccal measured v1; id=…; u=…; resolved=…; how=…" comment (the words are the rest of the line).
MeasuredInput read_measured_line(const CsvTable& table, const CsvTable::Comment& comment) {
  auto fail = [&](std::string problem) {
    return CsvError(table.source, comment.line, 0, std::string(kHeaderKey), std::move(problem));
  };
  const std::string accepted =
      "accepted: # ccal measured v1; id=<input id>; u=<standard uncertainty, SI>; resolved=true|false; how=<words>";
  std::string_view rest = std::string_view(comment.text).substr(kMeasuredMark.size());
  constexpr std::string_view kVersion = " v1; ", kHow = "; how=";
  if (!rest.starts_with(kVersion)) throw fail(fmt::format("unsupported measured-input line; {}", accepted));
  rest.remove_prefix(kVersion.size());
  const std::size_t how = rest.find(kHow);
  if (how == std::string_view::npos) throw fail(fmt::format("bad measured-input line; {}", accepted));
  MeasuredInput m;
  m.how = std::string(rest.substr(how + kHow.size()));
  bool has_id = false, has_u = false, has_resolved = false;
  for (const std::string& entry : split(rest.substr(0, how), ';')) {
    const std::size_t eq = entry.find('=');
    const std::string key = entry.substr(0, eq), value = eq == std::string::npos ? "" : entry.substr(eq + 1);
    if (key == "id" && !value.empty()) {
      m.id = value;
      has_id = true;
    } else if (key == "u") {
      const std::optional<double> u = parse_number(value);
      if (!u || !(*u > 0) || !std::isfinite(*u))
        throw fail(fmt::format("measured u '{}' is not a positive number; {}", value, accepted));
      m.standard_uncertainty = *u;
      has_u = true;
    } else if (key == "resolved" && (value == "true" || value == "false")) {
      m.resolved = value == "true";
      has_resolved = true;
    } else {
      throw fail(fmt::format("bad measured-input entry '{}'; {}", entry, accepted));
    }
  }
  if (!has_id || !has_u || !has_resolved) throw fail(fmt::format("incomplete measured-input line; {}", accepted));
  return m;
}

// The header line being read: a problem of it is a CsvError at its line, naming the header.
struct HeaderLine {
  const CsvTable& table;
  int line = 0;
  CsvError fail(std::string problem) const {
    return CsvError(table.source, line, 0, std::string(kHeaderKey), std::move(problem));
  }
};

// "<term>" or "<term>:<column>" (the column defaults to the term's id).
ObservationsHeader::Term read_header_term(const HeaderLine& at, const std::string& entry) {
  const std::size_t colon = entry.find(':');
  ObservationsHeader::Term t;
  t.id = std::string(trim_csv(std::string_view(entry).substr(0, colon)));
  t.column =
      colon == std::string::npos ? t.id : std::string(trim_csv(std::string_view(entry).substr(colon + 1)));
  if (!parse_term(t.id))
    throw at.fail(fmt::format("'{}' is not a term id; accepted: {}", t.id, fmt::join(all_term_ids(), ", ")));
  if (t.column.empty())
    throw at.fail(fmt::format("term '{}' has an empty column name; accepted: <term>:<column>", t.id));
  return t;
}

// fixed=<term>:<column>=<value> <unit>,...: each held term with its value.
void read_fixed_entries(const HeaderLine& at, const std::string& value, ObservationsHeader& h) {
  for (const auto& entry : split(value, ',')) {
    if (entry.empty()) continue;
    const auto assignment = split_term_assignment(entry);
    if (!assignment)
      throw at.fail(
          fmt::format("fixed entry '{}' has no value; accepted: <term>:<column>=<value> <unit>", entry));
    ObservationsHeader::Fixed f;
    f.term = read_header_term(at, assignment->term);
    const auto number = parse_number(assignment->value);
    if (!number)
      throw at.fail(
          fmt::format("fixed entry '{}': '{}' is not a finite number; accepted: "
                      "<term>:<column>=<value> <unit>",
                      entry, assignment->value));
    f.value = *number;
    f.unit = assignment->unit;
    h.fixed.push_back(std::move(f));
  }
}

// One key=value of the header line into h.
void read_header_entry(const HeaderLine& at, const std::string& key, const std::string& value,
                       ObservationsHeader& h) {
  if (key == "terms") {
    for (const auto& entry : split(value, ','))
      if (!entry.empty()) h.terms.push_back(read_header_term(at, entry));
  } else if (key == "fixed") {
    read_fixed_entries(at, value, h);
  } else if (key == "known") {
    for (const auto& entry : split(value, ','))
      if (!entry.empty()) h.known.push_back(entry);
  } else if (key == "output_unit") {
    h.output_unit = value;
  } else if (key == "config_sha256") {
    if (!is_sha256(value))
      throw at.fail(
          fmt::format("config_sha256 '{}' is not a SHA-256; accepted: 64 lower-case hex digits", value));
    h.config_sha256 = value;
  } else {
    throw at.fail(
        fmt::format("unknown key '{}'; accepted: terms, fixed, known, output_unit, config_sha256", key));
  }
}

// The terms as a whole: one free term at least, each term once (free or fixed), a column for each that is not
// a power of the input.
void check_header_terms(const HeaderLine& at, const ObservationsHeader& h) {
  if (h.terms.empty()) throw at.fail("no free terms; accepted: terms=<term>:<column>,...");
  std::set<std::string> ids;
  for (const auto& t : h.terms)
    if (!ids.insert(t.id).second) throw at.fail(fmt::format("term '{}' is listed twice", t.id));
  for (const auto& f : h.fixed)
    if (!ids.insert(f.term.id).second)
      throw at.fail(fmt::format("term '{}' is listed twice (free and fixed, or fixed twice)", f.term.id));
  for (const auto& t : h.terms)
    if (parse_term(t.id)->kind != TermKind::power && t.column.empty())
      throw at.fail(fmt::format("term '{}' needs a column", t.id));
}

}  // namespace

std::optional<ObservationsHeader> observations_header(const CsvTable& table) {
  constexpr std::string_view kMark = "ccal observations";
  for (const auto& comment : table.comments) {
    if (!comment.text.starts_with(kMark)) continue;
    const HeaderLine at{table, comment.line};
    const std::vector<std::string> parts = split(std::string_view(comment.text).substr(kMark.size()), ';');
    if (parts.front() != "v1")
      throw at.fail(fmt::format("unsupported version '{}'; accepted: v1", parts.front()));
    ObservationsHeader h;
    h.line = comment.line;
    std::set<std::string> keys;
    for (std::size_t k = 1; k < parts.size(); ++k) {
      if (parts[k].empty()) continue;
      const std::size_t eq = parts[k].find('=');
      const std::string key(trim_csv(std::string_view(parts[k]).substr(0, eq)));
      const std::string value = eq == std::string::npos
                                    ? std::string()
                                    : std::string(trim_csv(std::string_view(parts[k]).substr(eq + 1)));
      if (eq == std::string::npos)
        throw at.fail(fmt::format("'{}' has no value; accepted: <key>=<value>", parts[k]));
      if (!keys.insert(key).second) throw at.fail(fmt::format("'{}' is given twice", key));
      read_header_entry(at, key, value, h);
    }
    check_header_terms(at, h);
    for (const auto& c : table.comments)
      if (c.text.starts_with(kLogMark))
        h.logs.push_back(read_log_line(table, c));
      else if (c.text.starts_with(kMeasuredMark))
        h.measured.push_back(read_measured_line(table, c));
    return h;
  }
  return std::nullopt;
}

}  // namespace ccal
