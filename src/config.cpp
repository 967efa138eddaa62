#include "ccal/config.hpp"

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

#include "ccal/units.hpp"

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
  return out;
}
}  // namespace

ConfigError::ConfigError(std::string source, int line, int column, std::string key, std::string problem)
    : LocatedInputError(format_config_error(source, line, column, key, problem), source, line, column, key,
                        problem) {}


std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::size_t select_run(const TestPlan& plan, std::string_view name_or_index, std::string_view option_name) {
  for (std::size_t k = 0; k < plan.runs.size(); ++k)
    if (plan.runs[k].name == name_or_index) return k;
  std::size_t index = 0;
  const auto [end, ec] =
      std::from_chars(name_or_index.data(), name_or_index.data() + name_or_index.size(), index);
  if (ec == std::errc{} && end == name_or_index.data() + name_or_index.size() && index >= 1 &&
      index <= plan.runs.size())
    return index - 1;
  std::string names;
  for (const Run& r : plan.runs) names += (names.empty() ? "" : ", ") + r.name;
  throw InputError(fmt::format("{}: no run '{}'; give a run name ({}) or an index 1..{}", option_name,
                               name_or_index, names, plan.runs.size()));
}

// ---------------------------------------------------------------------------------------------------------
// The reader

namespace {

using Keys = std::vector<std::string_view>;

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

// The candidate closest to `word` if it is close enough to be a plausible typing error. Case differences cost
// little: "dr_s" finds "dR_s".
std::optional<std::string> closest(std::string_view word, const std::vector<std::string>& candidates) {
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

std::string type_name(const toml::node& n) {
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
std::optional<double> number_of(const toml::node& n) {
  if (const auto* i = n.as_integer()) return double(i->get());
  if (const auto* f = n.as_floating_point()) return f->get();
  return std::nullopt;
}

std::string number_text(double v) { return fmt::format("{:g}", v); }

// The unit a user most likely means for a dimension, for "such as" examples.
std::string example_unit(Dimension d) {
  if (d == kind::angle) return "deg";
  if (d == kind::length) return "m";
  if (d == kind::time) return "s";
  if (d == kind::angular_rate) return "rad/s";
  if (d == kind::acceleration_g) return "g";
  if (d == kind::acceleration) return "m/s^2";
  return si_unit(d);
}

struct Location {
  int line = 0;
  int column = 0;
};

Location where(const toml::source_region& r) {
  return {static_cast<int>(r.begin.line), static_cast<int>(r.begin.column)};
}

// A quantity's output dimension: how an instrument's output unit is written and what it is in SI.
struct OutputUnit {
  std::string text;  // as the user wrote it, e.g. "deg/s"
  Dimension dim;     // SI dimension (pulse counted as rad, see below)
  bool pulse = false;
};

// The instrument's output may be counted in pulses, which units.hpp does not know: "pulse" is read as "rad"
// (a pulse is then one unit of an angle-like count), and a string given for a pulse-output instrument must
// name pulses, so that "deg/s" cannot be silently taken for pulses.
std::string pulse_as_rad(std::string_view text) {
  std::string out(text);
  for (std::size_t pos = out.find("pulse"); pos != std::string::npos; pos = out.find("pulse", pos + 3))
    out.replace(pos, 5, "rad");
  return out;
}

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(Location at, std::string_view key, std::string problem) const {
    throw ConfigError(source_, at.line, at.column, std::string(key), std::move(problem));
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
    const auto s = string(t, table_path, key);
    if (!s) return std::nullopt;
    std::vector<std::string> names;
    for (const auto& [name, value] : words) {
      if (name == *s) return value;
      names.emplace_back(name);
    }
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
         fmt::format("must be positive, got {}; {}", number_text(v), hint));
  }
  void require_non_negative(const toml::table& t, std::string_view table_path, std::string_view key, double v,
                            std::string_view hint) const {
    if (v >= 0) return;
    fail(*t.get(key), path(table_path, key),
         fmt::format("must not be negative, got {}; {}", number_text(v), hint));
  }

  // Plausibility: a value beyond what any centrifuge test uses is a typing or unit error.
  void require_at_most(const toml::table& t, std::string_view table_path, std::string_view key, double v,
                       double most, std::string_view accepted) const {
    if (v <= most) return;
    fail(*t.get(key), path(table_path, key),
         fmt::format("{} is implausible; accepted: {}", number_text(v), accepted));
  }

  const std::string& source() const { return source_; }

 private:
  std::string source_;
};

// ---------------------------------------------------------------------------------------------------------
// Sections

const Keys kRootKeys{"site", "centrifuge", "errors", "tolerances", "instrument", "plan", "identification"};
const Keys kSiteKeys{"latitude", "g", "height", "earth_rotation"};
const Keys kCentrifugeKeys{
    "radius",         "base_plane_height", "instrument_height", "horizontal_axis_angle",
    "harmonic_order", "platform_control",  "main_rate_noise",   "platform_rate_noise"};
const Keys kRateNoiseKeys{"allan_deviation", "tau"};
const Keys kToleranceKeys{"bound", "distribution", "group", "cost"};
const Keys kInstrumentKeys{"model", "output_unit", "rate_gain", "noise_density", "quantum", "terms"};
const Keys kPlanKeys{"duration", "platform", "terminal_phase", "initial_phase", "arm_azimuth",
                     "mounting", "runs"};
const Keys kIdentificationKeys{"terms", "fixed", "compensate", "mode", "paper_cross_terms"};
const Keys kRunKeys{"name",           "g_level",       "speed",       "duration", "platform",
                    "terminal_phase", "initial_phase", "arm_azimuth", "mounting"};

constexpr int kMaxHarmonicOrder = 16;

Site read_site(const Reader& r, const toml::table& root) {
  const toml::table* t = r.table(root, "", "site", true, "add [site] with at least latitude = \"45.75 deg\"");
  r.check_keys(*t, "site", kSiteKeys);
  Site site;
  const auto latitude = r.quantity(*t, "site", "latitude", kind::angle, nullptr, "45.75 deg");
  if (!latitude)
    r.fail(where(t->source()), "site.latitude", "missing value; give e.g. latitude = \"45.75 deg\"");
  if (std::abs(*latitude) > std::numbers::pi / 2 + 1e-12)
    r.fail(
        *t->get("latitude"), "site.latitude",
        fmt::format("{} deg is outside [-90 deg, 90 deg]", number_text(*latitude * 180 / std::numbers::pi)));
  site.latitude = *latitude;
  const double height = r.quantity(*t, "site", "height", kind::length).value_or(0.0);
  if (const auto g = r.quantity(*t, "site", "g", kind::acceleration, nullptr, "9.8 m/s^2")) {
    r.require_positive(*t, "site", "g", *g, "local gravity such as \"9.8 m/s^2\"");
    site.g = *g;
  } else {
    site.g = normal_gravity(site.latitude, height);
  }
  site.earth_rotation = r.boolean(*t, "site", "earth_rotation").value_or(true);
  return site;
}

// A drive's white relative-rate noise (model.md §3.2): a density "0.2 ppm/rtHz", or an Allan deviation of the
// relative rate at an averaging time, { allan_deviation = "0.1 ppm", tau = "4 s" }, N = σ_A √τ.
double read_rate_noise(const Reader& r, const toml::table& t, std::string_view key) {
  const toml::node* n = t.get(key);
  if (!n) return 0.0;
  const std::string kp = Reader::path("centrifuge", key);
  const std::string accepted =
      "accepted: a density such as \"0.2 ppm/rtHz\" or { allan_deviation = \"0.1 ppm\", tau = \"4 s\" }";
  double density = 0.0;
  if (const auto* entry = n->as_table()) {
    r.check_keys(*entry, kp, kRateNoiseKeys);
    const auto sigma = r.quantity(*entry, kp, "allan_deviation", kind::dimensionless, nullptr, "0.1 ppm");
    const auto tau = r.quantity(*entry, kp, "tau", kind::time, nullptr, "4 s");
    if (!sigma || !tau) r.fail(*n, kp, "needs both allan_deviation and tau; " + accepted);
    r.require_positive(*entry, kp, "tau", *tau, "an averaging time > 0 such as \"4 s\"");
    density = *sigma * std::sqrt(*tau);
  } else if (const auto* text = n->as_string()) {
    std::string_view view(text->get());
    while (!view.empty() && view.back() == ' ') view.remove_suffix(1);
    bool stripped = false;
    for (std::string_view suffix : {"/rtHz", "/sqrt(Hz)", "/√Hz"})
      if (view.ends_with(suffix)) {
        view.remove_suffix(suffix.size());
        stripped = true;
        break;
      }
    if (!stripped) r.fail(*n, kp, fmt::format("'{}' must end in /rtHz; {}", text->get(), accepted));
    density =
        r.quantity_text(std::string(view), where(n->source()), kp, kind::dimensionless, nullptr, "0.2 ppm");
  } else {
    r.fail(*n, kp, fmt::format("expected a string or an inline table, got {}; {}", type_name(*n), accepted));
  }
  if (!(density >= 0) || !std::isfinite(density)) r.fail(*n, kp, "must not be negative; " + accepted);
  return density;
}

CentrifugeModel read_centrifuge(const Reader& r, const toml::table& root) {
  const toml::table* t =
      r.table(root, "", "centrifuge", true, "add [centrifuge] with at least radius = \"2.5 m\"");
  const std::string_view p = "centrifuge";
  r.check_keys(*t, p, kCentrifugeKeys);
  Geometry geo;
  const auto radius = r.quantity(*t, p, "radius", kind::length, nullptr, "2.5 m");
  if (!radius) r.fail(where(t->source()), "centrifuge.radius", "missing value; give e.g. radius = \"2.5 m\"");
  r.require_positive(*t, p, "radius", *radius, "the arm radius R0, e.g. \"2.5 m\"");
  r.require_at_most(*t, p, "radius", *radius, 100.0, "an arm radius up to 100 m (SI), e.g. \"2.5 m\"");
  geo.R0 = *radius;
  geo.L = r.quantity(*t, p, "base_plane_height", kind::length).value_or(0.0);
  r.require_non_negative(*t, p, "base_plane_height", geo.L, "a height >= 0 such as \"0.2 m\"");
  geo.l = r.quantity(*t, p, "instrument_height", kind::length).value_or(0.0);
  r.require_non_negative(*t, p, "instrument_height", geo.l, "a height >= 0 such as \"0.05 m\"");
  geo.beta = r.quantity(*t, p, "horizontal_axis_angle", kind::angle).value_or(0.0);
  geo.platform_control =
      r.word(*t, p, "platform_control",
             std::vector<std::pair<std::string_view, PlatformControl>>{
                 {"speed", PlatformControl::speed}, {"phase_locked", PlatformControl::phase_locked}})
          .value_or(PlatformControl::speed);
  int order = 1;
  if (const toml::node* n = t->get("harmonic_order")) {
    const auto* i = n->as_integer();
    if (!i)
      r.fail(*n, "centrifuge.harmonic_order",
             fmt::format("expected an integer 0..{}, got {}", kMaxHarmonicOrder, type_name(*n)));
    if (i->get() < 0 || i->get() > kMaxHarmonicOrder)
      r.fail(*n, "centrifuge.harmonic_order",
             fmt::format("{} is out of range; accepted: an integer 0..{}", i->get(), kMaxHarmonicOrder));
    order = static_cast<int>(i->get());
  }
  CentrifugeModel model(geo, order);
  model.rate_noise = {read_rate_noise(r, *t, "main_rate_noise"),
                      read_rate_noise(r, *t, "platform_rate_noise")};
  return model;
}

Dimension parameter_dimension(SourceUnit u) {
  switch (u) {
    case SourceUnit::rad:
      return kind::angle;
    case SourceUnit::m:
      return kind::length;
    case SourceUnit::rad_per_s:
      return kind::angular_rate;
    case SourceUnit::m_per_rad_per_s_squared:
      return kind::length / pow(kind::angular_rate, 2);
    case SourceUnit::relative:
      return kind::dimensionless;
  }
  return kind::dimensionless;
}

std::string parameter_example(SourceUnit u) {
  switch (u) {
    case SourceUnit::rad:
      return "1e-5 rad";
    case SourceUnit::m:
      return "25 um";
    case SourceUnit::rad_per_s:
      return "0.5e-6 rad/s";
    case SourceUnit::m_per_rad_per_s_squared:
      return "8.5e-8 m/(rad/s)^2";
    case SourceUnit::relative:
      return "10 ppm";
  }
  return "1";
}

// Index of an error parameter named by a key of [errors] or [tolerances]; fails with the closest id.
int parameter_index(const Reader& r, const ErrorLayout& layout, const toml::key& key,
                    std::string_view table) {
  const std::string p = Reader::path(table, key.str());
  if (auto i = layout.find_parameter(key.str())) {
    const Channel& c = channels()[layout.parameter_channel(*i)];
    const bool ripple = c.kind == ErrorKind::main_ripple || c.kind == ErrorKind::platform_ripple;
    if (ripple && layout.parameter_harmonic(*i) == 0)
      r.fail(where(key.source()), p,
             fmt::format("a rate ripple has no constant term (a constant rate error is {}); accepted: "
                         "{}_c<k>, {}_s<k> with 1 <= k <= harmonic_order",
                         c.kind == ErrorKind::main_ripple ? "domega" : "dOmega", c.id, c.id));
    return *i;
  }
  const ErrorLayout widest(kMaxHarmonicOrder);
  if (auto i = widest.find_parameter(key.str()))
    r.fail(where(key.source()), p,
           fmt::format(
               "harmonic {} is above centrifuge.harmonic_order = {}; raise harmonic_order to at least {}",
               widest.parameter_harmonic(*i), layout.harmonic_order(), widest.parameter_harmonic(*i)));
  if (auto c = find_channel(key.str()); c && channels()[*c].joint != Joint::none)
    r.fail(
        where(key.source()), p,
        fmt::format("'{0}' is a dynamic channel, whose parameters are its Fourier coefficients; did you mean "
                    "'{0}_c0'? accepted: {0}_c0 (constant), {0}_c<k>, {0}_s<k> with k <= harmonic_order",
                    key.str()));
  std::vector<std::string> ids = layout.parameter_ids();
  std::string hint;
  if (auto best = closest(key.str(), ids)) hint = fmt::format("did you mean '{}'? ", *best);
  std::string statics, dynamics;
  for (const Channel& c : channels()) {
    std::string& list = c.joint == Joint::none ? statics : dynamics;
    list += (list.empty() ? "" : ", ") + std::string(c.id);
  }
  r.fail(where(key.source()), p,
         fmt::format("unknown error parameter; {}accepted: a static id ({}) or a dynamic channel ({}) "
                     "with _c<k> or _s<k>, k <= harmonic_order (e.g. dx3_c1)",
                     hint, statics, dynamics));
}

void read_errors(const Reader& r, const toml::table& root, CentrifugeModel& model) {
  const toml::table* t = r.table(root, "", "errors", false);
  if (!t) return;
  for (const auto& [key, node] : *t) {
    const int index = parameter_index(r, model.layout, key, "errors");
    const SourceUnit u = model.layout.parameter_unit(index);
    model.errors[index] = r.quantity_node(node, Reader::path("errors", key.str()), parameter_dimension(u),
                                          nullptr, parameter_example(u));
  }
}

std::vector<Tolerance> read_tolerances(const Reader& r, const toml::table& root, const ErrorLayout& layout) {
  std::vector<Tolerance> out;
  const toml::table* t = r.table(root, "", "tolerances", false);
  if (!t) return out;
  const std::vector<std::pair<std::string_view, Distribution>> distributions{
      {"normal", Distribution::normal},
      {"uniform", Distribution::uniform},
      {"triangular", Distribution::triangular},
      {"arcsine", Distribution::arcsine}};
  for (const auto& [key, node] : *t) {
    Tolerance tol;
    tol.parameter = parameter_index(r, layout, key, "tolerances");
    tol.id = layout.parameter_id(tol.parameter);
    const SourceUnit u = layout.parameter_unit(tol.parameter);
    const Dimension dim = parameter_dimension(u);
    const std::string p = Reader::path("tolerances", key.str());
    if (const auto* entry = node.as_table()) {
      r.check_keys(*entry, p, kToleranceKeys);
      const auto bound = r.quantity(*entry, p, "bound", dim, nullptr, parameter_example(u));
      if (!bound)
        r.fail(node, p + ".bound",
               fmt::format("missing value; give e.g. {{ bound = \"{}\" }}", parameter_example(u)));
      r.require_positive(*entry, p, "bound", *bound,
                         "the tolerance bound, e.g. \"" + parameter_example(u) + "\"");
      tol.bound = *bound;
      tol.distribution = r.word(*entry, p, "distribution", distributions).value_or(Distribution::normal);
      tol.group = r.string(*entry, p, "group").value_or("");
      if (const auto cost = r.number(*entry, p, "cost")) {
        r.require_positive(*entry, p, "cost", *cost, "a relative cost weight such as 1.0");
        tol.cost = *cost;
      }
    } else {
      tol.bound = r.quantity_node(node, p, dim, nullptr, parameter_example(u));
      if (!(tol.bound > 0))
        r.fail(node, p,
               fmt::format("must be positive, got {}; the standard uncertainty, e.g. \"{}\"",
                           number_text(tol.bound), parameter_example(u)));
    }
    out.push_back(std::move(tol));
  }
  std::sort(out.begin(), out.end(),
            [](const Tolerance& a, const Tolerance& b) { return a.parameter < b.parameter; });
  return out;
}

// Coefficient dimension of a term for an output dimension.
Dimension term_dimension(const TermSpec& term, Dimension output) {
  switch (term.kind) {
    case TermKind::power:
      return kind::coefficient(output, term.power);
    case TermKind::p:
    case TermKind::o:
      return kind::coefficient(output, 1);
    case TermKind::rate:
      return output / kind::angular_rate;
    default:
      return kind::coefficient(output, 2);
  }
}

InstrumentModel read_instrument(const Reader& r, const toml::table& root) {
  const toml::table* t = r.table(root, "", "instrument", false);
  if (!t) return paper_piga();
  const std::string_view p = "instrument";
  r.check_keys(*t, p, kInstrumentKeys);
  enum class Model { piga, ieee };
  const Model model =
      r.word(*t, p, "model",
             std::vector<std::pair<std::string_view, Model>>{{"piga", Model::piga}, {"ieee", Model::ieee}})
          .value_or(Model::piga);

  InstrumentModel m = model == Model::piga ? paper_piga() : InstrumentModel{};
  if (model == Model::ieee) {
    m.name = "IEEE-style accelerometer";
    m.output_unit = "g";
    m.rate_gain = 0.0;
    m.term_ids.clear();
    m.coefficients.resize(0);
  }

  // Output unit: an angular rate (rate-output PIGA), a g-level, an acceleration, or pulses per second.
  OutputUnit out{m.output_unit, kind::angular_rate, false};
  if (const auto text = r.string(*t, p, "output_unit")) {
    out.text = *text;
    const std::string accepted =
        "accepted: an angular rate (deg/s, rad/s, deg/h), a g-level (g, mg, ug), "
        "an acceleration (m/s^2) or pulse/s";
    if (*text == "pulse/s") {
      out.pulse = true;
      out.dim = kind::angular_rate;
    } else {
      try {
        const Quantity q = parse_unit(*text);
        if (q.dim != kind::angular_rate && q.dim != kind::acceleration_g && q.dim != kind::acceleration)
          r.fail(*t->get("output_unit"), "instrument.output_unit",
                 fmt::format("'{}' is {}; {}", *text, describe(q.dim), accepted));
        out.dim = q.dim;
      } catch (const UnitError& e) {
        r.fail(*t->get("output_unit"), "instrument.output_unit", fmt::format("{}; {}", e.what(), accepted));
      }
    }
    m.output_unit = *text;
  } else if (model == Model::ieee) {
    out = {"g", kind::acceleration_g, false};
  }

  if (const toml::table* terms = r.table(*t, p, "terms", false)) {
    struct Parsed {
      TermSpec spec;
      std::string id;
      double value;
    };
    std::vector<Parsed> parsed;
    const std::vector<std::string> valid = all_term_ids();
    for (const auto& [key, node] : *terms) {
      const std::string kp = Reader::path("instrument.terms", key.str());
      const auto spec = parse_term(key.str());
      if (!spec) {
        const auto best = closest(key.str(), valid);
        r.fail(where(key.source()), kp,
               fmt::format("not a term id; {}accepted: {}",
                           best ? fmt::format("did you mean '{}'? ", *best) : "", fmt::join(valid, ", ")));
      }
      const Dimension dim = term_dimension(*spec, out.dim);
      std::string example = out.text;
      if (spec->kind == TermKind::rate)
        example += "/(rad/s)";
      else if (const int order = term_dimension(*spec, kind::dimensionless).g_level; order != 0)
        example += -order == 1 ? "/g" : fmt::format("/g^{}", -order);
      const double v = r.quantity_node(node, kp, dim, &out, "1 " + example);
      parsed.push_back({*spec, std::string(key.str()), v});
    }
    std::sort(parsed.begin(), parsed.end(),
              [](const Parsed& a, const Parsed& b) { return term_rank(a.spec) < term_rank(b.spec); });
    m.term_ids.clear();
    m.coefficients.resize(Eigen::Index(parsed.size()));
    for (std::size_t k = 0; k < parsed.size(); ++k) {
      m.term_ids.push_back(parsed[k].id);
      m.coefficients[Eigen::Index(k)] = parsed[k].value;
    }
  } else if (model == Model::ieee) {
    r.fail(where(t->source()), "instrument.terms",
           "missing table; model 'ieee' needs [instrument.terms] with coefficients, e.g. K1 = \"1 g/g\"");
  } else if (out.dim != kind::angular_rate || out.pulse) {
    r.fail(*t->get("output_unit"), "instrument.output_unit",
           fmt::format("'{}' cannot use the paper's PIGA coefficients, which are in deg/s; give "
                       "[instrument.terms] in this unit or use an angular-rate output such as deg/s",
                       out.text));
  }

  if (const auto gain = r.number(*t, p, "rate_gain")) m.rate_gain = *gain;

  if (const toml::node* n = t->get("noise_density")) {
    const std::string kp = "instrument.noise_density";
    const auto* s = n->as_string();
    if (!s)
      r.fail(*n, kp,
             fmt::format("expected a quantity string such as \"0.001 {}/rtHz\", got {}", out.text,
                         type_name(*n)));
    std::string text = s->get();
    bool stripped = false;
    for (std::string_view suffix : {"/rtHz", "/sqrt(Hz)", "/√Hz"}) {
      std::string_view view(text);
      while (!view.empty() && view.back() == ' ') view.remove_suffix(1);
      if (view.ends_with(suffix)) {
        text = std::string(view.substr(0, view.size() - suffix.size()));
        stripped = true;
        break;
      }
    }
    if (!stripped)
      r.fail(*n, kp,
             fmt::format("'{}' must end in /rtHz (or /sqrt(Hz)); accepted: \"<value> {}/rtHz\"", s->get(),
                         out.text));
    const double v = r.quantity_text(text, where(n->source()), kp, out.dim, &out, "0.001 " + out.text);
    if (v < 0)
      r.fail(*n, kp,
             fmt::format("must not be negative; a noise density >= 0 such as \"0.001 {}/rtHz\"", out.text));
    m.noise_density = v;
  }
  if (const toml::node* n = t->get("quantum")) {
    const Dimension dim = out.dim * kind::time;
    const double v = r.quantity_node(*n, "instrument.quantum", dim, &out, "0 " + si_unit(dim));
    if (v < 0) r.fail(*n, "instrument.quantum", "must not be negative; a quantisation step >= 0");
    m.quantum = v;
  }
  return m;
}

// Plan-level defaults and the run-level values that override them.
struct RunFields {
  std::optional<double> duration;
  std::optional<PlatformMode> platform;
  std::optional<double> initial_phase, terminal_phase;
  std::optional<double> arm_azimuth;
  std::optional<Mounting> mounting;
};

RunFields read_run_fields(const Reader& r, const toml::table& t, std::string_view p) {
  RunFields f;
  f.duration = r.quantity(t, p, "duration", kind::time, nullptr, "450 s");
  if (f.duration && !(*f.duration > 0))
    r.fail(*t.get("duration"), Reader::path(p, "duration"),
           fmt::format("must be positive, got {} s; a run duration such as \"450 s\"",
                       number_text(*f.duration)));
  if (f.duration) r.require_at_most(t, p, "duration", *f.duration, 1e6, "a run duration up to 1e6 s (11.6 days)");
  f.platform =
      r.word(t, p, "platform",
             std::vector<std::pair<std::string_view, PlatformMode>>{
                 {"counter_rotating", PlatformMode::counter_rotating}, {"fixed", PlatformMode::fixed}});
  f.initial_phase = r.quantity(t, p, "initial_phase", kind::angle, nullptr, "180 deg");
  f.terminal_phase = r.quantity(t, p, "terminal_phase", kind::angle, nullptr, "180 deg");
  if (f.initial_phase && f.terminal_phase) {
    const toml::node* second = t.get("initial_phase");
    const toml::node* other = t.get("terminal_phase");
    if (other->source().begin.line > second->source().begin.line) std::swap(second, other);
    r.fail(*second, Reader::path(p, second == t.get("initial_phase") ? "initial_phase" : "terminal_phase"),
           "both initial_phase and terminal_phase are given; accepted: exactly one of them in one table");
  }
  f.arm_azimuth = r.quantity(t, p, "arm_azimuth", kind::angle, nullptr, "0 deg");
  f.mounting =
      r.word(t, p, "mounting",
             std::vector<std::pair<std::string_view, Mounting>>{{"ia_horizontal", Mounting::ia_horizontal},
                                                                {"ia_reversed", Mounting::ia_reversed},
                                                                {"pa_vertical", Mounting::pa_vertical},
                                                                {"ia_vertical", Mounting::ia_vertical}});
  return f;
}

TestPlan read_plan(const Reader& r, const toml::table& root, const Geometry& geometry, const Site& site) {
  const toml::table* t =
      r.table(root, "", "plan", true, "add [plan] and at least one [[plan.runs]] with g_level");
  r.check_keys(*t, "plan", kPlanKeys);
  const RunFields defaults = read_run_fields(r, *t, "plan");
  const toml::node* runs_node = t->get("runs");
  if (!runs_node)
    r.fail(where(t->source()), "plan.runs",
           "missing runs; add at least one [[plan.runs]] with g_level = \"5 g\"");
  const toml::array* runs = runs_node->as_array();
  if (!runs)
    r.fail(*runs_node, "plan.runs",
           fmt::format("expected an array of tables ([[plan.runs]]), got {}", type_name(*runs_node)));
  if (runs->empty())
    r.fail(*runs_node, "plan.runs", "no runs; add at least one [[plan.runs]] with g_level = \"5 g\"");

  TestPlan plan;
  std::map<std::string, Location> names;
  for (std::size_t k = 0; k < runs->size(); ++k) {
    const toml::node& node = *runs->get(k);
    const std::string p = fmt::format("plan.runs[{}]", k + 1);
    const toml::table* rt = node.as_table();
    if (!rt) r.fail(node, p, fmt::format("expected a table ([[plan.runs]]), got {}", type_name(node)));
    r.check_keys(*rt, p, kRunKeys);
    Run run;
    run.name = r.string(*rt, p, "name").value_or(fmt::format("run{}", k + 1));
    if (run.name.empty()) r.fail(*rt->get("name"), p + ".name", "empty run name; give a name such as \"5g\"");
    const Location at = rt->get("name") ? where(rt->get("name")->source()) : where(rt->source());
    if (const auto it = names.find(run.name); it != names.end())
      r.fail(
          at, p + ".name",
          fmt::format("duplicate run name '{}' (first used at line {}); accepted: a name unique in the plan",
                      run.name, it->second.line));
    names.emplace(run.name, at);

    // A run is set by its g-level A or by the main-axis speed Ω (then A = Ω² R0 / g of the site).
    const auto g_level = r.quantity(*rt, p, "g_level", kind::acceleration_g, nullptr, "5 g");
    const auto speed = r.quantity(*rt, p, "speed", kind::angular_rate, nullptr, "120 rpm");
    if (g_level && speed)
      r.fail(*rt->get("speed"), p + ".speed",
             "both g_level and speed are given; accepted: exactly one of them per run");
    if (!g_level && !speed)
      r.fail(where(rt->source()), p + ".g_level",
             "missing value; give e.g. g_level = \"5 g\" (or the speed, e.g. speed = \"120 rpm\")");
    if (g_level) {
      r.require_positive(*rt, p, "g_level", *g_level, "the centripetal level such as \"5 g\"");
      r.require_at_most(*rt, p, "g_level", *g_level, 1000.0, "a centripetal level up to 1000 g");
      run.g_level = *g_level;
    } else {
      r.require_positive(*rt, p, "speed", *speed, "the main-axis speed such as \"120 rpm\"");
      run.g_level = *speed * *speed * geometry.R0 / site.g;
      r.require_at_most(*rt, p, "speed", run.g_level, 1000.0, "a speed giving at most 1000 g at the radius");
    }

    const RunFields own = read_run_fields(r, *rt, p);
    const auto duration = own.duration ? own.duration : defaults.duration;
    if (!duration)
      r.fail(where(rt->source()), p + ".duration",
             "missing value; give duration = \"450 s\" in this run or in [plan]");
    run.duration = *duration;
    run.mode = own.platform.value_or(defaults.platform.value_or(PlatformMode::counter_rotating));
    if (own.initial_phase || own.terminal_phase) {
      run.initial_phase = own.initial_phase;
      run.terminal_phase = own.terminal_phase;
    } else {
      run.initial_phase = defaults.initial_phase;
      run.terminal_phase = defaults.terminal_phase;
    }
    if (!run.initial_phase && !run.terminal_phase)
      r.fail(where(rt->source()), p + ".terminal_phase",
             "missing phase; give terminal_phase = \"180 deg\" or initial_phase = \"...\" in this run or in "
             "[plan]");
    run.arm_azimuth = own.arm_azimuth.value_or(defaults.arm_azimuth.value_or(0.0));
    run.mounting = own.mounting.value_or(defaults.mounting.value_or(Mounting::ia_horizontal));
    plan.runs.push_back(std::move(run));
  }
  return plan;
}

// A list of term ids (identification.terms or .fixed), each with its place in the file.
std::vector<std::pair<std::string, const toml::node*>> read_term_list(const Reader& r, const toml::table& t,
                                                                      std::string_view key) {
  const std::string p = Reader::path("identification", key);
  const toml::node* n = t.get(key);
  const auto* array = n->as_array();
  if (!array)
    r.fail(
        *n, p,
        fmt::format("expected an array of term ids such as [\"K0\", \"K2\", \"K3\"], got {}", type_name(*n)));
  const std::vector<std::string> valid = all_term_ids();
  std::vector<std::pair<std::string, const toml::node*>> out;
  for (const toml::node& item : *array) {
    const auto* s = item.as_string();
    if (!s) r.fail(item, p, fmt::format("expected a term id string such as \"K2\", got {}", type_name(item)));
    const std::string id = s->get();
    if (!parse_term(id)) {
      const auto best = closest(id, valid);
      r.fail(item, p,
             fmt::format("'{}' is not a term id; {}accepted: {}", id,
                         best ? fmt::format("did you mean '{}'? ", *best) : "", fmt::join(valid, ", ")));
    }
    for (const auto& [seen, node] : out)
      if (seen == id)
        r.fail(item, p,
               fmt::format("'{}' is listed twice (first at line {}); accepted: each term once", id,
                           node->source().begin.line));
    out.emplace_back(id, &item);
  }
  return out;
}

// [identification]: free and fixed terms, compensation and the model of the reduction. Fixed terms are held
// at the instrument's configured coefficients.
void read_identification(const Reader& r, const toml::table& root, const InstrumentModel& instrument,
                         IdentificationSpec& spec, ModelMode& mode) {
  spec = IdentificationSpec{};
  mode = ModelMode::exact;
  const toml::table* t = r.table(root, "", "identification", false);
  const std::string_view p = "identification";
  if (t) r.check_keys(*t, p, kIdentificationKeys);
  if (t && t->get("terms")) {
    spec.free_terms.clear();
    for (const auto& [id, node] : read_term_list(r, *t, "terms")) spec.free_terms.push_back(id);
    if (spec.free_terms.empty())
      r.fail(*t->get("terms"), "identification.terms",
             "empty; give at least one free term, e.g. terms = [\"K0\", \"K2\", \"K3\"]");
  }
  auto is_free = [&](const std::string& id) {
    return std::find(spec.free_terms.begin(), spec.free_terms.end(), id) != spec.free_terms.end();
  };
  spec.fixed_terms.clear();
  if (t && t->get("fixed")) {
    for (const auto& [id, node] : read_term_list(r, *t, "fixed")) {
      if (is_free(id))
        r.fail(*node, "identification.fixed",
               fmt::format("'{}' is also in identification.terms; accepted: a term is either free (terms) or "
                           "held at the instrument's value (fixed), not both",
                           id));
      const auto value = instrument.coefficient(id);
      if (!value)
        r.fail(*node, "identification.fixed",
               fmt::format("the instrument has no term '{}' to hold fixed; accepted: {} (the terms of the "
                           "instrument)",
                           id, fmt::join(instrument.term_ids, ", ")));
      spec.fixed_terms[id] = *value;
    }
  } else if (const auto k1 = instrument.coefficient("K1"); k1 && !is_free("K1")) {
    spec.fixed_terms["K1"] = *k1;
  }
  if (!t) return;
  spec.compensate = r.boolean(*t, p, "compensate").value_or(false);
  spec.paper_cross_terms = r.boolean(*t, p, "paper_cross_terms").value_or(false);
  mode = r.word(*t, p, "mode",
                std::vector<std::pair<std::string_view, ModelMode>>{{"exact", ModelMode::exact},
                                                                    {"paper", ModelMode::paper}})
             .value_or(ModelMode::exact);
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// Public interface

Config parse_config(std::string_view text, std::string_view source_name) {
  const Reader r{std::string(source_name)};
  toml::table root;
#if TOML_EXCEPTIONS
  try {
    root = toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    r.fail(where(e.source()), "", fmt::format("TOML syntax error: {}", e.description()));
  }
#else
  auto result = toml::parse(text, source_name);
  if (!result)
    r.fail(where(result.error().source()), "",
           fmt::format("TOML syntax error: {}", result.error().description()));
  root = std::move(result).table();
#endif
  r.check_keys(root, "", kRootKeys);
  Config cfg;
  cfg.source = std::string(source_name);
  cfg.site = read_site(r, root);
  cfg.centrifuge = read_centrifuge(r, root);
  read_errors(r, root, cfg.centrifuge);
  cfg.tolerances = read_tolerances(r, root, cfg.centrifuge.layout);
  cfg.instrument = read_instrument(r, root);
  cfg.plan = read_plan(r, root, cfg.centrifuge.geometry, cfg.site);
  read_identification(r, root, cfg.instrument, cfg.identification, cfg.mode);
  return cfg;
}

Experiment Config::experiment() const {
  Experiment ex;
  ex.geometry = centrifuge.geometry;
  ex.layout = centrifuge.layout;
  ex.site = site;
  ex.plan = plan;
  ex.instrument = instrument;
  ex.rate_noise = centrifuge.rate_noise;
  return ex;
}

Config load_config(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::ifstream in(path, std::ios::binary);
  std::error_code ec;
  if (!in || std::filesystem::is_directory(path, ec))
    throw ConfigError(name, 0, 0, "", "cannot read the file; check the path and permissions");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ConfigError(name, 0, 0, "", "cannot read the file; check the path and permissions");
  return parse_config(text.str(), name);
}

Config bundled_example() { return parse_config(bundled_example_text(), kBundledExampleName); }

}  // namespace ccal
