// [[inputs]]: the inputs a lab declares for what ccal does not model (docs/config.md), each with an id, what it
// is, its own unit, its tolerance and its sensitivity on the instrument's coefficients, so that the lab's whole
// budget is one table.
#include <fmt/format.h>

#include <cmath>

#include "ccal/model/error_sources.hpp"
#include "ccal/setup/input_description.hpp"
#include "config_reader.hpp"

namespace ccal::config_reading {

namespace {

const toml::array* input_entries(const Reader& r, const toml::table& root) {
  const toml::node* node = root.get("inputs");
  if (!node) return nullptr;
  const toml::array* entries = node->as_array();
  if (!entries)
    r.fail(*node, "inputs",
           fmt::format("expected an array of tables ([[inputs]] with id, description, unit, bound and "
                       "sensitivity), got {}",
                       type_name(*node)));
  return entries;
}

const toml::table& input_table(const Reader& r, const toml::array& entries, std::size_t k, std::string& p) {
  const toml::node& entry = *entries.get(k);
  p = fmt::format("inputs[{}]", k + 1);
  const toml::table* t = entry.as_table();
  if (!t) r.fail(entry, p, fmt::format("expected a table ([[inputs]]), got {}", type_name(entry)));
  return *t;
}

// An id that names nothing else of the configuration: a word of letters, digits and '_'.
void check_new_id(const Reader& r, const toml::table& t, const std::string& p, const std::string& id,
                  const Config& config) {
  const bool word = !id.empty() && std::all_of(id.begin(), id.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
  if (!word)
    r.fail(*t.get("id"), p + ".id",
           fmt::format("'{}' is no id; accepted: letters, digits and '_', e.g. id = \"temperature\"", id));
  const std::vector<std::string> fixed = fixed_term_ids(config);
  const bool taken = config.centrifuge.layout.find_parameter(id).has_value() ||
                     find_chain_input(id, config.chain, fixed, kMaxHarmonicOrder).has_value() ||
                     std::find(config.instrument.term_ids.begin(), config.instrument.term_ids.end(), id) !=
                         config.instrument.term_ids.end();
  if (taken)
    r.fail(*t.get("id"), p + ".id",
           fmt::format("'{}' names an input ccal models or a term already; accepted: an id of its own, e.g. "
                       "\"temperature\"",
                       id));
}

}  // namespace

void read_declared_inputs(const Reader& r, const toml::table& root, Config& config) {
  const toml::array* entries = input_entries(r, root);
  if (!entries) return;
  for (std::size_t k = 0; k < entries->size(); ++k) {
    std::string p;
    const toml::table& t = input_table(r, *entries, k, p);
    r.check_keys(t, p, kInputKeys);
    DeclaredInput in;
    const auto id = r.string(t, p, "id");
    if (!id) r.fail(t, p + ".id", "missing; give the input's id, e.g. id = \"temperature\"");
    check_new_id(r, t, p, *id, config);
    in.id = *id;
    in.description = r.string(t, p, "description").value_or("");
    const auto unit = r.string(t, p, "unit");
    if (!unit || unit->empty())
      r.fail(t, p + ".unit", "missing; give the unit its bound and sensitivities are in, e.g. unit = \"K\"");
    in.unit = *unit;
    const toml::table* sensitivity = r.table(t, p, "sensitivity", true,
                                             "give its sensitivity on each coefficient it moves, per one unit "
                                             "of the input, e.g. sensitivity = { K0 = \"0.002 deg/s\" }");
    const std::string sp = Reader::path(p, "sensitivity");
    for (const auto& [term, value] : *sensitivity) {
      const auto& terms = config.instrument.term_ids;
      if (std::find(terms.begin(), terms.end(), term.str()) == terms.end()) {
        std::string list;
        for (const std::string& s : terms) list += (list.empty() ? "" : ", ") + s;
        r.fail(where(term.source()), Reader::path(sp, term.str()),
               fmt::format("no term of the instrument; accepted: {}", list));
      }
      const std::string unit_text = coefficient_unit(config.instrument.output_unit, term.str(), config.instrument.g_symbol);
      const Dimension dim = parse_unit(pulse_as_rad(unit_text)).dim;
      in.sensitivity.emplace_back(
          term.str(), r.quantity_node(value, Reader::path(sp, term.str()), dim, nullptr,
                                      fmt::format("0.002 {} (per one {} of the input)", unit_text, in.unit)));
    }
    if (in.sensitivity.empty())
      r.fail(*t.get("sensitivity"), sp, "empty; give at least one coefficient it moves, e.g. { K0 = \"0.002 deg/s\" }");
    for (const DeclaredInput& other : config.chain.declared)
      if (other.id == in.id)
        r.fail(*t.get("id"), p + ".id", fmt::format("'{}' is declared twice; accepted: one entry per input", in.id));
    config.chain.declared.push_back(std::move(in));
  }
}

void read_declared_tolerances(const Reader& r, const toml::table& root, const Config& config,
                              std::vector<Tolerance>& out) {
  const toml::array* entries = input_entries(r, root);
  if (!entries) return;
  for (std::size_t k = 0; k < entries->size(); ++k) {
    std::string p;
    const toml::table& t = input_table(r, *entries, k, p);
    Tolerance tol;
    tol.parameter = chain_parameter({ChainKind::declared, int(k)});
    tol.id = config.chain.declared.at(k).id;
    if (!t.get("bound"))
      r.fail(t, p + ".bound",
             fmt::format("missing; give its tolerance in its unit ({}), e.g. bound = 0.05",
                         config.chain.declared.at(k).unit));
    read_tolerance_entry(r, t, t, p, config, tol);
    out.push_back(std::move(tol));
  }
}

}  // namespace ccal::config_reading
