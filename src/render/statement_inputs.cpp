// The calibration statement's Type A evaluation and its table of Type B inputs (the GUM table: each input's
// u, whether the test measured it or its tolerance bounds it, and what it does to each coefficient).
#include <fmt/format.h>

#include <cmath>

#include "ccal/core/units.hpp"
#include "ccal/render/table.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "parts.hpp"
#include "statement_part.hpp"

namespace ccal::render {
namespace {

// u in the unit the input is shown in (as written, else its own).
std::pair<double, std::string> shown_uncertainty(const verbs::StatementSource& s) {
  if (!s.unit.empty() && s.unit_si > 0) return {s.standard_uncertainty / s.unit_si, s.unit};
  return {s.standard_uncertainty, "SI"};
}

}  // namespace

std::string type_a_text(const verbs::CalibrationStatement& st, std::size_t width) {
  const verbs::TypeAEvaluation& a = st.type_a;
  if (!a.from_noise_model)
    return wrap_words(fmt::format("Type A: the fit's scatter (its residual standard error, nu = n - p = {}): the "
                                  "configuration states no noise of the instrument or the drives, or the rows "
                                  "are not runs of its plan.",
                                  a.dof),
                      width);
  std::string out = wrap_words(
      "Type A: the noise model (the instrument's noise density and quantum, the drives' rate noise: the sigma of "
      "each run mean) through the fit, nu = inf. The residuals tested against that noise and the Type B "
      "inputs' between-run effects:",
      width);
  out += wrap_words(fmt::format("S = sum r^2/sigma^2 = {}, expected {}, p-value {} ({} degrees of freedom): {}",
                                number(a.statistic, 4), number(a.expected, 4), number(a.p_value, 3), a.dof,
                                a.excess ? fmt::format("the scatter exceeds the prediction (p < {}); the excess, "
                                                       "{} per run mean (sigma), is charged as Type A with nu = {}",
                                                       verbs::kResidualCheckLevel,
                                                       number(std::sqrt(a.excess_variance), 3), a.dof)
                                         : "the model explains the scatter, nothing more is charged"),
                    width, "  ");
  return out;
}

std::string inputs_text(const verbs::CalibrationStatement& st, std::size_t width) {
  if (st.inputs.empty()) return "";
  std::vector<std::string> header{"input", "u", "unit", "from"};
  for (const CoefficientStatement& c : st.coefficients) header.push_back("u_i(" + c.input.coefficient + ")");
  Table t(header);
  t.gap(2);
  int measured = 0, silent = 0;
  for (const verbs::StatementSource& s : st.inputs) {
    bool acts = false;  // on some coefficient beyond the derivatives' round-off (kRoundOffFloor of its u_c)
    for (std::size_t k = 0; k < s.effect.size() && k < st.coefficients.size(); ++k)
      acts = acts || std::abs(s.effect[k]) >= kRoundOffFloor * st.coefficients[k].combined;
    if (!acts) {
      ++silent;
      continue;
    }
    const auto [u, unit] = shown_uncertainty(s);
    std::vector<std::string> row{s.id, number(u, 3), unit, s.measured ? "measured" : "tolerance"};
    for (double e : s.effect) row.push_back(number(e, 3));
    t.add_row(row);
    measured += s.measured;
  }
  return wrap_words(fmt::format("Type B inputs (u_i: signed effect c u in each coefficient's unit; {} measured in "
                                "this test, charged at the measurement's uncertainty, the rest from their "
                                "tolerances{}):",
                                measured,
                                silent ? fmt::format("; {} more act on no coefficient, listed in the JSON", silent)
                                       : std::string()),
                    width) +
         t.render("  ", width);
}

nlohmann::ordered_json type_a_json(const verbs::CalibrationStatement& st) {
  const verbs::TypeAEvaluation& a = st.type_a;
  nlohmann::ordered_json j{{"from_noise_model", a.from_noise_model}, {"dof", a.dof}};
  if (a.from_noise_model) {
    j["run_sd"] = a.run_sd;
    j["residual_check"] = {{"statistic", a.statistic},
                           {"expected", a.expected},
                           {"p_value", a.p_value},
                           {"level", verbs::kResidualCheckLevel},
                           {"excess", a.excess},
                           {"excess_variance", a.excess_variance}};
  }
  return j;
}

nlohmann::ordered_json inputs_json(const verbs::CalibrationStatement& st) {
  nlohmann::ordered_json inputs = nlohmann::ordered_json::array();
  for (const verbs::StatementSource& s : st.inputs) {
    nlohmann::ordered_json effect = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < s.effect.size() && k < st.coefficients.size(); ++k)
      effect[st.coefficients[k].input.coefficient] = s.effect[k];
    inputs.push_back({{"id", s.id},
                      {"u_si", s.standard_uncertainty},
                      {"u", s.standard_uncertainty / s.unit_si},
                      {"unit", s.unit},
                      {"measured", s.measured},
                      {"basis", s.basis},
                      {"effect", effect},
                      {"group", s.group}});
  }
  return inputs;
}

}  // namespace ccal::render
