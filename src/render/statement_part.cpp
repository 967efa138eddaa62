#include "statement_part.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>

#include "budget_parts.hpp"
#include "ccal/render/statement.hpp"
#include "ccal/render/table.hpp"
#include "ccal/version.hpp"
#include "parts.hpp"

namespace ccal::render {
namespace {

using Json = nlohmann::ordered_json;

std::string dof_text(double dof, int digits = 3) { return std::isfinite(dof) ? number(dof, digits) : "inf"; }

std::string percent_g(double p) { return fmt::format("{:g} %", 100 * p); }

// The statement's line: the figures rounded per JCGM 100 §7.2.6 (statement.hpp, round_figures); the Monte
// Carlo's interval, not centred on the estimate, with its ends only.
std::string statement_line(const CoefficientStatement& c, const std::string& pct) {
  const RoundedFigures r = round_figures(c);
  if (c.method == IntervalMethod::monte_carlo)
    return fmt::format("  {} = {} {}, p = {}: [{}, {}] (the Monte Carlo's interval, JCGM 101)", c.input.coefficient,
                       r.estimate, c.input.unit, pct, r.low, r.high);
  if (c.stated)  // the p a stated k gives: a normal quantity's, and Student's t at ν_eff where that is finite
    return fmt::format("  {} = ({} ± {}) {}, k = {:g} (stated), p = {:.4g} % for a normal quantity{}: [{}, {}]",
                       c.input.coefficient, r.estimate, r.expanded, c.input.unit, c.coverage_factor,
                       100 * c.stated->normal,
                       std::isfinite(c.effective_dof)
                           ? fmt::format(", {:.4g} % for Student's t at nu_eff = {}", 100 * c.stated->student_t,
                                         dof_text(c.effective_dof))
                           : std::string(),
                       r.low, r.high);
  return fmt::format("  {} = ({} ± {}) {}, k = {:.3f}, p = {}: [{}, {}]", c.input.coefficient, r.estimate,
                     r.expanded, c.input.unit, c.coverage_factor, pct, r.low, r.high);
}

Json monte_carlo_json(const CoefficientStatement& c) {
  if (!c.monte_carlo) return nullptr;
  const OutputSummary& m = *c.monte_carlo;
  const ValidationDiagnosis d = validation_diagnosis(m, c.monte_carlo_trials);
  return {{"mean", m.mean},
          {"standard_uncertainty", m.std_dev},
          {"interval_symmetric", {m.low_symmetric, m.high_symmetric}},
          {"interval_shortest", {m.low_shortest, m.high_shortest}},
          {"student_t_expanded_uncertainty", m.lpu_expanded},
          {"d_low", m.d_low},
          {"d_high", m.d_high},
          {"delta", m.validation_delta},
          {"validated", m.validated},
          {"interval_end_std_error", m.interval_end_std_error},
          {"explained_by_sampling", d.explained_by_sampling},
          {"trials_needed", d.trials_needed}};
}

Json matrix_json(const Eigen::MatrixXd& m) {
  Json rows = Json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    Json row = Json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    rows.push_back(row);
  }
  return rows;
}

Json quantity_json(const CoefficientStatement& c) {
  const RoundedFigures r = round_figures(c);
  Json o;
  o["unit"] = c.input.unit;
  o["estimate"] = c.input.estimate;
  o["correction"] = c.input.correction;
  o["corrected_estimate"] = c.corrected;
  o["type_a"] = {{"u", c.input.type_a.u}, {"dof", dof_json(c.input.type_a.dof)}};
  o["type_b"] = {{"u", c.input.type_b.u}, {"dof", dof_json(c.input.type_b.dof)}};
  o["combined_standard_uncertainty"] = c.combined;
  o["effective_dof"] = dof_json(c.effective_dof);
  o["coverage_factor"] = c.coverage_factor;
  o["expanded_uncertainty"] = c.expanded;
  o["interval"] = {c.low, c.high};
  o["significant"] = c.significant;
  o["interval_method"] = std::string(kIntervalMethodNames[std::size_t(c.method)]);
  // With a stated k: the coverage probability it gives a normal quantity, and Student's t at ν_eff (null
  // for ν_eff = ∞, where it is the normal's).
  if (c.stated)
    o["stated_coverage_probability"] = {
        {"normal", c.stated->normal},
        {"student_t", std::isfinite(c.effective_dof) ? Json(c.stated->student_t) : Json(nullptr)}};
  o["monte_carlo"] = monte_carlo_json(c);
  o["rounded"] = {{"estimate", r.estimate},
                  {"expanded_uncertainty", r.expanded},
                  {"interval", {r.low, r.high}},
                  {"place", r.place ? Json(*r.place) : Json(nullptr)}};
  return o;
}

// A square matrix of the coefficients as a text table, `digits` significant digits.
std::string matrix_text(const verbs::CalibrationStatement& st, const Eigen::MatrixXd& m, int digits,
                        std::size_t width) {
  std::vector<std::string> header{""};
  for (const CoefficientStatement& c : st.coefficients) header.push_back(c.input.coefficient);
  Table t(header);
  t.gap(2);
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    std::vector<std::string> row{st.coefficients[std::size_t(r)].input.coefficient};
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(number(m(r, c), digits));
    t.add_row(row);
  }
  return t.render("  ", width);
}

std::string outputs_text(const verbs::CalibrationStatement& st, std::size_t width) {
  if (st.outputs.empty()) return "";
  std::vector<std::string> header{"run", "g-level"};
  for (const char* h : {"modelled output", "u_A", "u_B", "u_c", "nu_eff", "k", "U"}) header.push_back(h);
  Table t(header);
  t.gap(2);
  for (std::size_t r = 0; r < st.outputs.size(); ++r) {
    const CoefficientStatement& o = st.outputs[r];
    std::vector<std::string> row{o.input.coefficient};
    row.push_back(std::isfinite(st.g_levels[r]) ? fmt::format("{} g", number(st.g_levels[r], 6)) : "-");
    for (const std::string& cell :
         {number(o.corrected, 10), number(o.input.type_a.u, 4), number(o.input.type_b.u, 4),
          number(o.combined, 4), dof_text(o.effective_dof), fmt::format("{:.3f}", o.coverage_factor),
          number(o.expanded, 3)})
      row.push_back(cell);
    t.add_row(row);
  }
  return wrap_words(fmt::format("Modelled output of each run from the covariance, ŷ = hᵀ(K̂ + b) with h the run's "
                                "regressors (fixed terms included, known columns left out) [{}]:",
                                st.outputs.front().input.unit),
                    width) +
         t.render("  ", width);
}

// How M came to be what it is, when it is not the requested: the check went on until every verdict was
// settled, or stopped at its cap.
std::string trials_note(const verbs::CalibrationStatement& st) {
  if (st.monte_carlo_trials == st.monte_carlo_requested_trials) return "";
  return fmt::format(" ({} requested; {})", st.monte_carlo_requested_trials,
                     st.monte_carlo_settled ? "more until every verdict was beyond the sampling error"
                                            : "more up to the cap, a verdict still within the sampling error");
}

// Which interval a checked statement states, and why.
std::string stated_text(const CoefficientStatement& c) {
  if (c.method == IntervalMethod::monte_carlo) return "Monte Carlo";
  if (c.method == IntervalMethod::coverage_factor)
    return fmt::format("k = {:g} stated ({})", c.coverage_factor, c.monte_carlo->validated ? "holds" : "not validated");
  if (c.monte_carlo->validated) return "Student t";
  return fmt::format("Student t (M too small to tell: {} trials would)",
                     validation_diagnosis(*c.monte_carlo, c.monte_carlo_trials).trials_needed);
}

// The Monte Carlo check of each coefficient, and which modelled outputs take the Monte Carlo's interval.
std::string monte_carlo_text(const verbs::CalibrationStatement& st, std::size_t width) {
  if (st.monte_carlo_trials == 0)
    return wrap_words("No Monte Carlo check of the intervals (statement trials 0, or no [tolerances]).", width);
  std::string out = wrap_words(
      fmt::format("Monte Carlo check (JCGM 101 §8; M = {}{}, seed {}): the {} interval holds where both "
                  "its ends are within δ (u_c to two significant digits) of the Monte Carlo's probabilistically "
                  "symmetric interval; {}:",
                  st.monte_carlo_trials, trials_note(st), st.monte_carlo_seed,
                  st.coverage_factor ? "stated" : "Student-t",
                  st.coverage_factor ? "the stated k is kept either way" : "where not, the Monte Carlo's interval is stated"),
      width);
  Table t({"coefficient", "u (MC)", "MC low", "MC high", "d_low", "d_high", "delta", "stated"});
  t.gap(2);
  for (const CoefficientStatement& c : st.coefficients) {
    if (!c.monte_carlo) continue;
    const OutputSummary& m = *c.monte_carlo;
    t.add_row({c.input.coefficient, number(m.std_dev, 4), number(m.low_symmetric, 6), number(m.high_symmetric, 6),
               number(m.d_low, 2), number(m.d_high, 2), number(m.validation_delta, 2),
               stated_text(c)});
  }
  out += t.render("  ", width);
  std::vector<std::string> runs;
  for (const CoefficientStatement& o : st.outputs)
    if (o.method == IntervalMethod::monte_carlo) runs.push_back(o.input.coefficient);
  if (!st.outputs.empty())
    out += wrap_words(st.coverage_factor ? fmt::format("Modelled outputs: y ± k u_c with the stated k = {:g}.",
                                                       *st.coverage_factor)
                      : runs.empty()     ? std::string("Modelled outputs: every Student-t interval holds.")
                                   : fmt::format("Modelled outputs with the Monte Carlo's interval: {}.",
                                                 fmt::join(runs, ", ")),
                      width, "  ");
  return out;
}

}  // namespace

nlohmann::ordered_json statement_json(const verbs::CalibrationStatement& st) {
  Json j;
  j["budget_config"] = st.budget_config;
  j["config_sha256"] = st.config_sha256;
  j["setup_sha256"] = st.setup_sha256;
  j["ccal_version"] = version();
  // What `ccal history add` records it under: the [certificate]'s instrument, serial number and date, and its
  // number, revision and the certificate it replaces (each "" when not set).
  if (!st.serial_number.empty() || !st.date_of_calibration.empty() || !st.instrument.empty() ||
      !st.certificate_number.empty() || !st.revision.empty() || !st.replaces.empty())
    j["certificate"] = {{"instrument", st.instrument},
                        {"serial_number", st.serial_number},
                        {"date_of_calibration", st.date_of_calibration},
                        {"number", st.certificate_number},
                        {"revision", st.revision},
                        {"replaces", st.replaces}};
  j["mode"] = mode_name(st.mode);
  j["coverage_probability"] = st.coverage_probability;
  // A k the user stated (a contract): every U is k u_c; null when k follows from the coverage probability.
  j["coverage_factor"] = st.coverage_factor ? Json(*st.coverage_factor) : Json(nullptr);
  j["known_errors"] = st.known_errors;
  j["compensated"] = st.compensated;
  j["monte_carlo"] = st.monte_carlo_trials > 0 ? Json{{"trials", st.monte_carlo_trials},
                                                     {"requested_trials", st.monte_carlo_requested_trials},
                                                     {"settled", st.monte_carlo_settled},
                                                     {"seed", st.monte_carlo_seed}}
                                               : Json(nullptr);
  Json coefficients = Json::object();
  Json names = Json::array();
  for (const CoefficientStatement& c : st.coefficients) {
    coefficients[c.input.coefficient] = quantity_json(c);
    names.push_back(c.input.coefficient);
  }
  j["coefficients"] = coefficients;
  j["type_a"] = type_a_json(st);
  j["inputs"] = inputs_json(st);
  j["input_correlations"] = Json::array();
  for (const Correlation& c : st.input_correlations)
    j["input_correlations"].push_back({c.first, c.second, c.r});
  j["covariance"] = {{"order", names},
                     {"type_a", matrix_json(st.covariance_a)},
                     {"type_b", matrix_json(st.covariance_b)},
                     {"combined", matrix_json(st.covariance)},
                     {"correlation", matrix_json(st.correlation)}};
  Json outputs = Json::array();
  for (std::size_t r = 0; r < st.outputs.size(); ++r) {
    Json o = {{"run", st.outputs[r].input.coefficient},
              {"g_level", std::isfinite(st.g_levels[r]) ? Json(st.g_levels[r]) : Json(nullptr)}};
    o.update(quantity_json(st.outputs[r]));
    outputs.push_back(o);
  }
  j["modelled_output"] = outputs;
  return j;
}

std::string statement_text(const verbs::CalibrationStatement& st, std::size_t width) {
  const std::string pct = percent_g(st.coverage_probability);
  std::string out = wrap_words(
      fmt::format(
          "Calibration statement (JCGM 100 §7): Type A from the noise, Type B from the inputs of {} "
          "({} mode), u_c² = u_A² + u_B², nu_eff by Welch-Satterthwaite, {}; known [errors]: {}.",
          st.budget_config, mode_name(st.mode),
          st.coverage_factor ? fmt::format("k = {:g} stated (p = {} for a normal quantity)", *st.coverage_factor, pct)
                             : fmt::format("k from Student's t at p = {}", pct),
          st.known_errors == 0 ? "none"
          : st.compensated     ? "compensated in the model (no correction)"
                               : "not compensated, corrected here"),
      width);
  Table values({"coefficient", "estimate", "correction", "corrected estimate", "unit"});
  values.gap(2);
  for (const CoefficientStatement& c : st.coefficients)
    values.add_row({c.input.coefficient, number(c.input.estimate, 10), number(c.input.correction, 4),
                    number(c.corrected, 10), c.input.unit});
  out += values.render("  ", width);
  Table parts({"coefficient", "u_A", "nu_A", "u_B", "u_c", "nu_eff", "k", "U"});
  parts.gap(2);
  for (const CoefficientStatement& c : st.coefficients)
    parts.add_row({c.input.coefficient, number(c.input.type_a.u, 4), dof_text(c.input.type_a.dof),
                   number(c.input.type_b.u, 4), number(c.combined, 4), dof_text(c.effective_dof),
                   fmt::format("{:.3f}", c.coverage_factor), number(c.expanded, 3)});
  out += parts.render("  ", width);
  out += type_a_text(st, width);
  out += inputs_text(st, width);
  out += wrap_words("Correlation of the corrected estimates (Type A + Type B; the covariance is in the JSON and "
                    "CSV exports):",
                    width);
  out += matrix_text(st, st.correlation, 4, width);
  out += outputs_text(st, width);
  out += monte_carlo_text(st, width);
  out += wrap_words(fmt::format("Result, U to two significant digits (JCGM 100 §7.2.6):"), width);
  for (const CoefficientStatement& c : st.coefficients)
    out += wrap_words(statement_line(c, pct), width, "    ");
  for (const CoefficientStatement& c : st.coefficients)
    if (!c.significant)
      out += wrap_words(fmt::format("  {0}'s interval holds 0: the test does not tell {0} from zero at p = {1}. A "
                                    "plan with higher or more g-levels lowers U({0}); ccal design finds one "
                                    "(--target {0}=U for the U needed).",
                                    c.input.coefficient, pct),
                        width, "    ");
  return out;
}

std::string text(const verbs::CalibrationStatement& statement) { return statement_text(statement); }

std::string json(const verbs::CalibrationStatement& statement) { return statement_json(statement).dump(2) + "\n"; }

std::string csv(const verbs::CalibrationStatement& st) {
  // One row per coefficient: its statement in full precision (the shortest digits that read back to the
  // same doubles), the rounded figures as written, and its row of the combined covariance.
  std::string out = "coefficient,unit,corrected_estimate,expanded_uncertainty,coverage_factor,"
                    "coverage_probability,effective_dof,low,high,combined_standard_uncertainty,u_a,dof_a,u_b,"
                    "significant,rounded_estimate,rounded_expanded_uncertainty,rounded_low,rounded_high,interval_method,"
                    "mc_trials,mc_standard_uncertainty,mc_low,mc_high,mc_d_low,mc_d_high,mc_delta,mc_validated";
  for (const CoefficientStatement& c : st.coefficients)
    out += fmt::format(",{}", budget_parts::csv_field(fmt::format("cov_{}", c.input.coefficient)));
  out += "\n";
  // Shortest round-trip digits; an infinite ν is "inf" (JSON's null), a NaN "nan". The rounded figures are
  // text, quoted, so that a reader that keeps quoted fields as text reads 0.020 and not 0.02.
  const auto as_text = [](const std::string& figure) { return "\"" + figure + "\""; };
  const auto full = [](double v) {
    return std::isfinite(v) ? fmt::format("{}", v) : std::isnan(v) ? std::string("nan") : std::string("inf");
  };
  for (std::size_t i = 0; i < st.coefficients.size(); ++i) {
    const CoefficientStatement& c = st.coefficients[i];
    const RoundedFigures r = round_figures(c);
    out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}", budget_parts::csv_field(c.input.coefficient),
                       budget_parts::csv_field(c.input.unit),
                       full(c.corrected), full(c.expanded), full(c.coverage_factor), full(st.coverage_probability),
                       full(c.effective_dof), full(c.low), full(c.high), full(c.combined), full(c.input.type_a.u),
                       full(c.input.type_a.dof), full(c.input.type_b.u), c.significant ? "true" : "false",
                       as_text(r.estimate), as_text(r.expanded), as_text(r.low), as_text(r.high));
    out += fmt::format(",{}", kIntervalMethodNames[std::size_t(c.method)]);
    if (c.monte_carlo) {
      const OutputSummary& m = *c.monte_carlo;
      out += fmt::format(",{},{},{},{},{},{},{},{}", c.monte_carlo_trials, full(m.std_dev), full(m.low_symmetric),
                         full(m.high_symmetric), full(m.d_low), full(m.d_high), full(m.validation_delta),
                         m.validated ? "true" : "false");
    } else {
      out += ",,,,,,,,";
    }
    for (Eigen::Index k = 0; k < st.covariance.cols(); ++k)
      out += fmt::format(",{}", full(st.covariance(Eigen::Index(i), k)));
    out += "\n";
  }
  return out;
}

}  // namespace ccal::render
