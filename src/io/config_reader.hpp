#pragma once
// The TOML configuration reader's pieces (private to the library): the located-error reader of a parsed
// file, the keys each table accepts, and one reader per section (docs/config.md). io/config_file.cpp puts
// them together.
#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include "ccal/core/units.hpp"
#include "ccal/io/config_file.hpp"

namespace ccal::config_reading {

using Keys = std::vector<std::string_view>;

inline std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

// The candidate closest to `word` if it is close enough to be a plausible typing error. Case differences cost
// little: "dr_s" finds "dR_s".
inline std::optional<std::string> closest(std::string_view word, const std::vector<std::string>& candidates) {
  std::optional<std::string> best;
  std::size_t best_distance = 0;
  const std::string w = lower(word);
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(w, lower(c));
    if (!best || d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
  if (best && best_distance <= limit) return best;
  return std::nullopt;
}

// A noise density's text without its per-root-hertz suffix ("/rtHz", "/sqrt(Hz)" or "/√Hz", trailing spaces
// allowed): "0.2 ppm/rtHz" → "0.2 ppm"; nullopt without the suffix.
inline std::optional<std::string_view> without_per_root_hz(std::string_view text) {
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  for (std::string_view suffix : {"/rtHz", "/sqrt(Hz)", "/√Hz"})
    if (text.ends_with(suffix)) return text.substr(0, text.size() - suffix.size());
  return std::nullopt;
}

inline std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
    case toml::node_type::time:
    case toml::node_type::date_time:
      return "a date/time";
    default:
      return "nothing";
  }
}

// A number as TOML holds it (integer or float), if the node is one.
inline std::optional<double> number_of(const toml::node& n) {
  if (const auto* i = n.as_integer()) return double(i->get());
  if (const auto* f = n.as_floating_point()) return f->get();
  return std::nullopt;
}

// The shortest text that reads back as the same double: a message shows what was typed, not a rounding of it
// (r = 1.0000001 is not "1").
inline std::string number_text(double v) { return fmt::format("{}", v); }

// The unit a user most likely means for a dimension, for "such as" examples.
inline std::string example_unit(Dimension d) {
  if (d == kind::angle) return "deg";
  if (d == kind::length) return "m";
  if (d == kind::time) return "s";
  if (d == kind::angular_rate) return "rad/s";
  if (d == kind::acceleration_g) return "g";
  if (d == kind::acceleration) return "m/s^2";
  return si_unit(d);
}

// A place in a file: a job's keys and its set-up's come from two files (config_job.cpp), so a place names its
// file (null: the reader's own).
struct Location {
  int line = 0;
  int column = 0;
  std::shared_ptr<const std::string> file;
};

inline Location where(const toml::source_region& r) {
  return {static_cast<int>(r.begin.line), static_cast<int>(r.begin.column), r.path};
}

// A quantity's output dimension: how an instrument's output unit is written and what it is in SI.
struct OutputUnit {
  std::string text;  // as the user wrote it, e.g. "deg/s"
  Dimension dim;     // SI dimension (pulse counted as rad, see below)
  bool pulse = false;
};

// A string given for a pulse-output instrument must name pulses, so that "deg/s" cannot be silently taken for
// pulses; its pulses are read by core/units.hpp's pulse_as_rad.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(Location at, std::string_view key, std::string problem) const {
    throw ConfigError(at.file && !at.file->empty() ? *at.file : source_, at.line, at.column, std::string(key),
                      std::move(problem));
  }
  [[noreturn]] void fail(const toml::node& n, std::string_view key, std::string problem) const {
    fail(where(n.source()), key, std::move(problem));
  }

  static std::string path(std::string_view parent, std::string_view key) {
    return parent.empty() ? std::string(key) : fmt::format("{}.{}", parent, key);
  }

  // Rejects any key of t not in `allowed`, suggesting the closest allowed one.
  void check_keys(const toml::table& t, std::string_view table_path, const Keys& allowed) const {
    std::vector<std::string> names(allowed.begin(), allowed.end());
    for (const auto& [key, node] : t) {
      if (std::find(allowed.begin(), allowed.end(), key.str()) != allowed.end()) continue;
      const std::string p = path(table_path, key.str());
      if (auto best = closest(key.str(), names))
        fail(where(key.source()), p, fmt::format("unknown key; did you mean '{}'?", *best));
      fail(where(key.source()), p, fmt::format("unknown key; accepted keys: {}", fmt::join(names, ", ")));
    }
  }

  const toml::table* table(const toml::table& parent, std::string_view parent_path, std::string_view key,
                           bool required, std::string_view what_if_missing = {}) const {
    const toml::node* n = parent.get(key);
    const std::string p = path(parent_path, key);
    if (!n) {
      if (required) fail(where(parent.source()), p, fmt::format("missing table; {}", what_if_missing));
      return nullptr;
    }
    if (const auto* t = n->as_table()) return t;
    fail(*n, p, fmt::format("expected a table, got {}", type_name(*n)));
  }

  // A quantity string of the given dimension, in SI; nullopt if absent. `example` is a number and unit in the
  // expected dimension for the message about a bare number (e.g. "2.5 m").
  std::optional<double> quantity(const toml::table& t, std::string_view table_path, std::string_view key,
                                 Dimension dim, const OutputUnit* output = nullptr,
                                 std::string_view example = {}) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    return quantity_node(*n, path(table_path, key), dim, output, example);
  }

  double quantity_node(const toml::node& n, const std::string& p, Dimension dim, const OutputUnit* output,
                       std::string_view example) const {
    const std::string unit = example.empty() ? "1 " + example_unit(dim) : std::string(example);
    if (const auto* s = n.as_string())
      return quantity_text(s->get(), where(n.source()), p, dim, output, unit);
    if (const auto v = number_of(n)) {
      if (dim == kind::dimensionless) {
        if (!std::isfinite(*v)) fail(n, p, "not a finite number; give a finite number");
        return *v;
      }
      // Replace the example's number by the user's, so the hint is the likely intended value.
      const std::string unit_only = unit.substr(unit.find(' ') + 1);
      fail(n, p,
           fmt::format("expected a quantity string such as \"{} {}\", got the bare number {}",
                       number_text(std::isfinite(*v) ? *v : 1.0), unit_only, number_text(*v)));
    }
    fail(n, p, fmt::format("expected a quantity string such as \"{}\", got {}", unit, type_name(n)));
  }

  // Parses a quantity string at a place in the file (see quantity_node).
  double quantity_text(const std::string& written, Location at, const std::string& p, Dimension dim,
                       const OutputUnit* output, std::string_view example) const {
    std::string text = written;
    if (output && output->pulse) {
      if (text.find("pulse") == std::string::npos)
        fail(at, p,
             fmt::format("'{}': the instrument's output_unit is 'pulse/s', so this value must be in pulses; "
                         "accepted: e.g. \"{}\"",
                         text, example));
      text = pulse_as_rad(text);
    }
    try {
      return parse_as(text, dim, "", dim == kind::dimensionless);
    } catch (const UnitError& e) {
      if (output && output->pulse)
        fail(at, p,
             fmt::format("'{}': not a valid quantity in pulses; accepted: e.g. \"{}\"", written, example));
      fail(at, p, e.what());
    }
  }

  std::optional<double> number(const toml::table& t, std::string_view table_path,
                               std::string_view key) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    const std::string p = path(table_path, key);
    const auto v = number_of(*n);
    if (!v) fail(*n, p, fmt::format("expected a number, got {}", type_name(*n)));
    if (!std::isfinite(*v)) fail(*n, p, "not a finite number; give a finite number such as 1.0");
    return v;
  }

  std::optional<std::string> string(const toml::table& t, std::string_view table_path,
                                    std::string_view key) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    if (const auto* s = n->as_string()) return s->get();
    fail(*n, path(table_path, key), fmt::format("expected a string, got {}", type_name(*n)));
  }

  std::optional<bool> boolean(const toml::table& t, std::string_view table_path, std::string_view key) const {
    const toml::node* n = t.get(key);
    if (!n) return std::nullopt;
    if (const auto* b = n->as_boolean()) return b->get();
    fail(*n, path(table_path, key), fmt::format("expected true or false, got {}", type_name(*n)));
  }

  // One of a list of words; the message lists them.
  template <class E>
  std::optional<E> word(const toml::table& t, std::string_view table_path, std::string_view key,
                        const std::vector<std::pair<std::string_view, E>>& words) const {
    std::vector<std::string> names;
    for (const auto& [name, value] : words) names.emplace_back(name);
    if (const toml::node* n = t.get(key); n && !n->is_string())
      fail(*n, path(table_path, key),
           fmt::format("expected a string, got {}; accepted: \"{}\"", type_name(*n), fmt::join(names, "\", \"")));
    const auto s = string(t, table_path, key);
    if (!s) return std::nullopt;
    for (const auto& [name, value] : words)
      if (name == *s) return value;
    const toml::node& n = *t.get(key);
    const auto best = closest(*s, names);
    fail(n, path(table_path, key),
         fmt::format("unknown value '{}'; {}accepted: {}", *s,
                     best ? fmt::format("did you mean '{}'? ", *best) : std::string(),
                     fmt::join(names, ", ")));
  }

  void require_positive(const toml::table& t, std::string_view table_path, std::string_view key, double v,
                        std::string_view hint) const {
    if (v > 0) return;
    fail(*t.get(key), path(table_path, key),
         fmt::format("must be positive, got {}; accepted: a positive value, {}", written(*t.get(key), v), hint));
  }
  void require_non_negative(const toml::table& t, std::string_view table_path, std::string_view key, double v,
                            std::string_view hint) const {
    if (v >= 0) return;
    fail(*t.get(key), path(table_path, key),
         fmt::format("must not be negative, got {}; {}", written(*t.get(key), v), hint));
  }

  // Plausibility: a value beyond what any centrifuge test uses is a typing or unit error.
  void require_at_most(const toml::table& t, std::string_view table_path, std::string_view key, double v,
                       double most, std::string_view accepted) const {
    if (v <= most) return;
    fail(*t.get(key), path(table_path, key),
         fmt::format("{} is implausible; accepted: {}", written(*t.get(key), v), accepted));
  }

  // The lower end of the same: a positive value below what any centrifuge test uses ("1e-300 m"), shown as
  // written.
  void require_at_least(const toml::table& t, std::string_view table_path, std::string_view key, double v,
                        double least, std::string_view accepted) const {
    if (v >= least) return;
    fail(*t.get(key), path(table_path, key),
         fmt::format("{} is implausible; accepted: {}", written(*t.get(key), v), accepted));
  }

  const std::string& source() const { return source_; }

  // A value in a message as the user wrote it ("1e300 m", with its unit), or the number of a bare one.
  static std::string written(const toml::node& n, double v) {
    return n.value<std::string>().value_or(number_text(v));
  }

 private:
  std::string source_;
};

inline const Keys kRootKeys{"site",       "centrifuge", "errors",         "tolerances", "correlations",
                            "instrument", "plan",       "identification", "design",     "certificate",
                            "inputs",     "setup",      "instruments"};
// The tables of the machine and the lab: a job's set-up holds them (config_job.cpp), Config::setup_sha256 is
// theirs. Every other table but [certificate] and [design] is the job's and changes the numbers.
inline const Keys kSetupKeys{"site", "centrifuge", "errors", "tolerances", "correlations", "inputs"};
inline const Keys kWordingKeys{"certificate", "design"};

// A job file's root merged with the set-up it names (`setup = "…toml"`, relative to the job's folder): the
// set-up's tables, each table the job gives replacing the set-up's of that name whole. setup_source: the set-up's
// path as read ("" for a file without `setup`). Every node keeps its own file and line for messages.
toml::table with_setup(const Reader& job_reader, toml::table job, std::string& setup_source);

// SHA-256 of the canonical TOML text (keys sorted, comments and layout dropped) of the root's tables named in
// `keys` (include) or of all but those (exclude).
enum class KeySelection { include, exclude };
std::string tables_sha256(const toml::table& root, const Keys& keys, KeySelection selection);
inline const Keys kInputKeys{"id", "description", "unit", "bound", "distribution", "group", "cost", "floor",
                             "sensitivity"};
inline const Keys kCorrelationKeys{"between", "r"};
inline const Keys kSiteKeys{"latitude", "g", "height", "earth_rotation", "g_unit"};
inline const Keys kCentrifugeKeys{
    "radius",         "base_plane_height", "instrument_height", "horizontal_axis_angle",
    "harmonic_order", "platform_control",  "main_rate_noise",   "platform_rate_noise", "encoders"};
inline const Keys kRateNoiseKeys{"allan_deviation", "tau"};
inline const Keys kToleranceKeys{"bound", "distribution", "group", "cost", "floor"};
inline const Keys kInstrumentKeys{"model",   "output_unit", "rate_gain",         "noise_density",
                                  "quantum", "terms",       "sampling_resistor"};
// The keys an [[instruments]] entry has besides an [instrument] table's.
inline const Keys kMountedInstrumentKeys{"id", "position", "azimuth", "serial_number"};
inline const Keys kPlanKeys{"duration", "platform", "terminal_phase", "initial_phase", "arm_azimuth",
                            "mounting", "runs"};
inline const Keys kIdentificationKeys{"terms", "fixed", "compensate", "mode", "paper_cross_terms"};
inline const Keys kRunKeys{"name",           "g_level",       "speed",       "duration", "platform",
                           "terminal_phase", "initial_phase", "arm_azimuth", "mounting"};

inline const Keys kDesignKeys{"runs",
                              "total_time",
                              "max_g",
                              "g_levels",
                              "g_range",
                              "g_step",
                              "durations",
                              "turn_fractions",
                              "phase",
                              "phases",
                              "phase_step",
                              "arm_azimuths",
                              "azimuth_step",
                              "mountings",
                              "platforms",
                              "refine",
                              "objective",
                              "coefficients",
                              "targets",
                              "weights",
                              "starts",
                              "seed",
                              "g_resolution",
                              "duration_resolution",
                              "angle_resolution",
                              "min_g_levels"};

// The sections, in file order (config_sections_centrifuge.cpp, config_sections_plan.cpp).
Site read_site(const Reader& r, const toml::table& root);
CentrifugeModel read_centrifuge(const Reader& r, const toml::table& root);
// [errors] of a configuration (chain_errors null: the chain's inputs are refused) or of a truth file (the
// chain's errors into *chain_errors); `config` names the chain's inputs (its fixed terms, [[inputs]]).
void read_errors(const Reader& r, const toml::table& root, const Config& config, CentrifugeModel& model,
                 std::vector<std::pair<int, double>>* chain_errors);
// The code of a key of [errors] or [tolerances] (config_sections_centrifuge.cpp): a layout parameter, or with
// `chain` an input of its measuring chain; fails with the accepted ids otherwise.
int parameter_index(const Reader& r, const ErrorLayout& layout, const toml::key& key, std::string_view table,
                    const Config* chain = nullptr);
std::vector<std::string> fixed_term_ids(const Config& config);
std::string fixed_term_list(const Config& config);
std::string lab_value_place(const Config& config, int code);
// A value of a chain input in SI (a declared input's in its own unit; a fixed term's also relative to it).
double chain_quantity(const Reader& r, const toml::node& node, const std::string& p, const Config& config,
                      int code);
// The unit a quantity string was written in, if of the dimension (config_sections_tolerances.cpp).
std::string written_unit(const toml::node* node, Dimension dim);
// [tolerances] and the bounds of [[inputs]], after the instrument, the identification and [[inputs]].
std::vector<Tolerance> read_tolerances(const Reader& r, const toml::table& root, const Config& config);
void read_tolerance_entry(const Reader& r, const toml::table& entry, const toml::node& node, const std::string& p,
                          const Config& config, Tolerance& tol);
// [[inputs]] (config_sections_inputs.cpp): the declared inputs into config.chain, then their tolerances.
void read_declared_inputs(const Reader& r, const toml::table& root, Config& config);
void read_declared_tolerances(const Reader& r, const toml::table& root, const Config& config,
                              std::vector<Tolerance>& out);
// [[correlations]] (config_sections_correlations.cpp), after the tolerances it refers to.
std::vector<Correlation> read_correlations(const Reader& r, const toml::table& root,
                                           const std::vector<Tolerance>& tolerances);
InstrumentModel read_instrument(const Reader& r, const toml::table& root);
// An [instrument] table at `path` (its messages name that path).
InstrumentModel read_instrument_table(const Reader& r, const toml::table& table, std::string_view path);
// One entry of [[instruments]] (config_sections_instruments.cpp): its id, model, place and azimuth.
struct MountedInstrument {
  std::string id;
  InstrumentModel model;
  double x5 = 0, y5 = 0;  // its place on the base plane [m]
  double azimuth5 = 0;    // its turn about z5 [rad]
  // Its serial number, the [certificate]'s for this instrument (its certificate and history); "": none given.
  std::string serial_number;
  long line = 0;          // the entry's line, for messages
  long serial_line = 0;   // serial_number's line, for messages
};
// [[instruments]], in the file's order; empty without the array. Refuses it beside [instrument], an entry
// without an id, a repeated or malformed id, and the [instrument] table's own errors.
std::vector<MountedInstrument> read_instruments(const Reader& r, const toml::table& root);
TestPlan read_plan(const Reader& r, const toml::table& root, const Geometry& geometry, const Site& site);
void read_identification(const Reader& r, const toml::table& root, const InstrumentModel& instrument,
                         IdentificationSpec& spec, ModelMode& mode);
// [design] (config_sections_design.cpp); the coefficients' units are checked against the free terms.
DesignSpace read_design(const Reader& r, const toml::table& root, const InstrumentModel& instrument,
                        const IdentificationSpec& spec);
// [certificate] (config_sections_certificate.cpp): its fields as written, the dates checked; unset if absent.
std::optional<Certificate> read_certificate(const Reader& r, const toml::table& root);

// A TOML text parsed, a syntax error located as every other (the files ccal reads: configuration, truth, log
// manifest).
// `accepted`, when given, ends a syntax error's message: what the file should be.
inline toml::table parse_toml(const Reader& r, std::string_view text, std::string_view source_name,
                              std::string_view accepted = {}) {
  toml::table root;
  // Bytes that are no UTF-8 (a binary file, text in UTF-16 or Latin-1) are said to be what they likely are.
  const auto tail = [&](std::string_view description) {
    if (description.find("invalid utf-8") != std::string_view::npos)
      return std::string("; accepted: a TOML text file in UTF-8 (a binary file, or text in UTF-16 or Latin-1, "
                         "is not one: convert it, e.g. iconv -t UTF-8)");
    // A JSON document (a statement, a result of ccal) given for a TOML file is said to be one.
    const std::size_t first = text.find_first_not_of(" \t\r\n\xEF\xBB\xBF");  // blanks, a byte-order mark
    const std::string_view json = first != std::string_view::npos && text[first] == '{'
                                      ? " (the file opens a JSON document, a statement or a result of ccal?, not TOML)"
                                      : "";
    return accepted.empty() ? std::string(json) : fmt::format("{}; accepted: {}", json, accepted);
  };
#if TOML_EXCEPTIONS
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    r.fail(where(e.source()), "", fmt::format("TOML syntax error: {}{}", e.description(), tail(e.description())));
  }
#else
  auto result = toml::parse(text, source_name);
  if (!result)
    r.fail(where(result.error().source()), "",
           fmt::format("TOML syntax error: {}{}", result.error().description(),
                       tail(result.error().description())));
  root = std::move(result).table();
#endif
  return root;
}

// A file's text; FileNotFound<ConfigError> with `missing` as the problem when it cannot be read.
// (default: why, unreadable_file_problem).
inline std::string read_file_text(const std::filesystem::path& path, std::string_view missing = {}) {
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  const auto refuse = [&] {
    return FileNotFound<ConfigError>(path.string(), 0, 0, "",
                                     missing.empty() ? unreadable_file_problem(path) : std::string(missing));
  };
  if (!in || std::filesystem::is_directory(path, ec)) throw refuse();
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw refuse();
  return text.str();
}

}  // namespace ccal::config_reading
