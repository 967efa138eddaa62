#include "ccal/intake/log_manifest.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <fstream>
#include <utility>
#include <numbers>
#include <map>
#include <set>
#include <sstream>

#include "../io/config_reader.hpp"

namespace ccal {

using namespace config_reading;

namespace {

const Keys kManifestKeys{"format", "columns", "instruments", "runs"};
const Keys kFormatKeys{"delimiter", "decimal", "comment", "skip_lines", "header_line", "units_row", "max_gap"};
const Keys kColumnKeys{"time", "time_unit", "pulses", "output", "theta1", "gamma", "angle_unit",
                       "counts_per_revolution", "count_rounding", "counter_bits"};
constexpr std::string_view kIsoTime = "iso8601";
constexpr std::string_view kManifestAccepted =
    "a manifest in TOML: the [runs] table (run = \"file\"), optionally [format] and [columns] (docs/cli.md, \"A "
    "folder of logs\")";


// A whole number of lines from 0 (or 1) to a million, or nothing.
std::optional<int> line_count(const Reader& r, const toml::table& t, std::string_view key, int least) {
  if (const toml::node* n = t.get(key); n && !n->is_number())
    r.fail(*n, Reader::path("format", key),
           fmt::format("expected a number, got {}; accepted: a whole number from {} to 1000000, without quotes",
                       type_name(*n), least));
  const auto v = r.number(t, "format", key);
  if (!v) return std::nullopt;
  if (!(*v >= least && *v <= 1e6 && *v == std::floor(*v)))
    r.fail(*t.get(key), Reader::path("format", key),
           fmt::format("{} is not a line {}; accepted: a whole number from {} to 1000000", number_text(*v),
                       least == 0 ? "count" : "number", least));
  return int(*v);
}

void read_format(const Reader& r, const toml::table& root, LogLayout& layout) {
  const toml::table* t = r.table(root, "", "format", false);
  if (!t) return;
  r.check_keys(*t, "format", kFormatKeys);
  CsvFormat& f = layout.format;
  if (const auto d = r.word<char>(*t, "format", "delimiter",
                                  {{"comma", ','}, {"semicolon", ';'}, {"tab", '\t'}, {"whitespace", ' '}}))
    f.delimiter = *d;
  if (const auto d = r.word<char>(*t, "format", "decimal", {{"point", '.'}, {"comma", ','}})) {
    f.decimal = *d;
    if (f.decimal == ',' && f.delimiter == ',')
      r.fail(*t->get("decimal"), "format.decimal",
             "a decimal comma cannot be told from the comma between cells; accepted: decimal = \"comma\" with "
             "delimiter = \"semicolon\", \"tab\" or \"whitespace\"");
  }
  if (const auto c = r.string(*t, "format", "comment")) {
    if (c->find_first_of(" \t\r\n") != std::string::npos)
      r.fail(*t->get("comment"), "format.comment",
             fmt::format("'{}' holds a blank; accepted: the prefix of a comment line without blanks (e.g. \"#\", "
                         "\"//\", \"%\"), or \"\" for none",
                         *c));
    f.comment = *c;
  }
  if (const auto n = line_count(r, *t, "skip_lines", 0)) f.skip_lines = *n;
  if (const auto n = line_count(r, *t, "header_line", 1)) {
    if (*n <= f.skip_lines)
      r.fail(*t->get("header_line"), "format.header_line",
             fmt::format("line {} is among the {} skipped lines; accepted: a header_line after skip_lines, or "
                         "one of the two",
                         *n, f.skip_lines));
    f.header_line = *n;
  }
  if (const auto b = r.boolean(*t, "format", "units_row")) f.units_row = *b;
  if (const toml::node* n = t->get("max_gap")) {
    double gap = 0;
    try {
      gap = r.quantity_node(*n, "format.max_gap", kind::time, nullptr, "10 s");
    } catch (const ConfigError& e) {  // the unit parser's words ("'nan' is not a finite number"), and what is
      if (e.problem().find("accepted") != std::string::npos || e.problem().find("such as") != std::string::npos)
        throw;  // accepted, where they do not say it
      r.fail(*n, "format.max_gap", fmt::format("{}; accepted: a positive time, e.g. \"10 s\"", e.problem()));
    }
    if (!(gap > 0))
      r.fail(*n, "format.max_gap",
             fmt::format("{} s is no gap; accepted: a positive time, e.g. \"10 s\"", number_text(gap)));
    layout.max_gap = gap;
    layout.max_gap_text = n->as_string()->get();
  }
}

// A unit of the given dimension, its SI size; the message names what was expected.
double unit_size(const Reader& r, const toml::table& t, std::string_view key, const std::string& text, Dimension dim,
                 std::string_view accepted) {
  try {
    const Quantity q = parse_unit(text);
    if (q.dim == dim && q.value_si > 0) return q.value_si;
  } catch (const UnitError&) {
  }
  r.fail(*t.get(key), Reader::path("columns", key), fmt::format("'{}' is not {}", text, accepted));
}

// The columns' names (time, pulses, output, theta1, gamma): each not empty, and each column named once,
// defaults included.
void read_column_names(const Reader& r, const toml::table* t, LogColumns& c) {
  std::map<std::string, std::string> used;  // column → the key that names it (or whose default it is)
  for (auto [key, name] : {std::pair{"time", &c.time}, {"pulses", &c.pulses}, {"output", &c.output},
                           {"theta1", &c.theta1}, {"gamma", &c.gamma}}) {
    if (const auto s = r.string(*t, "columns", key)) {
      if (s->empty()) r.fail(*t->get(key), Reader::path("columns", key), "an empty column name; accepted: the "
                                                                          "name of the log's column");
      *name = *s;
    }
    if (const auto [at, fresh] = used.emplace(*name, key); !fresh)
      r.fail(t->get(key) ? *t->get(key) : static_cast<const toml::node&>(*t), Reader::path("columns", key),
             fmt::format("'{}'{} is also the column of columns.{}{}; accepted: a column of its own for each of "
                         "time, pulses, output, theta1 and gamma",
                         *name, t->get(key) ? "" : " (its default)", at->second,
                         t->get(at->second) ? "" : " (its default)"));
  }
}

// The encoders' unit: an angle unit, or counts with counts_per_revolution (only then).
void read_angle_unit(const Reader& r, const toml::table* t, LogLayout& layout) {
  const auto counts = r.number(*t, "columns", "counts_per_revolution");
  if (const auto u = r.string(*t, "columns", "angle_unit")) {
    layout.angle_unit = *u;
    if (*u == "counts") {
      if (!counts)
        r.fail(*t->get("angle_unit"), "columns.angle_unit",
               "counts need the encoders' resolution; accepted: with counts_per_revolution = N (e.g. 16777216)");
      if (!(*counts >= 1 && *counts <= 1e15 && *counts == std::floor(*counts)))
        r.fail(*t->get("counts_per_revolution"), "columns.counts_per_revolution",
               fmt::format("{} is not a whole number of counts; accepted: 1 to 1e15", number_text(*counts)));
      layout.counts_per_revolution = static_cast<long long>(*counts);
      layout.angle_scale = 2 * std::numbers::pi / *counts;
    } else {
      layout.angle_scale = unit_size(r, *t, "angle_unit", *u, kind::angle, "an angle unit; accepted: rad, deg, "
                                                                            "arcsec, … or counts");
    }
  }
  if (counts && layout.angle_unit != "counts")
    r.fail(*t->get("counts_per_revolution"), "columns.counts_per_revolution",
           "is read only for encoders in counts; accepted: with angle_unit = \"counts\"");
}

void read_columns(const Reader& r, const toml::table& root, LogLayout& layout) {
  const toml::table* t = r.table(root, "", "columns", false);
  if (!t) return;
  r.check_keys(*t, "columns", kColumnKeys);
  LogColumns& c = layout.columns;
  read_column_names(r, t, c);
  if (const auto u = r.string(*t, "columns", "time_unit")) {
    c.iso_time = *u == kIsoTime;
    if (!c.iso_time)
      c.time_scale =
          unit_size(r, *t, "time_unit", *u, kind::time,
                    "a time unit; accepted: s, ms, us (or µs), min, …, or \"iso8601\" for timestamps "
                    "(2026-11-30T10:15:02.125Z)");
    layout.time_unit = *u;
  }
  if (const auto bits = r.number(*t, "columns", "counter_bits")) {
    if (!(*bits >= 8 && *bits <= 52 && *bits == std::floor(*bits)))
      r.fail(*t->get("counter_bits"), "columns.counter_bits",
             fmt::format(
                 "{} is not a counter's width; accepted: a whole number of bits from 8 to 52 (e.g. 16, 24, "
                 "32)",
                 number_text(*bits)));
    c.counter_bits = int(*bits);
  }
  read_angle_unit(r, t, layout);
  if (const auto rounding = r.word<CountRounding>(*t, "columns", "count_rounding",
                                                  {{"nearest", CountRounding::nearest},
                                                   {"floor", CountRounding::floor}})) {
    if (layout.angle_unit != "counts")
      r.fail(*t->get("count_rounding"), "columns.count_rounding",
             "is read only for encoders in counts; accepted: with angle_unit = \"counts\"");
    layout.count_rounding = *rounding;
  }
}

void read_runs(const Reader& r, const toml::table& root, const std::filesystem::path& folder, LogManifest& m) {
  const toml::table* t = r.table(root, "", "runs", true, "accepted: run = \"file\" lines, one per logged run");
  for (const auto& [key, node] : *t) {
    const std::string p = Reader::path("runs", key.str());
    const auto* s = node.as_string();
    if (!s) r.fail(node, p, fmt::format("expected a file name, got {}", type_name(node)));
    const std::filesystem::path file(s->get());
    // Inside the folder: a manifest moved with its folder still finds its logs, and reads nothing else.
    bool outside = file.empty() || file.is_absolute();
    for (const auto& part : file) outside = outside || part == "..";
    if (outside)
      r.fail(node, p, fmt::format("'{}' is not a file inside the folder; accepted: a path relative to {}",
                                  s->get(), folder.string()));
    const Location at = where(key.source());
    m.runs.push_back({std::string(key.str()), folder / file, at.line, at.column});
  }
  if (m.runs.empty()) r.fail(where(t->source()), "runs", "no run; accepted: run = \"file\" lines, one per run");
  // A TOML table's keys come sorted: back to the order the manifest wrote them in.
  std::stable_sort(m.runs.begin(), m.runs.end(), [&](const LogManifest::Entry& a, const LogManifest::Entry& b) {
    const auto& sa = t->get(a.run)->source().begin;
    const auto& sb = t->get(b.run)->source().begin;
    return std::pair(sa.line, sa.column) < std::pair(sb.line, sb.column);
  });
}

}  // namespace


namespace {

// [instruments]: per instrument id, { pulses = "column" } or { output = "column" }, a name of its own.
void read_instrument_columns(const Reader& r, const toml::table& root, LogLayout& layout) {
  const toml::table* t = r.table(root, "", "instruments", false);
  if (!t) return;
  // column → what it is already: the time, an encoder's, or an earlier instrument's output
  std::map<std::string, std::string> used{{layout.columns.time, "columns.time"},
                                          {layout.columns.theta1, "columns.theta1"},
                                          {layout.columns.gamma, "columns.gamma"}};
  for (const auto& [key, node] : *t) {
    const std::string p = Reader::path("instruments", key.str());
    const toml::table* entry = node.as_table();
    if (!entry)
      r.fail(node, p,
             fmt::format("expected the instrument's output column, got {}; accepted: {{ pulses = \"count_{}\" }} or "
                         "{{ output = \"rate_{}\" }}",
                         type_name(node), key.str(), key.str()));
    r.check_keys(*entry, p, Keys{"pulses", "output"});
    const auto pulses = r.string(*entry, p, "pulses"), output = r.string(*entry, p, "output");
    if (pulses.has_value() == output.has_value())
      r.fail(node, p, "needs exactly one of pulses (a cumulative count) and output (the output itself)");
    const std::string column = pulses ? *pulses : *output;
    const std::string_view which = pulses ? "pulses" : "output";
    if (column.empty()) r.fail(*entry->get(which), Reader::path(p, which), "an empty column name; accepted: the name "
                                                                            "of the log's column");
    if (const auto [at, fresh] = used.emplace(column, Reader::path(p, which)); !fresh)
      r.fail(*entry->get(which), Reader::path(p, which),
             fmt::format("'{}' is also the column of {}; accepted: a column of its own for each instrument's "
                         "output, besides the time's and the encoders'",
                         column, at->second));
    layout.instruments.push_back({std::string(key.str()), column, pulses.has_value(),
                                  int(node.source().begin.line)});
  }
}

}  // namespace

LogManifest parse_log_manifest(std::string_view text, std::string_view source_name,
                               const std::filesystem::path& folder) {
  const Reader r{std::string(source_name)};
  const toml::table root = parse_toml(r, text, source_name, kManifestAccepted);
  r.check_keys(root, "", kManifestKeys);
  LogManifest m;
  m.source = std::string(source_name);
  read_format(r, root, m.layout);
  read_columns(r, root, m.layout);
  read_instrument_columns(r, root, m.layout);
  read_runs(r, root, folder, m);
  return m;
}

LogManifest read_log_manifest(const std::filesystem::path& folder) {
  std::error_code ec;
  // The manifest's own path (or a log's) given for its folder.
  if (std::filesystem::is_regular_file(folder, ec))
    throw InputError(fmt::format("{}: a file, not the folder of the logs; accepted: the folder that holds {} and "
                                 "the logs, e.g. {}",
                                 folder.string(), kLogManifestName,
                                 folder.has_parent_path() ? folder.parent_path().string() : std::string(".")));
  const std::filesystem::path path = folder / kLogManifestName;
  const std::string text = read_file_text(
      path, fmt::format("no manifest in the folder; accepted: a folder with {} naming each run's file (a "
                        "simulation's logs come with one; docs/cli.md, \"A folder of logs\")",
                        kLogManifestName));
  return parse_log_manifest(text, path.string(), folder);
}

LogLayout parse_log_layout(std::string_view text, std::string_view source_name) {
  const Reader r{std::string(source_name)};
  const toml::table root = parse_toml(r, text, source_name, kLogLayoutAccepted);
  // An empty file (/dev/null, one truncated to nothing) would write ccal's own layout, not the one meant.
  if (root.empty())
    throw InputError(fmt::format("{}:1: the layout file holds no TOML table or key (it is empty); accepted: {} "
                                 "(for ccal's own layout, give no layout file)",
                                 source_name, kLogLayoutAccepted));
  // The runs of simulated logs are the plan's: a layout has the format and the columns only.
  r.check_keys(root, "", Keys{"format", "columns", "instruments"});
  LogLayout layout;
  read_format(r, root, layout);
  read_columns(r, root, layout);
  read_instrument_columns(r, root, layout);
  return layout;
}

LogLayout read_log_layout(const std::filesystem::path& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw ConfigError(file.string(), 0, 0, "", fmt::format("it is a folder; accepted: {}", kLogLayoutAccepted));
  return parse_log_layout(read_file_text(file), file.string());
}

std::string log_manifest_text(const LogLayout& layout, const std::vector<std::pair<std::string, std::string>>& runs) {
  const auto quoted = [](const std::string& s) { return toml::value<std::string>(s); };
  std::ostringstream out;
  out << "# The run logs of this folder, as `ccal reduce CONFIG --logs DIR` reads them (docs/cli.md).\n";
  const CsvFormat& f = layout.format;
  if (!f.is_default() || layout.max_gap > 0) {
    out << "[format]\n";
    if (f.delimiter != ',') out << "delimiter = " << quoted(std::string(csv_delimiter_name(f.delimiter))) << "\n";
    if (f.decimal != '.') out << "decimal = " << quoted("comma") << "\n";
    if (f.comment != "#") out << "comment = " << quoted(f.comment) << "\n";
    if (f.skip_lines > 0) out << "skip_lines = " << f.skip_lines << "\n";
    if (f.header_line > 0) out << "header_line = " << f.header_line << "\n";
    if (f.units_row) out << "units_row = true\n";
    if (layout.max_gap > 0) out << "max_gap = " << quoted(layout.max_gap_text) << "\n";
    out << "\n";
  }
  const LogColumns& c = layout.columns;
  out << "[columns]\n"
      << "time = " << quoted(c.time) << "\n"
      << "time_unit = " << quoted(layout.time_unit.empty() ? std::string("s") : layout.time_unit) << "\n";
  if (layout.instruments.empty())  // else each instrument's column is named in [instruments]
    out << "pulses = " << quoted(c.pulses) << "\n"
        << "output = " << quoted(c.output) << "\n";
  out << "theta1 = " << quoted(c.theta1) << "\n"
      << "gamma = " << quoted(c.gamma) << "\n";
  if (!layout.angle_unit.empty()) out << "angle_unit = " << quoted(layout.angle_unit) << "\n";
  if (layout.angle_unit == "counts") {
    out << "counts_per_revolution = " << layout.counts_per_revolution << "\n";
    out << "count_rounding = " << quoted(std::string(kCountRoundingNames[std::size_t(layout.count_rounding)]))
        << "\n";
  }
  if (c.counter_bits > 0) out << "counter_bits = " << c.counter_bits << "\n";
  if (!layout.instruments.empty()) {
    out << "\n[instruments]  # each instrument's output column\n";
    for (const LogLayout::InstrumentColumn& i : layout.instruments) {
      toml::table column{{i.pulses ? "pulses" : "output", i.column}};
      column.is_inline(true);
      toml::table line;
      line.insert(i.id, std::move(column));
      out << line << "\n";
    }
  }
  out << "\n[runs]\n";
  for (const auto& [run, file] : runs) {
    toml::table line;
    line.insert(run, file);
    out << line << "\n";
  }
  return out.str();
}

}  // namespace ccal
