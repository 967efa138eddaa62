// The configuration file's [site], [centrifuge], [errors] and [tolerances] sections (docs/config.md).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include "ccal/model/error_sources.hpp"
#include "ccal/setup/input_description.hpp"
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
  // The g of the g-levels and of the instrument's coefficients: the site's (the default) or standard gravity.
  enum class GUnit { local, standard };
  const std::vector<std::pair<std::string_view, GUnit>> g_units{{"local", GUnit::local},
                                                                 {"standard", GUnit::standard}};
  if (r.word(*t, "site", "g_unit", g_units).value_or(GUnit::local) == GUnit::standard)
    site.unit_g = kStandardGravity;
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
  if (!(density >= 0) || !std::isfinite(density))
    r.fail(*n, kp, fmt::format("must not be negative, got {}; {}", Reader::written(*n, density), accepted));
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

// Index of an error parameter named by a key of [errors] or [tolerances], or with a configuration the code
// of an input of its measuring chain; fails with the closest id.
int parameter_index(const Reader& r, const ErrorLayout& layout, const toml::key& key, std::string_view table,
                    const Config* chain) {
  const std::string p = Reader::path(table, key.str());
  if (chain != nullptr)
    if (auto code = find_chain_input(key.str(), chain->chain, fixed_term_ids(*chain), layout.harmonic_order()))
      return *code;
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
  if (chain != nullptr) {
    if (key.str().starts_with("encoder1_") || key.str().starts_with("encoder3_"))
      r.fail(where(key.source()), p,
             fmt::format("an encoder's angle error is encoder1_c<k>, encoder1_s<k>, encoder3_c<k> or "
                         "encoder3_s<k> with 1 <= k <= harmonic_order = {}",
                         layout.harmonic_order()));
    if (std::find(chain->instrument.term_ids.begin(), chain->instrument.term_ids.end(), key.str()) !=
        chain->instrument.term_ids.end())
      r.fail(where(key.source()), p,
             fmt::format("{0} is a free term, which the test identifies; only a fixed term has a tolerance "
                         "(its value from another calibration); accepted: a fixed term ({1}) or fix {0} in "
                         "[identification] fixed",
                         key.str(), fixed_term_list(*chain)));
  }
  std::vector<std::string> ids = layout.parameter_ids();
  if (chain != nullptr)
    for (const std::string& id : chain_input_ids(chain->chain, fixed_term_ids(*chain))) ids.push_back(id);
  std::string hint;
  if (auto best = closest(key.str(), ids)) hint = fmt::format("did you mean '{}'? ", *best);
  std::string statics, dynamics;
  for (const Channel& c : channels()) {
    std::string& list = c.joint == Joint::none ? statics : dynamics;
    list += (list.empty() ? "" : ", ") + std::string(c.id);
  }
  const std::string chain_ids =
      chain == nullptr ? ""
                       : fmt::format(", or an input of the measuring chain ({})",
                                     chain_input_ids_text(chain->chain, fixed_term_ids(*chain)));
  r.fail(where(key.source()), p,
         fmt::format("unknown error parameter; {}accepted: a static id ({}) or a dynamic channel ({}) "
                     "with _c<k> or _s<k>, k <= harmonic_order (e.g. dx3_c1){}",
                     hint, statics, dynamics, chain_ids));
}

std::vector<std::string> fixed_term_ids(const Config& config) {
  std::vector<std::string> out;
  for (const auto& [id, value] : config.identification.fixed_terms) out.push_back(id);
  return out;
}

std::string fixed_term_list(const Config& config) {
  std::string out;
  for (const std::string& id : fixed_term_ids(config)) out += (out.empty() ? "" : ", ") + id;
  return out.empty() ? "none is fixed" : out;
}


double chain_quantity(const Reader& r, const toml::node& node, const std::string& p, const Config& config,
                      int code) {
  const InputDescription d = describe_input(config, code);
  const ChainInput in = chain_input(code);
  if (in.kind == ChainKind::declared) {
    const auto v = node.value<double>();
    if (!v || !std::isfinite(*v))
      r.fail(node, p, fmt::format("is not a number; accepted: a number in the input's own unit ({}), e.g. 0.05",
                                  d.display_unit));
    return *v;
  }
  if (in.kind == ChainKind::fixed_term) {
    // Relative to the term's value ("0.5 ppm"), or in its unit.
    const auto* text = node.as_string();
    if (text != nullptr) {
      const std::string unit = written_unit(&node, kind::dimensionless);
      Quantity q{};
      bool parsed = true;
      try {
        q = parse_quantity(text->get());
      } catch (const UnitError&) {
        parsed = false;
      }
      if (parsed && q.dim == kind::dimensionless && !unit.empty()) {
        const double value = config.identification.fixed_terms.at(d.id);
        return q.value_si * std::abs(value);
      }
    }
  }
  return r.quantity_node(node, p, d.dim, nullptr, d.example);
}

namespace {

// A measured error of the machine beyond any centrifuge's, by its kind: a length beyond 1 m, an angle beyond
// half a turn, a rate error beyond 10 rad/s (the plans' rates are a few rad/s), a relative error (a ripple)
// beyond 100 %, an arm stretch beyond 1e-3 m/(rad/s)² (12 cm at 30 g on a 2.5 m arm). Such a value is a
// typing or unit error ("1.5e3 arcsec" for 1.5); beyond them the model's output overflows far from the file
// ("the means of run '5g' are not finite"), so it is refused at its line.
void check_error_size(const Reader& r, const toml::node& at, const std::string& key, double value,
                      const InputDescription& d) {
  struct Limit {
    Dimension dim;
    double most;
    std::string_view text;
  };
  static constexpr Limit kLimits[] = {{kind::length, 1, "1 m"},
                                      {kind::angle, std::numbers::pi, "180 deg"},
                                      {kind::angular_rate, 10, "10 rad/s"},
                                      {kind::dimensionless, 1, "1 (100 %)"},
                                      {kind::length / pow(kind::angular_rate, 2), 1e-3, "1e-3 m/(rad/s)^2"}};
  for (const Limit& limit : kLimits)
    if (limit.dim == d.dim && !(std::abs(value) <= limit.most))
      r.fail(at, key,
             fmt::format("{} is implausible for a measured error of the machine; accepted: up to {} in size, "
                         "e.g. \"{}\" (a larger value is a typing or unit error)",
                         Reader::written(at, value), limit.text, d.example));
}

}  // namespace

void read_errors(const Reader& r, const toml::table& root, const Config& config, CentrifugeModel& model,
                 std::vector<std::pair<int, double>>* chain_errors) {
  const toml::table* t = r.table(root, "", "errors", false);
  if (!t) return;
  for (const auto& [key, node] : *t) {
    const std::string p = Reader::path("errors", key.str());
    const int index = parameter_index(r, model.layout, key, "errors", &config);
    if (is_chain_parameter(index)) {
      if (chain_errors == nullptr)
        r.fail(where(key.source()), p,
               fmt::format("'{}' is an input of the measuring chain, whose value the configuration states "
                           "({}); [errors] holds the centrifuge's measured errors; accepted: a tolerance in "
                           "[tolerances], or an error of a simulated machine in a truth file",
                           key.str(), lab_value_place(config, index)));
      chain_errors->emplace_back(index, chain_quantity(r, node, p, config, index));
      continue;
    }
    const InputDescription d = describe_layout_parameter(model.layout, index);
    model.errors[index] = r.quantity_node(node, p, d.dim, nullptr, d.example);
    check_error_size(r, node, p, model.errors[index], d);
  }
}

std::string lab_value_place(const Config& config, int code) {
  switch (chain_input(code).kind) {
    case ChainKind::gravity:
      return "[site] g";
    case ChainKind::fixed_term:
      return "[instrument.terms]";
    case ChainKind::declared:
      return "[[inputs]]";
    default:
      return fmt::format("{}: nominally zero", chain_input_id(code, config.chain));
  }
}

}  // namespace ccal::config_reading
