// The configuration file's [site], [centrifuge], [errors] and [tolerances] sections (docs/config.md).
#include <cstdlib>

#include "ccal/model/error_sources.hpp"
#include "config_reader.hpp"

namespace ccal::config_reading {

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
  // The site is on the Earth: heights from the deepest mines to the highest laboratories, where the normal
  // gravity formula's free-air term holds; local gravity within the range of those (9.76 to 9.84 m/s² at the
  // surface). Beyond: a unit or typing error.
  const double height = r.quantity(*t, "site", "height", kind::length).value_or(0.0);
  if (!(height >= -5000 && height <= 10000))
    r.fail(
        *t->get("height"), "site.height",
        fmt::format("{} is not a height on the Earth; accepted: -5000 m to 10000 m above sea level, such as "
                    "\"150 m\", or the measured local gravity g",
                    t->get("height")->value<std::string>().value_or(number_text(height))));
  if (const auto g = r.quantity(*t, "site", "g", kind::acceleration, nullptr, "9.8 m/s^2")) {
    if (!(*g >= 9.7 && *g <= 9.9))
      r.fail(
          *t->get("g"), "site.g",
          fmt::format("{} is not the local gravity on the Earth; accepted: 9.7 m/s^2 to 9.9 m/s^2, such as "
                      "\"9.8 m/s^2\"",
                      t->get("g")->value<std::string>().value_or(number_text(*g))));
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
    const auto value = without_per_root_hz(text->get());
    if (!value) r.fail(*n, kp, fmt::format("'{}' must end in /rtHz; {}", text->get(), accepted));
    density =
        r.quantity_text(std::string(*value), where(n->source()), kp, kind::dimensionless, nullptr, "0.2 ppm");
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
  r.require_at_least(*t, p, "radius", *radius, 0.01, "an arm radius of at least 0.01 m, e.g. \"2.5 m\"");
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
  if (const toml::node* n = t->get("encoders")) {
    const std::string accepted = "accepted: a list of \"main\" and \"platform\", e.g. encoders = [\"main\", \"platform\"]";
    const auto* list = n->as_array();
    if (!list) r.fail(*n, "centrifuge.encoders", fmt::format("expected a list, got {}; {}", type_name(*n), accepted));
    for (const toml::node& item : *list) {
      const auto* word = item.as_string();
      bool* slot = !word                      ? nullptr
                   : word->get() == "main"     ? &model.encoders.main
                   : word->get() == "platform" ? &model.encoders.platform
                                               : nullptr;
      if (!slot)
        r.fail(item, "centrifuge.encoders",
               fmt::format("{} is not an encoder; {}",
                           word ? fmt::format("'{}'", word->get()) : std::string(type_name(item)), accepted));
      if (*slot) r.fail(item, "centrifuge.encoders", fmt::format("'{}' is listed twice; {}", word->get(), accepted));
      *slot = true;
    }
  }
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

// The unit a quantity string was written in ("25 um" gives "um"), kept for display; "" when the node is no
// string or its unit is not one of the dimension (a value already accepted always has one).
std::string written_unit(const toml::node* node, Dimension dim) {
  const auto* s = node ? node->as_string() : nullptr;
  if (!s) return "";
  const std::string& text = s->get();
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  std::string unit(end ? end : "");
  unit.erase(0, unit.find_first_not_of(" \t"));
  unit.erase(unit.find_last_not_of(" \t") + 1);
  try {
    if (!unit.empty() && parse_unit(unit).dim == dim) return unit;
  } catch (const UnitError&) {
  }
  return "";
}

// The largest tolerance bound accepted, in SI units (m, rad, rad/s, 1, m/(rad/s)²). Budgets, allocations and
// the LPU sum squares of sensitivity × bound in double precision (at most about 1.8e308): 1e100 keeps the
// square at 1e200, leaving 10¹⁰⁸ for the sensitivities and the sums, and is beyond any physical size by far
// (the observable universe is 9e26 m across). A larger bound is a typing or unit error, refused here with its
// place rather than as an infinite U far from the file.
constexpr double kMaxToleranceBound = 1e100;

void check_bound_size(const Reader& r, const toml::node& at, const std::string& key, double bound,
                      SourceUnit u) {
  if (bound <= kMaxToleranceBound) return;
  const std::string unit = u == SourceUnit::relative ? "relative units" : std::string(unit_symbol(u));
  r.fail(at, key,
         fmt::format("{} {} is too large: beyond 1e100 in SI units the budget's sums of squares are not a "
                     "finite number; accepted: a bound above 0 and up to 1e100 {}, e.g. \"{}\"",
                     number_text(bound), unit, unit, parameter_example(u)));
}

// A quantity as the file wrote it ("0.1 arcsec"), or its number.
std::string as_written(const toml::node* node) {
  if (const auto* s = node->as_string()) return fmt::format("\"{}\"", s->get());
  return number_text(node->value<double>().value_or(0));
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
      check_bound_size(r, *entry->get("bound"), p + ".bound", *bound, u);
      tol.bound = *bound;
      tol.unit = written_unit(entry->get("bound"), dim);
      tol.distribution = r.word(*entry, p, "distribution", distributions).value_or(Distribution::normal);
      tol.group = r.string(*entry, p, "group").value_or("");
      if (const auto cost = r.number(*entry, p, "cost")) {
        r.require_positive(*entry, p, "cost", *cost, "a relative cost weight such as 1.0");
        if (!kToleranceCostRange.accepts(*cost))
          r.fail(*entry->get("cost"), Reader::path(p, "cost"),
                 fmt::format(
                     "{} is out of range; accepted: {} (the allocation's objective Σ cost/λ stays finite "
                     "and its ratios meaningful)",
                     number_text(*cost), kToleranceCostRange.text()));
        tol.cost = *cost;
      }
      // The machine's best achievable value: the allocation never tightens the bound below it.
      if (const auto floor = r.quantity(*entry, p, "floor", dim, nullptr, parameter_example(u))) {
        r.require_positive(*entry, p, "floor", *floor,
                           "the best value the machine achieves, in the bound's units, at most the bound");
        if (*floor > tol.bound)
          r.fail(
              *entry->get("floor"), p + ".floor",
              fmt::format("{} is above the bound {}; accepted: a floor > 0 and at most the bound (the best "
                          "value the machine achieves)",
                          as_written(entry->get("floor")), as_written(entry->get("bound"))));
        tol.floor = *floor;
      }
    } else {
      tol.bound = r.quantity_node(node, p, dim, nullptr, parameter_example(u));
      tol.unit = written_unit(&node, dim);
      if (!(tol.bound > 0))
        r.fail(node, p,
               fmt::format("must be positive, got {}; the standard uncertainty, e.g. \"{}\"",
                           number_text(tol.bound), parameter_example(u)));
      check_bound_size(r, node, p, tol.bound, u);
    }
    out.push_back(std::move(tol));
  }
  std::sort(out.begin(), out.end(),
            [](const Tolerance& a, const Tolerance& b) { return a.parameter < b.parameter; });
  return out;
}

}  // namespace ccal::config_reading
