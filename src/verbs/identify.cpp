#include "ccal/verbs/identify.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <set>

#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"

namespace ccal::verbs {
namespace {

// "K2" or "K2:Z2" of an option; named terms need a column.
TableTerm parse_term_option(const std::string& text, std::string_view option) {
  const std::size_t colon = text.find(':');
  TableTerm t;
  t.id = text.substr(0, colon);
  if (colon != std::string::npos) {
    t.column = text.substr(colon + 1);
    if (t.column.empty())
      throw InputError(fmt::format(
          "{}: '{}' binds no column; accepted: <term> or <term>:<column>, e.g. K2:Z2", option, text));
  }
  const auto spec = parse_term(t.id);
  if (!spec)
    throw InputError(fmt::format("{}: '{}' is not a term id; accepted: {}", option, t.id,
                                 fmt::join(all_term_ids(), ", ")));
  if (spec->kind != TermKind::power && t.column.empty())
    throw InputError(
        fmt::format("{}: {} is not a power of the input, so it needs its column: bind it as {}:<column>, "
                    "e.g. {}:{} (only K0 ... K10 are computed from the --input column)",
                    option, t.id, t.id, t.id, t.id));
  return t;
}

// A coefficient written with a unit, converted to `expected` (the file's coefficient unit). Throws UnitError.
double convert_coefficient(double value, const std::string& unit, const std::string& expected) {
  if (unit == expected) return value;
  const auto pulse = [](std::string s) {
    for (std::size_t pos = s.find("pulse"); pos != std::string::npos; pos = s.find("pulse", pos + 3))
      s.replace(pos, 5, "rad");
    return s;
  };
  const Quantity given = parse_unit(pulse(unit));
  const Quantity wanted = parse_unit(pulse(expected));
  if (given.dim != wanted.dim)
    throw UnitError(
        fmt::format("'{}' is {}, but this coefficient is in {}", unit, describe(given.dim), expected));
  return value * given.value_si / wanted.value_si;
}

ColumnUnits column_units(const std::optional<ObservationsHeader>& header, const IdentifyOptions& o) {
  ColumnUnits u;
  u.output_column = o.output;
  u.input_column = o.input;
  if (header && o.output == "output") u.output_unit = header->output_unit;
  u.input_in_g = header.has_value() && o.input == "a_i";
  return u;
}

TableFitSpec fit_spec(const CsvTable& table, const std::optional<ObservationsHeader>& header,
                      const IdentifyOptions& o, const ColumnUnits& units) {
  TableFitSpec spec;
  spec.input = o.input;
  spec.output = o.output;
  spec.weight = o.weight;

  if (o.terms) {
    for (const auto& text : *o.terms) spec.terms.push_back(parse_term_option(text, "--terms"));
  } else if (header) {
    for (const auto& t : header->terms) spec.terms.push_back({t.id, t.column});
  } else {
    throw InputError(fmt::format(
        "{}: no '# ccal observations' line to take the terms from; accepted: --terms, e.g. --terms K0,K1,K2 "
        "--input x --output y for y = K0 + K1 x + K2 x^2",
        table.source));
  }
  if (spec.terms.empty()) throw InputError("--terms: no terms; accepted: e.g. --terms K0,K2,K3");
  std::set<std::string> ids;
  for (const auto& t : spec.terms)
    if (!ids.insert(t.id).second)
      throw InputError(fmt::format("--terms: {} is listed twice; accepted: each term once", t.id));

  auto expected_unit = [&](const TableTerm& t) { return term_unit(t, units); };
  if (o.fix) {
    for (const auto& text : *o.fix) {
      const std::size_t eq = text.find('=');
      if (eq == std::string::npos)
        throw InputError(
            fmt::format("--fix: '{}' has no value; accepted: <term>=<value>, e.g. K1=505.2097", text));
      TableFixed f;
      f.term = parse_term_option(text.substr(0, eq), "--fix");
      std::string_view rest(text);
      rest.remove_prefix(eq + 1);
      while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
      const std::size_t space = rest.find(' ');
      const auto value = parse_number(rest.substr(0, space));
      if (!value)
        throw InputError(
            fmt::format("--fix: '{}' in '{}' is not a finite number; accepted: <term>=<value>, e.g. "
                        "K1=505.2097",
                        rest.substr(0, space), text));
      f.value = *value;
      if (space != std::string_view::npos) {
        std::string unit(rest.substr(space + 1));
        while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
        if (!unit.empty()) {
          if (units.output_unit.empty())
            throw InputError(
                fmt::format("--fix: '{}': a value with a unit needs the file's output_unit (an "
                            "observations file of ccal simulate); accepted: the bare number in the "
                            "file's units",
                            text));
          try {
            f.value = convert_coefficient(f.value, unit, expected_unit(f.term));
          } catch (const UnitError& e) {
            throw InputError(fmt::format("--fix: '{}': {}", text, e.what()));
          }
        }
      }
      if (!ids.insert(f.term.id).second)
        throw InputError(
            fmt::format("--fix: {} is also a free term or fixed twice; accepted: a term is either "
                        "free (--terms) or fixed (--fix)",
                        f.term.id));
      spec.fixed.push_back(std::move(f));
    }
  } else if (header) {
    // The file's fixed terms, except those the user frees.
    for (const auto& hf : header->fixed) {
      if (ids.count(hf.term.id)) continue;
      TableFixed f{{hf.term.id, hf.term.column}, hf.value};
      if (!hf.unit.empty() && !units.output_unit.empty()) {
        try {
          f.value = convert_coefficient(hf.value, hf.unit, expected_unit(f.term));
        } catch (const UnitError& e) {
          throw CsvError(table.source, header->line, 0, "ccal observations header",
                         fmt::format("fixed {}: {}", hf.term.id, e.what()));
        }
      }
      ids.insert(f.term.id);
      spec.fixed.push_back(std::move(f));
    }
  }

  if (o.known) {
    if (!(o.known->size() == 1 && o.known->front() == "none")) spec.known = *o.known;
  } else if (header) {
    spec.known = header->known;
  }
  return spec;
}

// In an observations file the regressor of K2 is the run mean ⟨a_i²⟩, which is not ⟨a_i⟩² (on a
// counter-rotating run ⟨a_i⟩ is nearly 0 while ⟨a_i²⟩ ≈ A²/2): a power of the input where the file has the
// term's own column is almost certainly a mistake.
void warn_about_powers_of_means(const CsvTable& table, const TableFitSpec& spec, Identification& id) {
  std::vector<TableTerm> all = spec.terms;
  for (const auto& f : spec.fixed) all.push_back(f.term);
  for (const auto& t : all)
    if (t.column.empty() && parse_term(t.id)->power >= 2 && table.find(t.id))
      id.fit.warnings.push_back(fmt::format(
          "{0} is fitted as {1}^{2}, the power of the run means in the {1} column, but the file has a {0} "
          "column with the run means of the power (they differ unless {1} is constant over a run); bind it "
          "as "
          "{0}:{0} to use that column",
          t.id, spec.input, parse_term(t.id)->power));
}

}  // namespace

IdentifyResult identify(const CsvTable& table, const IdentifyOptions& options) {
  IdentifyResult r;
  r.source = table.source;
  r.rows = table.rows.size();
  const std::optional<ObservationsHeader> header = observations_header(table);
  const ColumnUnits units = column_units(header, options);
  r.spec = fit_spec(table, header, options, units);
  r.identification = identify_table(table, r.spec, units, table.source);
  if (header) warn_about_powers_of_means(table, r.spec, r.identification);
  if (options.budget)
    r.statement =
        calibration_statement(*options.budget, r.identification, options.statement, options.budget_option);
  return r;
}

}  // namespace ccal::verbs
