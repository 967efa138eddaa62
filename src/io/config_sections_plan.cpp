// The configuration file's [instrument], [plan] and [identification] sections (docs/config.md).
#include <cmath>
#include <numbers>
#include <utility>

#include "../core/text_shown.hpp"
#include "config_reader.hpp"

namespace ccal::config_reading {

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

namespace {

// [instrument] output_unit: an angular rate (rate-output PIGA), a g-level, an acceleration, or pulses per
// second; the model's default when absent.
OutputUnit read_output_unit(const Reader& r, const toml::table& t, std::string_view p, InstrumentModel& m,
                            bool ieee) {
  OutputUnit out{m.output_unit, kind::angular_rate, false};
  if (const auto text = r.string(t, p, "output_unit")) {
    out.text = *text;
    const std::string accepted =
        "accepted: an angular rate (deg/s, rad/s, deg/h), a g-level (g, mg, ug), "
        "an acceleration (m/s^2), a current (mA, uA), a voltage (V, mV) or pulse/s";
    if (*text == "pulse/s") {
      out.pulse = true;
      out.dim = kind::angular_rate;
    } else {
      try {
        const Quantity q = parse_unit(*text);
        if (q.dim != kind::angular_rate && q.dim != kind::acceleration_g && q.dim != kind::acceleration &&
            q.dim != kind::current && q.dim != kind::voltage)
          r.fail(*t.get("output_unit"), Reader::path(p, "output_unit"),
                 fmt::format("'{}' is {}; {}", *text, describe(q.dim), accepted));
        out.dim = q.dim;
      } catch (const UnitError& e) {
        r.fail(*t.get("output_unit"), Reader::path(p, "output_unit"), fmt::format("{}; {}", e.what(), accepted));
      }
    }
    m.output_unit = *text;
  } else if (ieee) {
    out = {"g", kind::acceleration_g, false};
  }
  return out;
}

// [instrument.terms]: each coefficient in the output unit per g^n (per rad/s for K_w), sorted into the
// model's term order; a model without its own coefficients must give them.
void read_terms(const Reader& r, const toml::table& t, std::string_view p, const OutputUnit& out, bool ieee,
                InstrumentModel& m) {
  if (const toml::table* terms = r.table(t, p, "terms", false)) {
    struct Parsed {
      TermSpec spec;
      std::string id;
      double value;
    };
    std::vector<Parsed> parsed;
    const std::vector<std::string> valid = all_term_ids();
    for (const auto& [key, node] : *terms) {
      const std::string kp = Reader::path(Reader::path(p, "terms"), key.str());
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
      // The model's output is a sum of K_n a^n up to 1000 g, the fit squares it: beyond 1e100 (SI) a
      // coefficient overflows the run means far from the file; it is a typing or unit error.
      if (!(std::abs(v) <= 1e100))
        r.fail(node, kp,
               fmt::format(
                   "{} is implausible: beyond 1e100 in SI units the model's output overflows; accepted: a "
                   "coefficient up to 1e100 (SI) in size, e.g. \"{}\"",
                   Reader::written(node, v), "1 " + example));
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
  } else if (ieee) {
    r.fail(where(t.source()), Reader::path(p, "terms"),
           "missing table; model 'ieee' needs [instrument.terms] with coefficients, e.g. K1 = \"1 g/g\"");
  } else if (out.dim != kind::angular_rate || out.pulse) {
    r.fail(*t.get("output_unit"), Reader::path(p, "output_unit"),
           fmt::format("'{}' cannot use the paper's PIGA coefficients, which are in deg/s; give "
                       "[instrument.terms] in this unit or use an angular-rate output such as deg/s",
                       out.text));
  }
}

// [instrument] noise_density ("<value> <output unit>/rtHz") and quantum (the output's quantisation step).
void read_noise(const Reader& r, const toml::table& t, std::string_view p, const OutputUnit& out,
                InstrumentModel& m) {
  if (const toml::node* n = t.get("noise_density")) {
    const std::string kp = Reader::path(p, "noise_density");
    const auto* s = n->as_string();
    if (!s)
      r.fail(*n, kp,
             fmt::format("expected a quantity string such as \"0.001 {}/rtHz\", got {}", out.text,
                         type_name(*n)));
    const auto text = without_per_root_hz(s->get());
    if (!text)
      r.fail(*n, kp,
             fmt::format("'{}' must end in /rtHz (or /sqrt(Hz)); accepted: \"<value> {}/rtHz\"", s->get(),
                         out.text));
    const double v =
        r.quantity_text(std::string(*text), where(n->source()), kp, out.dim, &out, "0.001 " + out.text);
    if (v < 0)
      r.fail(*n, kp,
             fmt::format("must not be negative, got {}; accepted: a noise density >= 0 such as \"0.001 {}/rtHz\"",
                         s->get(), out.text));
    m.noise_density = v;
  }
  if (const toml::node* n = t.get("quantum")) {
    const Dimension dim = out.dim * kind::time;
    const double v = r.quantity_node(*n, Reader::path(p, "quantum"), dim, &out, "0 " + si_unit(dim));
    if (v < 0)
      r.fail(*n, Reader::path(p, "quantum"),
             fmt::format("must not be negative, got {}; accepted: a quantisation step >= 0 (0: an output sampled, "
                         "not counted)",
                         Reader::written(*n, v)));
    m.quantum = v;
  }
  // A current output read as the voltage across a sampling resistor: the logs' output column is in volts.
  if (const toml::node* n = t.get("sampling_resistor")) {
    if (out.dim != kind::current)
      r.fail(*n, Reader::path(p, "sampling_resistor"),
             fmt::format("a sampling resistor converts a current output; this output is in '{}'; accepted: "
                         "output_unit = \"mA\" (or another current) with it, or no sampling_resistor",
                         out.text));
    const double v = r.quantity_node(*n, Reader::path(p, "sampling_resistor"), kind::resistance, nullptr, "100 ohm");
    if (!(v > 0))
      r.fail(*n, Reader::path(p, "sampling_resistor"), "must be positive; accepted: a positive resistance, e.g. \"100 ohm\"");
    m.sampling_resistor = v;
  }
}

}  // namespace

InstrumentModel read_instrument(const Reader& r, const toml::table& root) {
  const toml::table* t = r.table(root, "", "instrument", false);
  if (!t) return paper_piga();
  r.check_keys(*t, "instrument", kInstrumentKeys);
  return read_instrument_table(r, *t, "instrument");
}

InstrumentModel read_instrument_table(const Reader& r, const toml::table& table, std::string_view p) {
  const toml::table* t = &table;
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

  const OutputUnit out = read_output_unit(r, *t, p, m, model == Model::ieee);
  read_terms(r, *t, p, out, model == Model::ieee, m);
  if (const auto gain = r.number(*t, p, "rate_gain")) m.rate_gain = *gain;
  read_noise(r, *t, p, out, m);
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
           fmt::format("must be positive, got {} s; accepted: a positive run duration such as \"450 s\"",
                       number_text(*f.duration)));
  if (f.duration) {
    r.require_at_most(t, p, "duration", *f.duration, 1e6, "a run duration up to 1e6 s (11.6 days)");
    r.require_at_least(t, p, "duration", *f.duration, 1e-3,
                       "a run duration of at least 1 ms, such as \"450 s\"");
  }
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
  // An angle beyond a turn ("1e300 deg") is a typing or unit error, and loses its digits when wrapped.
  for (const auto& [key, angle] :
       {std::pair{"initial_phase", f.initial_phase}, std::pair{"terminal_phase", f.terminal_phase},
        std::pair{"arm_azimuth", f.arm_azimuth}})
    if (angle)
      r.require_at_most(t, p, key, std::abs(*angle), 2 * std::numbers::pi,
                        "an angle of at most one turn in size (-360 deg to 360 deg), e.g. \"180 deg\"");
  f.mounting =
      r.word(t, p, "mounting",
             std::vector<std::pair<std::string_view, Mounting>>{{"ia_horizontal", Mounting::ia_horizontal},
                                                                {"ia_reversed", Mounting::ia_reversed},
                                                                {"pa_vertical", Mounting::pa_vertical},
                                                                {"ia_vertical", Mounting::ia_vertical}});
  return f;
}

namespace {

// [plan]'s runs: an array of tables with one run at least.
const toml::array& plan_runs(const Reader& r, const toml::table& t) {
  const toml::node* runs_node = t.get("runs");
  if (!runs_node)
    r.fail(where(t.source()), "plan.runs",
           "missing runs; add at least one [[plan.runs]] with g_level = \"5 g\"");
  const toml::array* runs = runs_node->as_array();
  if (!runs)
    r.fail(*runs_node, "plan.runs",
           fmt::format("expected an array of tables ([[plan.runs]]), got {}", type_name(*runs_node)));
  if (runs->empty())
    r.fail(*runs_node, "plan.runs", "no runs; add at least one [[plan.runs]] with g_level = \"5 g\"");
  return *runs;
}

// Run k's name (default "run<k+1>"), unique in the plan (`names`: those before, with where they are).
std::string run_name(const Reader& r, const toml::table& rt, const std::string& p, std::size_t k,
                     std::map<std::string, Location>& names) {
  std::string name = r.string(rt, p, "name").value_or(fmt::format("run{}", k + 1));
  if (name.empty()) r.fail(*rt.get("name"), p + ".name", "empty run name; give a name such as \"5g\"");
  // A run's name is a cell of the observations CSV, a log's file name and the NAME of --log NAME=FILE: one
  // line, no '=', no blank at either end.
  const bool control = detail::has_control_character(name);
  if (control || name.find('=') != std::string::npos ||
      std::isspace(static_cast<unsigned char>(name.front())) ||
      std::isspace(static_cast<unsigned char>(name.back())))
    r.fail(
        *rt.get("name"), p + ".name",
        fmt::format("run name {} has {}; accepted: a name of printable characters without '=' or blanks at "
                    "either end, such as \"5g\"",
                    detail::shown_text(name, '"'),
                    control ? "a control character (a line end, a tab)"
                    : name.find('=') != std::string::npos
                        ? "'=' (which separates a run's name from its log file where both are given)"
                        : "a blank at one end"));
  const Location at = rt.get("name") ? where(rt.get("name")->source()) : where(rt.source());
  if (const auto it = names.find(name); it != names.end())
    r.fail(at, p + ".name",
           fmt::format("duplicate run name '{}' (first used at line {}); accepted: a name unique in the plan",
                       name, it->second.line));
  names.emplace(name, at);
  return name;
}

// A run is set by its g-level A or by the main-axis speed Ω (then A = Ω² R0 / g of the site); either way
// within [0.001 g, 1000 g].
double run_g_level(const Reader& r, const toml::table& rt, const std::string& p, const Geometry& geometry,
                   const Site& site) {
  const auto g_level = r.quantity(rt, p, "g_level", kind::acceleration_g, nullptr, "5 g");
  const auto speed = r.quantity(rt, p, "speed", kind::angular_rate, nullptr, "120 rpm");
  if (g_level && speed)
    r.fail(*rt.get("speed"), p + ".speed",
           "both g_level and speed are given; accepted: exactly one of them per run");
  if (!g_level && !speed)
    r.fail(where(rt.source()), p + ".g_level",
           "missing value; give e.g. g_level = \"5 g\" (or the speed, e.g. speed = \"120 rpm\")");
  if (g_level) {
    r.require_positive(rt, p, "g_level", *g_level, "the centripetal level such as \"5 g\"");
    r.require_at_most(rt, p, "g_level", *g_level, 1000.0, "a centripetal level up to 1000 g");
    r.require_at_least(rt, p, "g_level", *g_level, 1e-3, "a centripetal level of at least 0.001 g");
    return *g_level;
  }
  r.require_positive(rt, p, "speed", *speed, "the main-axis speed such as \"120 rpm\"");
  const double level = *speed * *speed * geometry.R0 / site.g_unit();
  r.require_at_most(rt, p, "speed", level, 1000.0, "a speed giving at most 1000 g at the radius");
  r.require_at_least(rt, p, "speed", level, 1e-3, "a speed giving at least 0.001 g at the radius");
  return level;
}

// The run's own fields, else [plan]'s (`defaults`), else the defaults of a run: its duration (required), its
// platform, its phases (one of them required; the run's pair replaces [plan]'s whole), its arm azimuth and
// mounting.
void read_run_settings(const Reader& r, const toml::table& rt, const std::string& p,
                       const RunFields& defaults, Run& run) {
  const RunFields own = read_run_fields(r, rt, p);
  const auto duration = own.duration ? own.duration : defaults.duration;
  if (!duration)
    r.fail(where(rt.source()), p + ".duration",
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
    r.fail(where(rt.source()), p + ".terminal_phase",
           "missing phase; give terminal_phase = \"180 deg\" or initial_phase = \"...\" in this run or in "
           "[plan]");
  run.arm_azimuth = own.arm_azimuth.value_or(defaults.arm_azimuth.value_or(0.0));
  run.mounting = own.mounting.value_or(defaults.mounting.value_or(Mounting::ia_horizontal));
}

}  // namespace

TestPlan read_plan(const Reader& r, const toml::table& root, const Geometry& geometry, const Site& site) {
  const toml::table* t =
      r.table(root, "", "plan", true, "add [plan] and at least one [[plan.runs]] with g_level");
  r.check_keys(*t, "plan", kPlanKeys);
  const RunFields defaults = read_run_fields(r, *t, "plan");
  const toml::array& runs = plan_runs(r, *t);
  TestPlan plan;
  std::map<std::string, Location> names;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const toml::node& node = *runs.get(k);
    const std::string p = fmt::format("plan.runs[{}]", k + 1);
    const toml::table* rt = node.as_table();
    if (!rt) r.fail(node, p, fmt::format("expected a table ([[plan.runs]]), got {}", type_name(node)));
    r.check_keys(*rt, p, kRunKeys);
    Run run;
    run.name = run_name(r, *rt, p, k, names);
    run.g_level = run_g_level(r, *rt, p, geometry, site);
    read_run_settings(r, *rt, p, defaults, run);
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

}  // namespace ccal::config_reading
