// ccal identify: least-squares identification of calibration coefficients from a CSV file of observations,
// either an observations file of `ccal simulate` (which records its terms) or any table with an input and an
// output column (docs/cli.md).
#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "ccal/observation_csv.hpp"
#include "ccal/units.hpp"
#include "ccal/version.hpp"
#include "commands.hpp"
#include "identification.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct IdentifyOptions {
  std::string file;
  std::vector<std::string> terms, fix, known;
  std::string input = "a_i";
  std::string output_column = "output";
  std::string weight;
  OutputOptions output;
  CLI::Option* terms_option = nullptr;
  CLI::Option* fix_option = nullptr;
  CLI::Option* known_option = nullptr;
};

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
  u.output_column = o.output_column;
  u.input_column = o.input;
  if (header && o.output_column == "output") u.output_unit = header->output_unit;
  u.input_in_g = header.has_value() && o.input == "a_i";
  return u;
}

TableFitSpec fit_spec(const CsvTable& table, const std::optional<ObservationsHeader>& header,
                      const IdentifyOptions& o, const ColumnUnits& units) {
  TableFitSpec spec;
  spec.input = o.input;
  spec.output = o.output_column;
  spec.weight = o.weight;

  if (o.terms_option->count() > 0) {
    for (const auto& text : o.terms) spec.terms.push_back(parse_term_option(text, "--terms"));
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
  if (o.fix_option->count() > 0) {
    for (const auto& text : o.fix) {
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

  if (o.known_option->count() > 0) {
    if (!(o.known.size() == 1 && o.known.front() == "none")) spec.known = o.known;
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

std::string to_text(const CsvTable& table, const TableFitSpec& spec, const Identification& id) {
  std::string subtracted;
  for (const auto& k : spec.known) subtracted += " - " + k;
  std::string out = fmt::format("ccal identify: {}, {} rows; {}{} fitted on {}{}\n\n", table.source,
                                table.rows.size(), spec.output, subtracted, fmt::join(id.fit.names, ", "),
                                spec.weight.empty() ? "" : fmt::format(" (weights 1/{}^2)", spec.weight));
  return out + identification_text(id);
}

std::string to_json(const CsvTable& table, const TableFitSpec& spec, const Identification& id) {
  nlohmann::ordered_json j;
  j["command"] = "identify";
  j["ccal_version"] = version();
  j["file"] = table.source;
  j["rows"] = table.rows.size();
  j["input"] = spec.input;
  j["output"] = spec.output;
  j["weight"] = spec.weight.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(spec.weight);
  const nlohmann::ordered_json fit = identification_json(id);
  for (const auto& [key, value] : fit.items()) j[key] = value;
  return j.dump(2) + "\n";
}

}  // namespace

Command add_identify(CLI::App& app) {
  auto o = std::make_shared<IdentifyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "identify",
      "Least-squares identification of calibration coefficients from a CSV file: an observations file of "
      "'ccal simulate' or any table of input and output.");
  cmd->add_option("file", o->file, "CSV file: a header row, then one row per observation")
      ->required()
      ->type_name("FILE.csv");
  o->terms_option =
      cmd->add_option(
             "--terms", o->terms,
             "Free terms, comma-separated: Kn is the coefficient of input^n; <term>:<column> takes the "
             "column as the term's regressor (needed for K_p ... K_w). Default: the file's "
             "'# ccal observations' line")
          ->delimiter(',')
          ->type_name("TERMS");
  o->fix_option =
      cmd->add_option("--fix", o->fix,
                      "Terms held at known values, comma-separated <term>[:<column>]=<value>, the value "
                      "in the file's output unit per input unit^n (or with a unit). Default: the "
                      "file's fixed terms")
          ->delimiter(',')
          ->type_name("TERM=VALUE");
  cmd->add_option("--input", o->input, "Column of the input x of the power terms")
      ->capture_default_str()
      ->type_name("COL");
  cmd->add_option("--output", o->output_column, "Column of the output y")
      ->capture_default_str()
      ->type_name("COL");
  cmd->add_option("--weight", o->weight, "Column of the standard deviations sigma of y (weights 1/sigma^2)")
      ->type_name("COL");
  o->known_option =
      cmd->add_option("--known", o->known,
                      "Columns subtracted from the output, comma-separated, or 'none'. Default: the "
                      "file's known columns")
          ->delimiter(',')
          ->type_name("COL[,COL]");
  add_output_options(*cmd, o->output, {"text", "json"}, false);  // --output names the output column
  cmd->footer(
      "Examples:\n"
      "  ccal simulate --observations-out obs.csv && ccal identify obs.csv\n"
      "      the paper's K0, K2, K3 from the simulated run means (terms, fixed K1 and the rate term from the "
      "file)\n"
      "  ccal identify obs.csv --terms K0,K2:K2,K3:K3 --fix K1=505.2097 --format json\n"
      "  ccal identify data.csv --input x --output y --terms K0,K1,K2 --weight sigma\n"
      "      polynomial y = K0 + K1 x + K2 x^2 of a plain table\n");

  return {cmd, [o] {
            note_input(o->file);
            const CsvTable table = read_csv_file(o->file);
            const std::optional<ObservationsHeader> header = observations_header(table);
            const ColumnUnits units = column_units(header, *o);
            const TableFitSpec spec = fit_spec(table, header, *o, units);
            Identification id = identify_table(table, spec, units, table.source);
            if (header) warn_about_powers_of_means(table, spec, id);
            write_output(o->output,
                         o->output.format == "json" ? to_json(table, spec, id) : to_text(table, spec, id));
          }};
}

}  // namespace ccal::cli
