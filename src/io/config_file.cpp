#include "ccal/io/config_file.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "ccal/core/sha256.hpp"
#include "ccal/core/units.hpp"
#include "ccal/io/observation_csv.hpp"
#include "config_reader.hpp"

namespace ccal {

// ---------------------------------------------------------------------------------------------------------
// Errors, distributions, run selection, edit distance

namespace {
std::string format_config_error(const std::string& source, int line, int column, const std::string& key,
                                const std::string& problem) {
  std::string out = source;
  if (line > 0) out += fmt::format(":{}:{}", line, std::max(column, 1));
  out += ": ";
  if (!key.empty()) out += key + ": ";
  out += problem;
  return with_nul_shown(std::move(out));  // a TOML string may hold "\u0000"
}
}  // namespace

ConfigError::ConfigError(std::string source, int line, int column, std::string key, std::string problem)
    : LocatedInputError(format_config_error(source, line, column, key, problem), source, line, column, key,
                        problem) {}

// Insertions, deletions, substitutions and swaps of two adjacent characters, one each (the optimal string
// alignment distance): "shwo" is one step from "show", as a typist's slip is.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  const std::size_t w = b.size() + 1;
  std::vector<std::size_t> d((a.size() + 1) * w);
  for (std::size_t j = 0; j < w; ++j) d[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    d[i * w] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t best = std::min({d[(i - 1) * w + j] + 1, d[i * w + j - 1] + 1,
                                   d[(i - 1) * w + j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        best = std::min(best, d[(i - 2) * w + j - 2] + 1);
      d[i * w + j] = best;
    }
  }
  return d[a.size() * w + b.size()];
}

std::optional<std::string> nearest_name(std::string_view typed, std::span<const std::string> names) {
  const std::string* nearest = nullptr;
  const std::string* prefixed = nullptr;
  std::size_t best = 0, prefixed_count = 0;
  for (const std::string& name : names) {
    const std::size_t d = edit_distance(typed, name);
    if (nearest == nullptr || d < best) best = d, nearest = &name;
    if (!typed.empty() && name.starts_with(typed)) ++prefixed_count, prefixed = &name;
  }
  if (nearest != nullptr && 3 * best <= nearest->size()) return *nearest;
  if (prefixed_count == 1) return *prefixed;
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------------------
// Public interface

using namespace config_reading;

namespace {

// Every table of a configuration but the instrument's, for that instrument.
Config read_tables(const Reader& r, const toml::table& root, std::string_view text, std::string_view source_name,
                   const std::string& setup_source, InstrumentModel instrument) {
  Config cfg;
  cfg.setup_source = setup_source;
  cfg.source = std::string(source_name);
  cfg.text_sha256 = sha256_hex(text);
  cfg.numbers_sha256 = tables_sha256(root, kWordingKeys, KeySelection::exclude);
  cfg.setup_sha256 = tables_sha256(root, kSetupKeys, KeySelection::include);
  cfg.site = read_site(r, root);
  cfg.centrifuge = read_centrifuge(r, root);
  cfg.instrument = std::move(instrument);
  cfg.instrument.g_symbol = cfg.site.unit_g > 0 ? "gn" : "g";
  cfg.plan = read_plan(r, root, cfg.centrifuge.geometry, cfg.site);
  read_identification(r, root, cfg.instrument, cfg.identification, cfg.mode);
  // The chain's inputs name the fixed terms and the declared inputs: read after them.
  read_declared_inputs(r, root, cfg);
  read_errors(r, root, cfg, cfg.centrifuge, nullptr);
  cfg.tolerances = read_tolerances(r, root, cfg);
  cfg.correlations = read_correlations(r, root, cfg.tolerances);
  cfg.design = read_design(r, root, cfg.instrument, cfg.identification);
  cfg.certificate = read_certificate(r, root);
  return cfg;
}

// An instrument's serial number in a test of several: its [[instruments]] serial_number, the [certificate]'s for it
// (its certificate and its history are its own). Two instruments of one certificate table would otherwise carry
// the same serial: each entry must then give its own (distinct ids are checked by read_instruments, distinct
// serials here by the caller).
void apply_serial_number(const Reader& r, const MountedInstrument& m, std::size_t k, std::size_t count, Config& c) {
  const std::string entry = fmt::format("instruments[{}]", k + 1);
  if (!m.serial_number.empty()) {
    if (!c.certificate)
      r.fail(Location{int(m.serial_line), 1, nullptr}, Reader::path(entry, "serial_number"),
             "has no [certificate] table to go to (the certificate and the history name an instrument by its serial "
             "number); accepted: a [certificate] table, or no serial_number");
    c.certificate->serial_number = m.serial_number;
  } else if (c.certificate && count > 1) {
    r.fail(Location{int(m.line), 1, nullptr}, entry,
           fmt::format("instrument '{}' has no serial_number, and the [certificate] is for each of the {} "
                       "instruments; accepted: serial_number = \"…\" in every [[instruments]] entry, each its own",
                       m.id, count));
  }
}

// Two instruments of one test with one serial number would share a history: refused at the second.
void check_distinct_serials(const Reader& r, const std::vector<MountedInstrument>& mounted) {
  for (std::size_t k = 1; k < mounted.size(); ++k)
    for (std::size_t j = 0; j < k; ++j)
      if (!mounted[k].serial_number.empty() && mounted[k].serial_number == mounted[j].serial_number)
        r.fail(Location{int(mounted[k].serial_line), 1, nullptr},
               Reader::path(fmt::format("instruments[{}]", k + 1), "serial_number"),
               fmt::format("'{}' is also the serial number of instrument '{}'; accepted: each instrument's own "
                           "serial number",
                           mounted[k].serial_number, mounted[j].id));
}

// An empty file (/dev/null, a file truncated to nothing) or a truth file given for a configuration would be
// refused for its missing [site], a table the user did not think of: said for what it is.
constexpr std::string_view kConfigurationFile =
    "a configuration file ([site], [centrifuge], [instrument], [plan], …; docs/config.md), e.g. examples/lab.toml";

void refuse_what_is_no_configuration(const toml::table& root, std::string_view source) {
  const std::string accepted = fmt::format("accepted: {}", kConfigurationFile);
  if (root.empty())
    throw InputError(fmt::format("{}:1: the file holds no TOML table or key (it is empty); {}", source, accepted));
  if (root.size() == 1 && root.contains("errors"))
    throw InputError(fmt::format("{}:1: the file holds only [errors], as a truth file does (the errors a simulated "
                                 "machine has), not a configuration; {}, with the truth file given as the "
                                 "simulation's truth",
                                 source, accepted));
}

}  // namespace

Config parse_config(std::string_view text, std::string_view source_name) {
  const Reader r{std::string(source_name)};
  std::string setup_source;
  const toml::table root = with_setup(r, parse_toml(r, text, source_name, kConfigurationFile), setup_source);
  refuse_what_is_no_configuration(root, source_name);
  r.check_keys(root, "", kRootKeys);
  std::vector<MountedInstrument> mounted = read_instruments(r, root);
  if (mounted.empty()) return read_tables(r, root, text, source_name, setup_source, read_instrument(r, root));
  check_distinct_serials(r, mounted);
  std::vector<Config> each;
  for (std::size_t k = 0; k < mounted.size(); ++k) {
    MountedInstrument& m = mounted[k];
    Config c = read_tables(r, root, text, source_name, setup_source, std::move(m.model));
    c.instrument_id = m.id;
    // One fingerprint per instrument: observations of one are not those of another.
    c.numbers_sha256 = sha256_hex(c.numbers_sha256 + "\ninstrument " + m.id);
    Geometry& geo = c.centrifuge.geometry;
    geo.x5 = m.x5;
    geo.y5 = m.y5;
    geo.azimuth5 = m.azimuth5;
    // The paper's first-order forms (model.md §5) hold for an instrument on the platform axis only.
    if (c.mode == ModelMode::paper && (m.x5 != 0 || m.y5 != 0 || m.azimuth5 != 0))
      r.fail(Location{int(m.line), 1, nullptr}, fmt::format("instruments[{}]", k + 1),
             fmt::format("instrument '{}' is placed off the platform axis or turned, which the paper's first-order "
                         "rules (mode = \"paper\") do not model; accepted: mode = \"exact\" (the default), or "
                         "no position and azimuth",
                         m.id));
    apply_serial_number(r, m, k, mounted.size(), c);
    each.push_back(std::move(c));
  }
  Config first = each.front();
  first.instruments = std::move(each);
  return first;
}

Config load_config(const std::filesystem::path& path) {
  return parse_config(read_file_text(path), path.string());
}

Config bundled_example() { return parse_config(bundled_example_text(), kBundledExampleName); }

}  // namespace ccal