// The configuration's [tolerances] and [[inputs]] (docs/config.md): the bound, distribution, group and cost of
// each input of the budget, a centrifuge error or an input of the measuring chain.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "ccal/setup/input_description.hpp"
#include "config_reader.hpp"

namespace ccal::config_reading {

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

namespace {

// The largest tolerance bound accepted, in SI units (m, rad, rad/s, 1, m/(rad/s)²). Budgets, allocations and
// the LPU sum squares of sensitivity × bound in double precision (at most about 1.8e308): 1e100 keeps the
// square at 1e200, leaving 10¹⁰⁸ for the sensitivities and the sums, and is beyond any physical size by far
// (the observable universe is 9e26 m across). A larger bound is a typing or unit error, refused here with its
// place rather than as an infinite U far from the file.
constexpr double kMaxToleranceBound = 1e100;

void check_bound_size(const Reader& r, const toml::node& at, const std::string& key, double bound,
                      const InputDescription& d) {
  if (bound <= kMaxToleranceBound) return;
  const std::string unit = d.si_unit == "1" ? "relative units" : d.si_unit;
  r.fail(at, key,
         fmt::format("{} {} is too large: beyond 1e100 in SI units the budget's sums of squares are not a "
                     "finite number; accepted: a bound above 0 and up to 1e100 {}, e.g. \"{}\"",
                     number_text(bound), unit, unit, d.example));
}

// A quantity as the file wrote it ("0.1 arcsec"), or its number.
std::string as_written(const toml::node* node) {
  if (const auto* s = node->as_string()) return fmt::format("\"{}\"", s->get());
  return number_text(node->value<double>().value_or(0));
}

// A bound of [tolerances] (or a floor): in the input's dimension, a fixed term's also relative to its value.
std::optional<double> tolerance_quantity(const Reader& r, const toml::table& t, const std::string& p,
                                         std::string_view key, const Config& config, int parameter) {
  const toml::node* n = t.get(key);
  if (n == nullptr) return std::nullopt;
  const std::string at = Reader::path(p, key);
  if (is_chain_parameter(parameter)) return chain_quantity(r, *n, at, config, parameter);
  const InputDescription d = describe_input(config, parameter);
  return r.quantity_node(*n, at, d.dim, nullptr, d.example);
}

const std::vector<std::pair<std::string_view, Distribution>>& distribution_words() {
  static const std::vector<std::pair<std::string_view, Distribution>> words{
      {"normal", Distribution::normal},
      {"uniform", Distribution::uniform},
      {"triangular", Distribution::triangular},
      {"arcsine", Distribution::arcsine}};
  return words;
}

}  // namespace

// The keys of a tolerance given as a table (bound, distribution, group, cost, floor) into tol.
void read_tolerance_entry(const Reader& r, const toml::table& entry, const toml::node& node, const std::string& p,
                          const Config& config, Tolerance& tol) {
  const InputDescription d = describe_input(config, tol.parameter);
  const auto bound = tolerance_quantity(r, entry, p, "bound", config, tol.parameter);
  if (!bound) r.fail(node, p + ".bound", fmt::format("missing value; give e.g. {{ bound = \"{}\" }}", d.example));
  r.require_positive(entry, p, "bound", *bound, "the tolerance bound, e.g. \"" + d.example + "\"");
  check_bound_size(r, *entry.get("bound"), p + ".bound", *bound, d);
  tol.bound = *bound;
  tol.unit = written_unit(entry.get("bound"), d.dim);
  if (tol.unit.empty() && d.relative_to > 0) tol.unit = written_unit(entry.get("bound"), kind::dimensionless);
  tol.distribution = r.word(entry, p, "distribution", distribution_words()).value_or(Distribution::normal);
  tol.group = r.string(entry, p, "group").value_or("");
  if (const auto cost = r.number(entry, p, "cost")) {
    r.require_positive(entry, p, "cost", *cost, "a relative cost weight such as 1.0");
    if (!kToleranceCostRange.accepts(*cost))
      r.fail(*entry.get("cost"), Reader::path(p, "cost"),
             fmt::format("{} is out of range; accepted: {} (the allocation's objective Σ cost/λ stays finite "
                         "and its ratios meaningful)",
                         number_text(*cost), kToleranceCostRange.text()));
    tol.cost = *cost;
  }
  // The machine's best achievable value: the allocation never tightens the bound below it.
  if (const auto floor = tolerance_quantity(r, entry, p, "floor", config, tol.parameter)) {
    r.require_positive(entry, p, "floor", *floor,
                       "the best value the machine achieves, in the bound's units, at most the bound");
    if (*floor > tol.bound)
      r.fail(*entry.get("floor"), p + ".floor",
             fmt::format("{} is above the bound {}; accepted: a floor > 0 and at most the bound (the best "
                         "value the machine achieves)",
                         as_written(entry.get("floor")), as_written(entry.get("bound"))));
    tol.floor = *floor;
  }
}

std::vector<Tolerance> read_tolerances(const Reader& r, const toml::table& root, const Config& config) {
  std::vector<Tolerance> out;
  const ErrorLayout& layout = config.centrifuge.layout;
  if (const toml::table* t = r.table(root, "", "tolerances", false)) {
  for (const auto& [key, node] : *t) {
    Tolerance tol;
    tol.parameter = parameter_index(r, layout, key, "tolerances", &config);
    const std::string p = Reader::path("tolerances", key.str());
    if (is_chain_parameter(tol.parameter) && chain_input(tol.parameter).kind == ChainKind::declared)
      r.fail(where(key.source()), p,
             fmt::format("'{}' is declared in [[inputs]], which holds its bound; accepted: its bound, "
                         "distribution and group in its [[inputs]] entry",
                         key.str()));
    const InputDescription d = describe_input(config, tol.parameter);
    tol.id = d.id;
    if (const auto* entry = node.as_table()) {
      r.check_keys(*entry, p, kToleranceKeys);
      read_tolerance_entry(r, *entry, node, p, config, tol);
    } else {
      tol.bound = is_chain_parameter(tol.parameter) ? chain_quantity(r, node, p, config, tol.parameter)
                                                    : r.quantity_node(node, p, d.dim, nullptr, d.example);
      tol.unit = written_unit(&node, d.dim);
      if (tol.unit.empty() && d.relative_to > 0) tol.unit = written_unit(&node, kind::dimensionless);  // "2 ppm" of K1
      if (!(tol.bound > 0))
        r.fail(node, p,
               fmt::format("must be positive, got {}; accepted: a positive bound, e.g. \"{}\"",
                           number_text(tol.bound), d.example));
      check_bound_size(r, node, p, tol.bound, d);
    }
    out.push_back(std::move(tol));
  }
  }
  read_declared_tolerances(r, root, config, out);
  std::sort(out.begin(), out.end(),
            [](const Tolerance& a, const Tolerance& b) { return a.parameter < b.parameter; });
  return out;
}


}  // namespace ccal::config_reading
