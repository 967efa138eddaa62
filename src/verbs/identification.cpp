#include "ccal/verbs/identification.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "ccal/core/errors.hpp"
#include "ccal/core/format.hpp"

namespace ccal::verbs {

namespace {

std::string power_suffix(int n) { return n == 1 ? "" : fmt::format("^{}", n); }

}  // namespace

std::string term_unit(const TableTerm& term, const ColumnUnits& units) {
  const TermSpec spec = parse_term(term.id).value();
  const bool known = !units.output_unit.empty();
  if (!term.column.empty())
    return known ? coefficient_unit(units.output_unit, spec, units.g_symbol)
                 : fmt::format("{}/{}", units.output_column, term.column);
  if (spec.power == 0) return known ? units.output_unit : units.output_column;
  if (known && units.input_in_g) return coefficient_unit(units.output_unit, spec, units.g_symbol);
  return fmt::format("{}/{}{}", known ? units.output_unit : units.output_column, units.input_column,
                     power_suffix(spec.power));
}

std::string ill_posed_hint(const std::vector<std::string>& terms) {
  bool mounting = false, levels = false;
  for (const auto& id : terms) {
    const auto term = parse_term(id);
    if (!term) continue;
    switch (term->kind) {
      case TermKind::p:
      case TermKind::o:
      case TermKind::ip:
      case TermKind::io:
      case TermKind::pp:
      case TermKind::oo:
      case TermKind::po:
        mounting = true;
        break;
      case TermKind::power:
      case TermKind::abs_square:
        levels = true;
        break;
      case TermKind::rate:
        break;
    }
  }
  if (mounting)
    return "; runs with another mounting (ia_reversed, pa_vertical, ia_vertical) would separate them";
  if (levels) return "; add g-levels or runs with the IA reversed";
  return "";
}

namespace {

// No degrees of freedom (as many rows as free terms): the fit passes every row, so the residual scale is
// 0 / 0, and without weights the standard errors (and the covariance) scaled by it too. They are reported as
// undefined (NaN: "n/a" in the text, null in the JSON, an empty cell in the CSV), not as fit()'s zeros, which
// would read as exact coefficients, and the fit's warning says so.
void mark_undefined_scale(Identification& id) {
  FitResult& fit = id.fit;
  if (fit.dof != 0 || fit.names.empty()) return;
  constexpr double undefined = std::numeric_limits<double>::quiet_NaN();
  fit.residual_std = undefined;
  fit.chi2_per_dof = undefined;
  if (!id.weighted) {
    fit.std_error.setConstant(undefined);
    fit.covariance.setConstant(undefined);
  }
  std::erase_if(fit.warnings, [](const std::string& w) { return w.starts_with("no degrees of freedom"); });
  fit.warnings.insert(
      fit.warnings.begin(),
      fmt::format(
          "no degrees of freedom ({0} rows, {0} free terms): the fit passes every row, so {1} undefined "
          "(n/a in the text, null in the JSON, empty in the CSV); more rows than free terms{2}",
          fit.names.size(),
          id.weighted ? "the residual std and chi2/dof are (the standard errors come from the weights)"
                      : "the standard errors, the residual std and chi2/dof are",
          id.weighted ? " give them" : ", or a weight column, give standard errors"));
}

// The fit of a table's problem (the rows' line numbers label repeated run names).
Identification identify_problem(const FitProblem& problem, const TableFitSpec& spec, const ColumnUnits& units,
                                std::string_view source, const DataResolution* resolution,
                                const std::vector<int>& row_lines) {
  Identification id;
  try {
    id.fit = fit(problem);
  } catch (const IllPosedFit& e) {
    std::string message = e.what();
    if (message.starts_with("fit: ")) message.erase(0, 5);
    // A plain table has no plan: what separates its terms is more distinct values of its input column.
    const std::string hint = units.output_unit.empty()
                                 ? fmt::format("; accepted: rows at more distinct values of the input column ({})",
                                               units.input_column)
                                 : ill_posed_hint(e.terms());
    throw IllPosedFit(fmt::format("{}: {}{}", source, message, hint), e.terms());
  } catch (const InputError& e) {  // a solution that overflows: fit refuses results that are not finite
    std::string message = e.what();
    if (message.starts_with("fit: ")) message.erase(0, 5);
    throw InputError(fmt::format("{}: {}", source, message));
  }
  for (const auto& t : spec.terms) id.units.push_back(term_unit(t, units));
  id.observability = assess_fit(problem, id.fit, id.units, resolution, source);
  for (const auto& f : spec.fixed) id.fixed.push_back({f.term.id, f.value, term_unit(f.term, units)});
  id.known = spec.known;
  id.output_unit = units.output_unit;
  id.residual_unit = units.output_unit.empty() ? units.output_column : units.output_unit;
  id.weighted = !spec.weight.empty();
  id.design.resize(problem.H.rows(), Eigen::Index(id.fit.names.size()));
  for (std::size_t k = 0; k < id.fit.names.size(); ++k) {
    const auto column = std::find(problem.term_names.begin(), problem.term_names.end(), id.fit.names[k]);
    id.design.col(Eigen::Index(k)) = problem.H.col(Eigen::Index(column - problem.term_names.begin()));
  }
  id.modelled = problem.y - id.fit.residuals;
  // Residuals are keyed by run label; labels that repeat are replaced by the line numbers.
  id.row_labels = problem.row_labels;
  const std::set<std::string> distinct(id.row_labels.begin(), id.row_labels.end());
  if (distinct.size() != id.row_labels.size())
    for (std::size_t r = 0; r < id.row_labels.size(); ++r)
      id.row_labels[r] = fmt::format("line {}", row_lines[r]);
  mark_undefined_scale(id);  // identify, reduce and simulate alike
  return id;
}

// What the observations file's header line says to fit (observations_file_header), as identify reads it.
TableFitSpec observations_spec(const ObservationsHeader& header) {
  TableFitSpec s;
  for (const auto& t : header.terms) s.terms.push_back({t.id, t.column});
  for (const auto& f : header.fixed) s.fixed.push_back({{f.term.id, f.term.column}, f.value});
  s.known = header.known;
  return s;
}

// The problem table_fit_problem forms from that file, formed from the observations themselves: the file holds
// every number to 17 significant digits, which read back to the same doubles, so these are the very numbers
// (y = output − rate in the output unit, each term's column its regressor) and the fit is bit for bit the one
// of `ccal identify` on the file (tests/cli/simulate_test.cpp).
FitProblem observations_problem(const Observations<double>& obs, const TableFitSpec& s, double output_unit) {
  FitProblem p;
  const Eigen::Index rows = obs.output.size();
  p.y.resize(rows);
  for (Eigen::Index j = 0; j < rows; ++j) p.y[j] = obs.output[j] / output_unit;
  for (Eigen::Index j = 0; j < rows; ++j) p.y[j] -= obs.known_rate[j] / output_unit;
  std::vector<TableTerm> all = s.terms;
  for (const auto& f : s.fixed) all.push_back(f.term);
  p.H.resize(rows, Eigen::Index(all.size()));
  for (std::size_t k = 0; k < all.size(); ++k) {
    const auto column = std::find(obs.columns.begin(), obs.columns.end(), all[k].column);
    p.H.col(Eigen::Index(k)) = obs.regressors.col(Eigen::Index(column - obs.columns.begin()));
    p.term_names.push_back(all[k].id);
  }
  for (const auto& f : s.fixed) p.fixed[f.term.id] = f.value;
  p.row_labels = obs.runs;
  return p;
}

}  // namespace

Identification identify_table(const CsvTable& table, const TableFitSpec& spec, const ColumnUnits& units,
                              std::string_view source, const DataResolution* resolution) {
  return identify_problem(table_fit_problem(table, spec), spec, units, source, resolution, table.row_lines);
}

FileIdentification identify_observations(const Observations<double>& obs, const IdentificationSpec& spec,
                                         const InstrumentModel& instrument, std::string_view source,
                                         const DataResolution* resolution, std::string_view config_sha256,
                                         const std::vector<ObservationsHeader::Log>& logs,
                                         const std::vector<MeasuredInput>& measured) {
  // A run mean that is not finite is named by its run, not at a line of the generated CSV (which the source
  // name would place in the configuration file).
  for (Eigen::Index j = 0; j < obs.output.size(); ++j) {
    const bool finite = std::isfinite(obs.output[j]) && std::isfinite(obs.known_rate[j]) &&
                        std::isfinite(obs.input[j]) && obs.regressors.row(j).allFinite();
    if (!finite)
      throw InputError(fmt::format(
          "{}: the means of run '{}' are not finite (output {}, a_i {}): the errors or the logged values are "
          "beyond what double precision can carry; accepted: errors and outputs of a real centrifuge test",
          source, obs.runs[std::size_t(j)], obs.output[j], obs.input[j]));
  }
  const double unit = output_unit_si(instrument.output_unit);
  FileIdentification f;
  f.csv = observations_csv(obs, spec, instrument, config_sha256, logs, measured);
  f.spec = observations_spec(observations_file_header(spec, instrument));
  ColumnUnits units;
  units.output_unit = instrument.output_unit;
  units.input_in_g = true;
  units.g_symbol = instrument.g_symbol;
  // The file's rows start on line 3, after its header comment and column names.
  std::vector<int> row_lines(obs.runs.size());
  for (std::size_t r = 0; r < row_lines.size(); ++r) row_lines[r] = int(r) + 3;
  if (obs.output.size() < Eigen::Index(spec.free_terms.size()))
    throw InputError(fmt::format("{}: {} runs cannot determine {} free terms; accepted: at least {} runs",
                                 source, obs.output.size(), spec.free_terms.size(), spec.free_terms.size()));
  f.id =
      identify_problem(observations_problem(obs, f.spec, unit), f.spec, units, source, resolution, row_lines);
  return f;
}

}  // namespace ccal::verbs
