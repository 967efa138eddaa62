// The configuration file's [design] table: the design space of `ccal design` (docs/config.md).
#include "ccal/setup/coefficient_target.hpp"
#include "config_reader.hpp"

namespace ccal::config_reading {

namespace {

const std::vector<std::pair<std::string_view, Mounting>> kMountingWords{
    {"ia_horizontal", Mounting::ia_horizontal},
    {"ia_reversed", Mounting::ia_reversed},
    {"pa_vertical", Mounting::pa_vertical},
    {"ia_vertical", Mounting::ia_vertical}};
const std::vector<std::pair<std::string_view, PlatformMode>> kPlatformWords{
    {"counter_rotating", PlatformMode::counter_rotating}, {"fixed", PlatformMode::fixed}};

const toml::array* array_of(const Reader& r, const toml::table& t, std::string_view key,
                            std::string_view what) {
  const toml::node* n = t.get(key);
  if (!n) return nullptr;
  const toml::array* a = n->as_array();
  const std::string p = Reader::path("design", key);
  if (!a) r.fail(*n, p, fmt::format("expected an array such as {}, got {}", what, type_name(*n)));
  if (a->empty()) r.fail(*n, p, fmt::format("empty array; give at least one value such as {}", what));
  return a;
}

// An array of quantity strings of one dimension, each checked by `check` (which fails with a message).
template <class Check>
std::vector<double> quantities(const Reader& r, const toml::table& t, std::string_view key, Dimension dim,
                               std::string_view example, Check check) {
  std::vector<double> out;
  const toml::array* a = array_of(r, t, key, fmt::format("[\"{}\"]", example));
  if (!a) return out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const std::string p = fmt::format("design.{}[{}]", key, i + 1);
    const double v = r.quantity_node(*a->get(i), p, dim, nullptr, example);
    check(*a->get(i), p, v);
    out.push_back(v);
  }
  return out;
}

template <class E>
std::vector<E> words(const Reader& r, const toml::table& t, std::string_view key,
                     const std::vector<std::pair<std::string_view, E>>& accepted) {
  std::vector<E> out;
  std::vector<std::string> names;
  for (const auto& [name, value] : accepted) names.emplace_back(name);
  const toml::array* a = array_of(r, t, key, fmt::format("[\"{}\"]", names.front()));
  if (!a) return out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& n = *a->get(i);
    const std::string p = fmt::format("design.{}[{}]", key, i + 1);
    const auto* s = n.as_string();
    if (!s)
      r.fail(n, p,
             fmt::format("expected a string, got {}; accepted: {}", type_name(n), fmt::join(names, ", ")));
    const auto it =
        std::find_if(accepted.begin(), accepted.end(), [&](const auto& w) { return w.first == s->get(); });
    if (it == accepted.end())
      r.fail(n, p, fmt::format("unknown value '{}'; accepted: {}", s->get(), fmt::join(names, ", ")));
    if (std::find(out.begin(), out.end(), it->second) == out.end()) out.push_back(it->second);
  }
  return out;
}

std::optional<int> count(const Reader& r, const toml::table& t, std::string_view key, int least, int most,
                         std::string_view what) {
  const toml::node* n = t.get(key);
  if (!n) return std::nullopt;
  const std::string p = Reader::path("design", key);
  const auto* i = n->as_integer();
  if (!i) r.fail(*n, p, fmt::format("expected a whole number, got {}; accepted: {}", type_name(*n), what));
  if (i->get() < least || i->get() > most)
    r.fail(*n, p, fmt::format("{} is out of range; accepted: {}", i->get(), what));
  return int(i->get());
}

// The coefficient names of the objective must be free terms.
void check_free(const Reader& r, const toml::node& n, const std::string& p, const std::string& name,
                const IdentificationSpec& spec) {
  if (std::find(spec.free_terms.begin(), spec.free_terms.end(), name) != spec.free_terms.end()) return;
  r.fail(n, p,
         fmt::format("'{}' is not a free term of the identification; accepted: {}", name,
                     fmt::join(spec.free_terms, ", ")));
}

void read_objective(const Reader& r, const toml::table& t, const InstrumentModel& instrument,
                    const IdentificationSpec& spec, DesignSpace& d) {
  d.objective =
      r.word(t, "design", "objective",
             std::vector<std::pair<std::string_view, DesignObjective>>{
                 {design_objective_name(DesignObjective::uncertainty), DesignObjective::uncertainty},
                 {design_objective_name(DesignObjective::d_optimal), DesignObjective::d_optimal},
                 {design_objective_name(DesignObjective::a_optimal), DesignObjective::a_optimal}})
          .value_or(DesignObjective::uncertainty);
  if (const toml::array* a = array_of(r, t, "coefficients", "[\"K2\", \"K3\"]")) {
    for (std::size_t i = 0; i < a->size(); ++i) {
      const toml::node& n = *a->get(i);
      const std::string p = fmt::format("design.coefficients[{}]", i + 1);
      const auto* s = n.as_string();
      if (!s) r.fail(n, p, fmt::format("expected a term id such as \"K3\", got {}", type_name(n)));
      check_free(r, n, p, s->get(), spec);
      d.coefficients.push_back(s->get());
    }
  }
  std::vector<std::string> units;
  for (const auto& id : spec.free_terms) units.push_back(coefficient_unit(instrument.output_unit, id, instrument.g_symbol));
  if (const toml::table* targets = r.table(t, "design", "targets", false)) {
    for (const auto& [key, node] : *targets) {
      const std::string p = Reader::path("design.targets", key.str());
      check_free(r, node, p, std::string(key.str()), spec);
      std::string value;
      if (const auto* s = node.as_string())
        value = s->get();
      else if (const auto v = number_of(node))
        value = fmt::format("{:.17g}", *v);
      else
        r.fail(node, p,
               fmt::format("expected an expanded uncertainty such as \"1e-6 {}\", got {}",
                           coefficient_unit(instrument.output_unit, key.str(), instrument.g_symbol), type_name(node)));
      try {
        const AllocationTarget target =
            parse_allocation_target(fmt::format("{}={}", key.str(), value), spec.free_terms, units, p);
        d.targets[target.coefficient] = target.expanded;
      } catch (const InputError& e) {
        r.fail(node, p, e.what());
      }
    }
  }
  if (const toml::table* weights = r.table(t, "design", "weights", false)) {
    for (const auto& [key, node] : *weights) {
      const std::string p = Reader::path("design.weights", key.str());
      check_free(r, node, p, std::string(key.str()), spec);
      const auto v = number_of(node);
      if (!v || !std::isfinite(*v) || *v <= 0)
        r.fail(node, p, "expected a positive number such as 1 (the coefficient's weight in the objective)");
      d.weights[std::string(key.str())] = *v;
    }
  }
  d.starts = count(r, t, "starts", 1, 1000, "a number of starts from 1 to 1000");
  if (const toml::node* n = t.get("seed")) {
    const auto* i = n->as_integer();
    if (!i || i->get() < 0) r.fail(*n, "design.seed", "expected a whole number >= 0 such as 1");
    d.seed = static_cast<unsigned long long>(i->get());
  }
}

// A value of [design] that must be positive, named as the user wrote it ("-1 ms"), else as the number.
void require_positive_setting(const Reader& r, const toml::node& n, const std::string& path, double v) {
  // The value as the user wrote it ("-1 ms"), else the number.
  const std::optional<std::string> written = n.value<std::string>();
  if (!(v > 0))
    r.fail(n, path,
           fmt::format("must be positive, got {}; accepted: a positive value", written ? *written : number_text(v)));
}

// g_range: two positive g-levels, the smallest first, and not with g_levels.
void read_g_range(const Reader& r, const toml::table& t, DesignSpace& d) {
  auto positive = [&r](const toml::node& n, const std::string& path, double v) {
    require_positive_setting(r, n, path, v);
  };
  if (const std::vector<double> range = quantities(r, t, "g_range", kind::acceleration_g, "5 g", positive);
      !range.empty()) {
    if (range.size() != 2 || range[0] > range[1])
      r.fail(*t.get("g_range"), "design.g_range",
             "expected two g-levels, the smallest first, such as [\"5 g\", \"30 g\"]");
    if (!d.g_levels.empty())
      r.fail(*t.get("g_range"), "design.g_range",
             "both g_levels and g_range are given; accepted: one of them");
    d.g_min = range[0];
    d.g_max = range[1];
  }
}

// A machine's setting step: positive and no finer than 1e-6 of the unit (a finer step is a unit error, and
// the settings are counted in steps as 64-bit integers). Coarser than the design space allows:
// resolve_design_space.
std::optional<double> setting_step(const Reader& r, const toml::table& t, std::string_view key, Dimension dim,
                                   std::string_view example, double finest, std::string_view finest_text) {
  const std::string_view p = "design";
  const std::optional<double> v = r.quantity(t, p, key, dim, nullptr, example);
  if (!v) return v;
  const toml::node& n = *t.get(key);
  const std::string path = Reader::path(p, key);
  require_positive_setting(r, n, path, *v);
  if (*v < finest * (1 - 1e-12))
    r.fail(n, path,
           fmt::format("{} is finer than any machine sets; accepted: at least {}, such as \"{}\"",
                       n.value<std::string>().value_or(number_text(*v)), finest_text, example));
  return v;
}

}  // namespace

DesignSpace read_design(const Reader& r, const toml::table& root, const InstrumentModel& instrument,
                        const IdentificationSpec& spec) {
  DesignSpace d;
  const toml::table* t = r.table(root, "", "design", false);
  if (!t) return d;
  const std::string_view p = "design";
  r.check_keys(*t, p, kDesignKeys);
  auto positive = [&r](const toml::node& n, const std::string& path, double v) {
    require_positive_setting(r, n, path, v);
  };
  d.runs = count(r, *t, "runs", 1, 1000, "a number of runs from 1 to 1000");
  d.min_g_levels = count(r, *t, "min_g_levels", 1, 1000, "a number of distinct g-levels from 1 to 1000");
  d.total_time = r.quantity(*t, p, "total_time", kind::time, nullptr, "2700 s");
  if (d.total_time) positive(*t->get("total_time"), "design.total_time", *d.total_time);
  d.max_g = r.quantity(*t, p, "max_g", kind::acceleration_g, nullptr, "30 g");
  if (d.max_g) positive(*t->get("max_g"), "design.max_g", *d.max_g);
  d.g_levels = quantities(r, *t, "g_levels", kind::acceleration_g, "5 g", positive);
  read_g_range(r, *t, d);
  d.g_step = r.quantity(*t, p, "g_step", kind::acceleration_g, nullptr, "1 g");
  if (d.g_step) positive(*t->get("g_step"), "design.g_step", *d.g_step);
  d.durations = quantities(r, *t, "durations", kind::time, "450 s", positive);
  d.turn_fractions = count(r, *t, "turn_fractions", 0, 360, "0 (durations as given) to 360");
  d.phase = r.word(*t, p, "phase",
                   std::vector<std::pair<std::string_view, DesignPhase>>{{"terminal", DesignPhase::terminal},
                                                                         {"initial", DesignPhase::initial}});
  d.phases = quantities(r, *t, "phases", kind::angle, "180 deg", [](auto&&...) {});
  d.phase_step = r.quantity(*t, p, "phase_step", kind::angle, nullptr, "30 deg");
  if (d.phase_step) positive(*t->get("phase_step"), "design.phase_step", *d.phase_step);
  d.arm_azimuths = quantities(r, *t, "arm_azimuths", kind::angle, "0 deg", [](auto&&...) {});
  d.azimuth_step = r.quantity(*t, p, "azimuth_step", kind::angle, nullptr, "90 deg");
  if (d.azimuth_step) positive(*t->get("azimuth_step"), "design.azimuth_step", *d.azimuth_step);
  d.mountings = words(r, *t, "mountings", kMountingWords);
  d.platforms = words(r, *t, "platforms", kPlatformWords);
  d.refine = r.boolean(*t, p, "refine").value_or(true);
  d.g_resolution = setting_step(r, *t, "g_resolution", kind::acceleration_g, "0.01 g", 1e-6, "1e-6 g");
  d.duration_resolution = setting_step(r, *t, "duration_resolution", kind::time, "0.001 s", 1e-6, "1e-6 s");
  d.angle_resolution = setting_step(r, *t, "angle_resolution", kind::angle, "0.1 deg",
                                    1e-6 * std::numbers::pi / 180, "1e-6 deg");
  read_objective(r, *t, instrument, spec, d);
  return d;
}

}  // namespace ccal::config_reading
