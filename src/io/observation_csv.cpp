#include "ccal/io/observation_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <stdexcept>

#include "../core/text_trim.hpp"
#include "ccal/core/sha256.hpp"
#include "ccal/core/units.hpp"
#include "ccal/io/csv_stream.hpp"

namespace ccal {

namespace {

std::string format_csv_error(const std::string& source, int line, int column, const std::string& name,
                             const std::string& problem) {
  std::string out = source;
  if (line > 0) out += fmt::format(":{}", line);
  if (line > 0 && column > 0) out += fmt::format(":{}", column);
  out += ": ";
  if (!name.empty()) out += name + ": ";
  out += problem;
  return with_nul_shown(std::move(out));
}

using detail::blank;
using detail::trim_blanks;
using detail::trim_csv;

enum class NumberKind { finite, non_finite, empty, not_a_number };

NumberKind read_number(std::string_view text, double& value) {
  text = trim_csv(text);
  if (text.empty()) return NumberKind::empty;
  if (text.front() == '+') {
    text.remove_prefix(1);
    if (text.empty() || text.front() == '-' || text.front() == '+') return NumberKind::not_a_number;
  }
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size()) return NumberKind::not_a_number;
  return std::isfinite(value) ? NumberKind::finite : NumberKind::non_finite;
}

// Splits one CSV line into trimmed fields (quotes removed). On a malformed quote, returns the 0-based index
// of the offending field in `bad` with a description.
std::vector<std::string> split_fields(std::string_view line,
                                      std::optional<std::pair<std::size_t, std::string>>& bad) {
  std::vector<std::string> fields;
  std::size_t i = 0;
  while (true) {
    while (i < line.size() && blank(line[i])) ++i;
    std::string field;
    if (i < line.size() && line[i] == '"') {
      ++i;
      bool closed = false;
      while (i < line.size()) {
        if (line[i] == '"') {
          if (i + 1 < line.size() && line[i + 1] == '"') {
            field += '"';
            i += 2;
            continue;
          }
          closed = true;
          ++i;
          break;
        }
        field += line[i++];
      }
      if (!closed) {
        bad.emplace(fields.size(),
                    "unterminated quote; accepted: a field in double quotes, \"\" for a quote");
        return fields;
      }
      while (i < line.size() && (blank(line[i]) || line[i] == '\r')) ++i;
      if (i < line.size() && line[i] != ',') {
        bad.emplace(fields.size(), "text after a closing quote; accepted: a comma after the quoted field");
        return fields;
      }
    } else {
      const std::size_t end = std::min(line.find(',', i), line.size());
      field = std::string(trim_csv(line.substr(i, end - i)));
      i = end;
    }
    fields.push_back(std::move(field));
    if (i >= line.size()) break;
    ++i;  // the comma
  }
  return fields;
}

std::string quote_if_needed(const std::string& s) {
  if (s.find_first_of(",\"#") == std::string::npos && trim_csv(s) == s && !s.empty()) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string number17(double v) { return fmt::format("{:.17g}", v); }


}  // namespace

std::string with_nul_shown(std::string message) {
  for (std::size_t at = message.find('\0'); at != std::string::npos; at = message.find('\0', at + 4))
    message.replace(at, 1, "\\x00");
  return message;
}

CsvError::CsvError(std::string source, int line, int column, std::string column_name, std::string problem)
    : LocatedInputError(format_csv_error(source, line, column, column_name, problem), source, line, column,
                        column_name, problem) {}

std::optional<double> parse_number(std::string_view text) {
  double v = 0;
  if (read_number(text, v) == NumberKind::finite) return v;
  return std::nullopt;
}

std::optional<TermAssignment> split_term_assignment(std::string_view text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string_view::npos) return std::nullopt;
  const std::string_view rest = trim_blanks(text.substr(eq + 1));
  const std::size_t space = rest.find_first_of(" \t");
  TermAssignment a;
  a.term = std::string(trim_blanks(text.substr(0, eq)));
  a.value = std::string(rest.substr(0, space));
  if (space != std::string_view::npos) a.unit = std::string(trim_blanks(rest.substr(space)));
  return a;
}

std::string number_cell_problem(std::string_view cell) {
  double v = 0;
  switch (read_number(cell, v)) {
    case NumberKind::finite:
      return "";
    case NumberKind::empty:
      return "empty cell; accepted: a finite number";
    case NumberKind::non_finite:
      return fmt::format("'{}' is not a finite number; accepted: a finite number", cell);
    case NumberKind::not_a_number:
      break;
  }
  // A decimal number beyond the range of double (1e400) is a number, just not one a double holds.
  double parsed = 0;
  const auto [end, ec] = std::from_chars(cell.data(), cell.data() + cell.size(), parsed);
  if (ec == std::errc::result_out_of_range && end == cell.data() + cell.size())
    return fmt::format("'{}' is out of range of double; accepted: a finite number (magnitude below 1.8e308, or 0)",
                       cell);
  return fmt::format("'{}' is not a number; accepted: a decimal number such as 1.5 or -2e-3", cell);
}

std::vector<std::string> split_csv_fields(std::string_view line, CsvFieldProblem& bad) {
  return split_fields(line, bad);
}

void check_csv_header(const std::vector<std::string>& fields, const CsvFieldProblem& bad,
                      const std::string& source, int line_no) {
  if (bad) throw CsvError(source, line_no, static_cast<int>(bad->first + 1), "", bad->second);
  // Duplicates found through a map of the names seen (O(n log n); a pairwise check took seconds for a
  // header of tens of thousands of columns).
  std::map<std::string_view, std::size_t> seen;
  for (std::size_t k = 0; k < fields.size(); ++k) {
    if (fields[k].empty())
      throw CsvError(source, line_no, static_cast<int>(k + 1), "",
                     "empty column name in the header; accepted: a header row naming every column, e.g. x,y");
    const auto [it, fresh] = seen.emplace(fields[k], k);
    if (!fresh)
      throw CsvError(
          source, line_no, static_cast<int>(k + 1), fields[k],
          fmt::format("duplicate column name (also column {}); accepted: unique names", it->second + 1));
  }
  if (std::all_of(fields.begin(), fields.end(),
                  [](const std::string& f) { return parse_number(f).has_value(); }))
    throw CsvError(source, line_no, 1, "",
                   fmt::format("the first row holds numbers, not column names; accepted: a header row naming "
                               "the columns first, e.g. {}",
                               fields.size() == 2 ? "x,y" : "run,a_i,output"));
}

void check_csv_row(std::size_t field_count, const CsvFieldProblem& bad,
                   const std::vector<std::string>& header, const std::string& source, int line_no) {
  if (bad) {
    const std::size_t k = std::min(bad->first, header.size() - 1);
    throw CsvError(source, line_no, static_cast<int>(bad->first + 1), header[k], bad->second);
  }
  if (field_count != header.size()) {
    const std::size_t k = std::min(field_count, header.size());
    throw CsvError(
        source, line_no, static_cast<int>(k + 1), k < header.size() ? header[k] : "",
        fmt::format("ragged row: {} field{}, the header has {}; accepted: one field per column "
                    "({})",
                    field_count, field_count == 1 ? "" : "s", header.size(), fmt::join(header, ", ")));
  }
}

CsvError no_csv_header(const std::string& source, int line_no) {
  return CsvError(source, std::max(line_no, 1), 0, "",
                  fmt::format("{}; accepted: a header row naming the columns, then one row per observation",
                              line_no == 0 ? "empty file" : "no header row (only comments and blank lines)"));
}

// ---------------------------------------------------------------------------------------------------------
// Tables

std::optional<std::size_t> CsvTable::find(std::string_view column) const {
  for (std::size_t k = 0; k < header.size(); ++k)
    if (header[k] == column) return k;
  return std::nullopt;
}

CsvError CsvTable::error_at(std::size_t row, std::size_t column, std::string problem) const {
  return CsvError(source, row_lines[row], static_cast<int>(column + 1), header[column], std::move(problem));
}

Eigen::VectorXd CsvTable::numbers(std::string_view column, std::string_view needed_by) const {
  const auto k = find(column);
  if (!k)
    throw CsvError(source, header_line, 0, std::string(column),
                   fmt::format("no such column (needed by {}); accepted: one of the columns {}", needed_by,
                               fmt::join(header, ", ")));
  Eigen::VectorXd out(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::string& cell = rows[r][*k];
    double v = 0;
    if (read_number(cell, v) != NumberKind::finite) throw error_at(r, *k, number_cell_problem(cell));
    out[static_cast<Eigen::Index>(r)] = v;
  }
  return out;
}

CsvTable parse_csv(std::string_view text, std::string_view source) {
  CsvTable t;
  t.source = std::string(source);
  t.text_sha256 = sha256_hex(text);
  int line_no = 0;
  // A UTF-8 byte-order mark, as spreadsheet programs write it, is not part of the first column's name.
  std::size_t start = text.starts_with("\xEF\xBB\xBF") ? 3 : 0;
  while (start < text.size()) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (t.header.empty()) check_csv_line_ends(line, t.source, line_no);
    const std::string_view content = trim_csv(line);
    if (content.empty()) continue;
    if (content.front() == '#') {
      t.comments.push_back({line_no, std::string(trim_csv(content.substr(1)))});
      continue;
    }
    CsvFieldProblem bad;
    std::vector<std::string> fields = split_fields(line, bad);
    if (t.header.empty()) {
      check_csv_delimiter(line, fields, CsvFormat{}, t.source, line_no);
      check_csv_header(fields, bad, t.source, line_no);
      t.header = std::move(fields);
      t.header_line = line_no;
      continue;
    }
    check_csv_row(fields.size(), bad, t.header, t.source, line_no);
    t.rows.push_back(std::move(fields));
    t.row_lines.push_back(line_no);
  }
  if (t.header.empty()) throw no_csv_header(t.source, line_no);
  return t;
}

CsvTable read_csv_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path, ec))
    throw FileNotFound<CsvError>(name, 0, 0, "", unreadable_file_problem(path));
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw FileNotFound<CsvError>(name, 0, 0, "", unreadable_file_problem(path));
  return parse_csv(text.str(), name);
}

// ---------------------------------------------------------------------------------------------------------
// Writing simulated observations

double output_unit_si(std::string_view output_unit) {
  std::string text(output_unit);
  for (std::size_t pos = text.find("pulse"); pos != std::string::npos; pos = text.find("pulse", pos + 3))
    text.replace(pos, 5, "rad");
  return parse_unit(text).value_si;
}

ObservationsHeader observations_file_header(const IdentificationSpec& spec,
                                            const InstrumentModel& instrument,
                                            std::string_view config_sha256,
                                            const std::vector<ObservationsHeader::Log>& logs,
                                            const std::vector<MeasuredInput>& measured) {
  const double unit = output_unit_si(instrument.output_unit);
  ObservationsHeader h;
  for (const auto& id : spec.free_terms) h.terms.push_back({id, id});
  for (const auto& [id, value] : spec.fixed_terms)
    h.fixed.push_back(
        {{id, id}, value / unit, coefficient_unit(instrument.output_unit, parse_term(id).value(), instrument.g_symbol)});
  h.known = {"rate"};
  h.output_unit = instrument.output_unit;
  h.config_sha256 = std::string(config_sha256);
  h.logs = logs;
  h.measured = measured;
  return h;
}

std::string observations_csv(const Observations<double>& obs, const IdentificationSpec& spec,
                             const InstrumentModel& instrument, std::string_view config_sha256,
                             const std::vector<ObservationsHeader::Log>& logs,
                             const std::vector<MeasuredInput>& measured) {
  const double unit = output_unit_si(instrument.output_unit);
  const ObservationsHeader h = observations_file_header(spec, instrument, config_sha256, logs, measured);

  // Regressor columns in canonical term order.
  std::vector<std::size_t> order(obs.columns.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return term_rank(parse_term(obs.columns[a]).value()) < term_rank(parse_term(obs.columns[b]).value());
  });
  std::string out = format_observations_header(h) + "\n";
  out += "run,a_i,output,rate";
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "," + std::string.
  for (std::size_t k : order) {
    out += ',';
    out += obs.columns[k];
  }
  out += '\n';
  for (Eigen::Index j = 0; j < obs.output.size(); ++j) {
    out += quote_if_needed(obs.runs[static_cast<std::size_t>(j)]);
    for (double v : {obs.input[j], obs.output[j] / unit, obs.known_rate[j] / unit}) {
      out += ',';
      out += number17(v);
    }
    for (std::size_t k : order) {
      out += ',';
      out += number17(obs.regressors(j, static_cast<Eigen::Index>(k)));
    }
    out += '\n';
  }
  return out;
}

// ---------------------------------------------------------------------------------------------------------
// The fit of a table

namespace {
// Finite numbers can still overflow in the fit's columns: x^n of a large input, or the output less a known
// contribution. Each is refused at its row, naming the term and the column it comes from.
void check_finite_problem(const CsvTable& table, const TableFitSpec& spec, const std::vector<TableTerm>& all,
                          const FitProblem& p) {
  for (Eigen::Index i = 0; i < p.y.size(); ++i)
    if (!std::isfinite(p.y[i]))
      throw table.error_at(std::size_t(i), *table.find(spec.output),
                           "the output less the known contributions overflows; accepted: values whose "
                           "difference is a finite number");
  for (Eigen::Index c = 0; c < p.H.cols(); ++c)
    for (Eigen::Index i = 0; i < p.H.rows(); ++i) {
      if (std::isfinite(p.H(i, c))) continue;
      const TableTerm& t = all[std::size_t(c)];
      const std::string& column = t.column.empty() ? spec.input : t.column;
      throw table.error_at(std::size_t(i), *table.find(column),
                           fmt::format("term {} of {} overflows (|{}| too large for its power); accepted: "
                                       "inputs in a unit that keeps x^n finite, e.g. g rather than mg",
                                       t.id, table.rows[std::size_t(i)][*table.find(column)], column));
    }
}
// The highest power of the input among the terms without a column of their own (-1: none); each term a term
// id, given once, and a column for each that is not a power of the input.
int highest_input_power(const std::vector<TableTerm>& all) {
  std::set<std::string> ids;
  int max_power = -1;
  for (const auto& t : all) {
    const auto term = parse_term(t.id);
    if (!term) throw std::invalid_argument(fmt::format("table_fit_problem: '{}' is not a term id", t.id));
    if (!ids.insert(t.id).second)
      throw std::invalid_argument(fmt::format("table_fit_problem: term '{}' is given twice", t.id));
    if (t.column.empty()) {
      if (term->kind != TermKind::power)
        throw std::invalid_argument(fmt::format("table_fit_problem: term '{}' needs a column", t.id));
      max_power = std::max(max_power, term->power);
    }
  }
  return max_power;
}

// The weights 1/σ² of the weight column's σ: each σ positive, and its weight neither overflowing nor
// underflowing.
Eigen::VectorXd table_weights(const CsvTable& table, const std::string& weight_column) {
  const Eigen::VectorXd sigma = table.numbers(weight_column, "the weights");
  const std::size_t column = *table.find(weight_column);
  const auto rows = sigma.size();
  Eigen::VectorXd weights(rows);
  for (Eigen::Index i = 0; i < rows; ++i) {
    if (!(sigma[i] > 0))
      throw table.error_at(
          static_cast<std::size_t>(i), column,
          fmt::format("standard deviation {} is not positive; accepted: σ > 0 (the weight is "
                      "1/σ²)",
                      table.rows[static_cast<std::size_t>(i)][column]));
    weights[i] = 1.0 / (sigma[i] * sigma[i]);
    if (!std::isfinite(weights[i]))
      throw table.error_at(static_cast<std::size_t>(i), column,
                           "standard deviation too small: its weight 1/σ² overflows; accepted: σ > 1e-154");
    if (weights[i] < std::numeric_limits<double>::min())  // underflow: no weight at all
      throw table.error_at(static_cast<std::size_t>(i), column,
                           "standard deviation too large: its weight 1/σ² underflows; accepted: σ < 1e154");
  }
  return weights;
}

}  // namespace

FitProblem table_fit_problem(const CsvTable& table, const TableFitSpec& spec) {
  std::vector<TableTerm> all = spec.terms;
  for (const auto& f : spec.fixed) all.push_back(f.term);
  const int max_power = highest_input_power(all);

  const auto rows = static_cast<Eigen::Index>(table.rows.size());
  const auto free_count = static_cast<Eigen::Index>(spec.terms.size());
  FitProblem p;
  p.y = table.numbers(spec.output, "the output");
  for (const auto& column : spec.known) p.y -= table.numbers(column, "a known contribution");

  Eigen::MatrixXd powers;
  if (max_power >= 1) {
    std::string users;
    for (const auto& t : all)
      if (t.column.empty() && parse_term(t.id)->power >= 1) users += (users.empty() ? "" : ", ") + t.id;
    powers = polynomial_design(table.numbers(spec.input, fmt::format("{}, powers of the input", users)),
                               max_power);
  } else {
    powers = Eigen::MatrixXd::Ones(rows, 1);
  }
  p.H.resize(rows, static_cast<Eigen::Index>(all.size()));
  for (std::size_t k = 0; k < all.size(); ++k) {
    const auto col = static_cast<Eigen::Index>(k);
    const TableTerm& t = all[k];
    p.H.col(col) = t.column.empty() ? powers.col(parse_term(t.id)->power)
                                    : table.numbers(t.column, fmt::format("term {}", t.id));
    p.term_names.push_back(t.id);
  }
  for (const auto& f : spec.fixed) p.fixed[f.term.id] = f.value;
  check_finite_problem(table, spec, all, p);

  if (!spec.weight.empty()) p.weights = table_weights(table, spec.weight);

  if (rows < free_count) {
    std::vector<std::string> names;
    for (const auto& t : spec.terms) names.push_back(t.id);
    throw CsvError(
        table.source, rows > 0 ? table.row_lines.back() : table.header_line, 0, "",
        fmt::format("{} data row{} cannot determine {} free terms ({}); accepted: at least {} rows", rows,
                    rows == 1 ? "" : "s", free_count, fmt::join(names, ", "), free_count));
  }

  const auto run = table.find("run");
  for (std::size_t r = 0; r < table.rows.size(); ++r)
    p.row_labels.push_back(run ? table.rows[r][*run] : fmt::format("line {}", table.row_lines[r]));
  return p;
}

}  // namespace ccal
