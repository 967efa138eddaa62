#include "ccal/verbs/identify.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/core/units.hpp"

namespace ccal::verbs {
namespace {

// "K2" or "K2:Z2" of the option `field`; named terms need a column.
TableTerm parse_term_option(const std::string& text, std::string_view field) {
  const std::size_t colon = text.find(':');
  TableTerm t;
  t.id = text.substr(0, colon);
  const std::string f(field);
  if (colon != std::string::npos) {
    t.column = text.substr(colon + 1);
    if (t.column.empty())
      throw OptionError(f, "'" + text + "'",
                        "binds no column; accepted: <term> or <term>:<column>, e.g. K2:Z2");
  }
  const auto spec = parse_term(t.id);
  if (!spec)
    throw OptionError(f, "'" + t.id + "'",
                      fmt::format("is not a term id; accepted: {}", fmt::join(all_term_ids(), ", ")));
  if (spec->kind != TermKind::power && t.column.empty())
    throw OptionError(
        f, t.id,
        fmt::format("is not a power of the input, so it needs its column: bind it as {0}:<column>, "
                    "e.g. {0}:{0} (only K0 ... K10 are computed from the {1} column)",
                    t.id, OptionError::name("input_column")));
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
  u.output_column = o.output_column;
  u.input_column = o.input_column;
  if (header && o.output_column == "output") u.output_unit = header->output_unit;
  u.input_in_g = header.has_value() && o.input_column == "a_i";
  // Per standard gravity where the configuration says so, or where the file's fixed terms were written per gn.
  if (o.config) u.g_symbol = o.config->instrument.g_symbol;
  if (header)
    for (const ObservationsHeader::Fixed& f : header->fixed)
      if (f.unit.find("/gn") != std::string::npos) u.g_symbol = "gn";
  return u;
}

// A fix item "<term>[:<column>]=<value> [unit]", its value in the file's unit of the term.
TableFixed parse_fixed_option(const std::string& text, const ColumnUnits& units) {
  const std::string quoted = "'" + text + "'";
  const std::optional<TermAssignment> parts = split_term_assignment(text);  // as the file's header reads it
  if (!parts) throw OptionError("fix", quoted, "has no value; accepted: <term>=<value>, e.g. K1=505.2097");
  TableFixed f;
  f.term = parse_term_option(parts->term, "fix");
  const auto value = parse_number(parts->value);
  if (!value)
    throw OptionError("fix", fmt::format("'{}' in {}", parts->value, quoted),
                      "is not a finite number; accepted: <term>=<value>, e.g. K1=505.2097");
  f.value = *value;
  if (parts->unit.empty()) return f;
  if (units.output_unit.empty())
    throw OptionError(
        "fix", quoted,
        "has a unit, which needs the file's output_unit (an observations file of ccal simulate); "
        "accepted: the bare number in the file's units");
  try {
    f.value = convert_coefficient(f.value, parts->unit, term_unit(f.term, units));
  } catch (const UnitError& e) {
    throw OptionError("fix", quoted, std::string("has a unit that does not convert: ") + e.what());
  }
  return f;
}

// The known columns given as the option `known`: each once, none of them the output itself (y - y would
// leave nothing to fit: every coefficient 0 with standard error 0), "none" only alone.
void check_known_option(const std::vector<std::string>& known, const std::string& output_column) {
  std::set<std::string> seen;
  for (const auto& column : known) {
    if (column == "none")
      throw OptionError(
          "known", "none",
          "is listed with columns; accepted: 'none' alone (no column subtracted) or the columns "
          "to subtract, each once");
    if (column == output_column)
      throw OptionError("known", column,
                        fmt::format("is the output column ({}), which cannot be subtracted from itself; "
                                    "accepted: the columns of known contributions to subtract from the "
                                    "output, other than the output",
                                    OptionError::name("output_column")));
    if (!seen.insert(column).second)
      throw OptionError("known", column, "is listed twice; accepted: each column once");
  }
}

// One column in two roles (the input also the output, the weights the output or the input) fits nothing
// meaningful: y against itself gives exact coefficients with no error.
void check_column_roles(const IdentifyOptions& o) {
  const auto refuse = [](std::string_view field, const std::string& column, std::string_view other) {
    throw OptionError(std::string(field), column,
                      fmt::format("is also the {}; accepted: another column of the file for each role",
                                  OptionError::name(other)));
  };
  // An empty name (an unset shell variable) names no column: said of the option, not as a column not found.
  for (const auto& [field, column] : {std::pair<std::string_view, const std::string&>{"input_column", o.input_column},
                                      {"output_column", o.output_column}, {"weight_column", o.weight_column}})
    if (column.find_first_not_of(" \t") == std::string::npos && (field != "weight_column" || !column.empty()))
      throw OptionError(std::string(field), "'" + column + "'",
                        fmt::format("is {}; accepted: the name of a column of the file", column.empty() ? "empty"
                                                                                                        : "blank"));
  if (o.output_column == o.input_column) refuse("output_column", o.output_column, "input_column");
  if (!o.weight_column.empty() && o.weight_column == o.output_column)
    refuse("weight_column", o.weight_column, "output_column");
  if (!o.weight_column.empty() && o.weight_column == o.input_column)
    refuse("weight_column", o.weight_column, "input_column");
}

// The held terms: the option's (each neither free nor held twice), else the file's except those the user
// frees (their values converted to the terms' units); `ids` gains each.
std::vector<TableFixed> fixed_terms(const CsvTable& table, const std::optional<ObservationsHeader>& header,
                                    const IdentifyOptions& o, const ColumnUnits& units,
                                    std::set<std::string>& ids) {
  std::vector<TableFixed> fixed;
  if (o.fix) {
    for (const auto& text : *o.fix) {
      TableFixed f = parse_fixed_option(text, units);
      if (!ids.insert(f.term.id).second)
        throw OptionError(
            "fix", f.term.id,
            fmt::format("is also a free term or fixed twice; accepted: a term is either free ({}) "
                        "or fixed ({})",
                        OptionError::name("terms"), OptionError::name("fix")));
      fixed.push_back(std::move(f));
    }
    // --fix replaces the file's fixed terms: one it does not name (nor --terms frees) would silently leave
    // the model, and the fit would take its contribution into the other coefficients.
    if (header)
      for (const auto& hf : header->fixed)
        if (!ids.count(hf.term.id))
          throw OptionError(
              "fix", fmt::format("'{}'", fmt::join(*o.fix, ",")),
              fmt::format("replaces the fixed terms of {}, and its {} = {} {} would be left out of the model; "
                          "accepted: {} naming {} too (e.g. {}={}), or {} in {} to fit it",
                          table.source, hf.term.id, option_number_text(hf.value), hf.unit,
                          OptionError::name("fix"), hf.term.id, hf.term.id, option_number_text(hf.value),
                          hf.term.id, OptionError::name("terms")));
  } else if (header) {
    // The file's fixed terms, except those the user frees.
    for (const auto& hf : header->fixed) {
      if (ids.count(hf.term.id)) continue;
      TableFixed f{{hf.term.id, hf.term.column}, hf.value};
      if (!hf.unit.empty() && !units.output_unit.empty()) {
        try {
          f.value = convert_coefficient(hf.value, hf.unit, term_unit(f.term, units));
        } catch (const UnitError& e) {
          throw CsvError(table.source, header->line, 0, "ccal observations header",
                         fmt::format("fixed {}: {}", hf.term.id, e.what()));
        }
      }
      ids.insert(f.term.id);
      fixed.push_back(std::move(f));
    }
  }
  return fixed;
}

TableFitSpec fit_spec(const CsvTable& table, const std::optional<ObservationsHeader>& header,
                      const IdentifyOptions& o, const ColumnUnits& units) {
  check_column_roles(o);
  TableFitSpec spec;
  spec.input = o.input_column;
  spec.output = o.output_column;
  spec.weight = o.weight_column;

  if (o.terms) {
    for (const auto& text : *o.terms) spec.terms.push_back(parse_term_option(text, "terms"));
  } else if (header) {
    for (const auto& t : header->terms) spec.terms.push_back({t.id, t.column});
  } else {
    throw OptionError(
        "terms", "",
        fmt::format("{}: no '# ccal observations' line to take the terms from; accepted: the terms "
                    "to fit, e.g. K0,K1,K2 with {} x and {} y for y = K0 + K1 x + K2 x^2",
                    table.source, OptionError::name("input_column"), OptionError::name("output_column")));
  }
  std::set<std::string> ids;
  for (const auto& t : spec.terms)
    if (!ids.insert(t.id).second)
      throw OptionError("terms", t.id, "is listed twice; accepted: each term once");

  spec.fixed = fixed_terms(table, header, o, units, ids);

  if (o.known) {
    if (!(o.known->size() == 1 && o.known->front() == "none")) spec.known = *o.known;
    check_known_option(spec.known, o.output_column);
  } else if (header) {
    spec.known = header->known;
  }
  // An input column named by the user must be there, also where every term has a column of its own (an
  // observations file's) and the fit would not read it, so that a mistyped name is not passed over.
  if (o.input_column != IdentifyOptions{}.input_column && !table.find(o.input_column))
    (void)table.numbers(o.input_column, "the input column named");
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

constexpr auto kIdentifyRows = join_rows(
    std::to_array<OptionSpec<IdentifyOptions>>({
        {"terms",
         &IdentifyOptions::terms,
         "TERMS",
         "Free terms, comma-separated: Kn is the coefficient of input^n; <term>:<column> takes the column as the "
         "term's regressor (needed for K_p ... K_w). Default: the file's '# ccal observations' line",
         {},
         true},
        {"fix", &IdentifyOptions::fix, "TERM=VALUE",
         "Terms held at known values, comma-separated <term>[:<column>]=<value>, the value in the file's output "
         "unit per input unit^n (or with a unit). Default: the file's fixed terms"},
        {"known", &IdentifyOptions::known, "COL[,COL]",
         "Columns subtracted from the output, comma-separated, or 'none'. Default: the file's known columns"},
        {"input_column", &IdentifyOptions::input_column, "COL", "Column of the input x of the power terms"},
        {"output_column", &IdentifyOptions::output_column, "COL", "Column of the output y"},
        {"weight_column", &IdentifyOptions::weight_column, "COL",
         "Column of the standard deviations sigma of y (weights 1/sigma^2); default: unweighted"},
        {"statement", &IdentifyOptions::statement, "",
         "Also the calibration statement (JCGM 100 §7): Type A from the fit, Type B from the tolerances of the "
         "configuration given as config, the correction for its known [errors], u_c, nu_eff, k, U, interval"},
    }),
    lifted_rows<&IdentifyOptions::statement_options, kStatementRows>());

// The table's checks, and a statement asked for without its configuration or the other way round.
void check_verb_options(const IdentifyOptions& o) {
  check_options(o, option_table<IdentifyOptions>());
  if (o.statement && !o.config)
    throw OptionError("statement", "",
                      fmt::format("needs the configuration whose tolerances give its Type B part; accepted: "
                                  "that configuration as {}",
                                  OptionError::name("config")));
  if (o.config && !o.statement)
    throw OptionError("config", o.config->source,
                      fmt::format("is read only for the calibration statement; accepted: with {}",
                                  OptionError::name("statement")));
  if (!o.statement) refuse_statement_options_unasked(o.statement_options, "statement", true);
  if (o.config) require_one_instrument(*o.config, "identify");  // the observations are one instrument's
}

}  // namespace

OptionTable<IdentifyOptions> options_of(std::type_identity<IdentifyOptions>) { return kIdentifyRows; }

void check_observations_configuration(const CsvTable& table, const Config& config, std::string_view field) {
  const std::optional<ObservationsHeader> header = observations_header(table);
  // Files written before the fingerprint of the numbers carry the text's: either matches.
  if (!header || header->config_sha256.empty() || config.numbers_sha256.empty() ||
      header->config_sha256 == config.numbers_sha256 || header->config_sha256 == config.text_sha256)
    return;
  // Another instrument's of the same test: named, with the choice that takes it.
  for (const Config::OtherInstrument& other : config.other_instruments)
    if (header->config_sha256 == other.numbers_sha256)
      throw OptionError("instrument", config.instrument_id,
                        fmt::format("is not the instrument of {}: it holds instrument {}'s observations of {}; "
                                    "accepted: {}",
                                    table.source, other.id, config.source, other.id));
  throw OptionError(
      std::string(field), "",
      fmt::format("{} was made with another configuration than {}: the file's SHA-256 (line {}) "
                  "is {}, {}'s {}; accepted: the configuration the logs were reduced (or "
                  "simulated) with",
                  table.source, config.source, header->line, header->config_sha256, config.source,
                  config.numbers_sha256));
}

void refuse_empty_weight_column(std::string_view given) {
  if (given.empty())
    throw OptionError("weight_column", "''",
                      fmt::format("names no column; accepted: the column of the standard deviations of y, or {} "
                                  "left out for an unweighted fit",
                                  OptionError::name("weight_column")));
}

IdentifyResult identify(const CsvTable& table, const IdentifyOptions& options) {
  check_verb_options(options);
  IdentifyResult r;
  r.source = table.source;
  r.rows = table.rows.size();
  const std::optional<ObservationsHeader> header = observations_header(table);
  const ColumnUnits units = column_units(header, options);
  r.spec = fit_spec(table, header, options, units);
  r.identification = identify_table(table, r.spec, units, table.source);
  if (header) warn_about_powers_of_means(table, r.spec, r.identification);
  if (options.statement) {
    if (r.identification.fit.dof == 0 && !r.identification.weighted)
      throw OptionError(
          "statement", "",
          fmt::format("{}: {} rows for {} free terms leave no degrees of freedom, so the Type A "
                      "part (the standard errors) is undefined; accepted: more rows than free "
                      "terms, or the standard deviations of the output as {}",
                      table.source, r.rows, r.identification.fit.names.size(),
                      OptionError::name("weight_column")));
    check_observations_configuration(table, *options.config, "config");
    const TestEvidence evidence = test_evidence(header, r.identification);
    r.statement = calibration_statement(*options.config, r.identification, options.statement_options,
                                        "statement", evidence.measured, evidence.durations);
  }
  return r;
}

}  // namespace ccal::verbs
