#include "statement_part.hpp"

#include <fmt/format.h>

#include <cmath>

#include "ccal/render/table.hpp"

namespace ccal::render {
namespace {

nlohmann::ordered_json dof_json(double dof) {
  return std::isfinite(dof) ? nlohmann::ordered_json(dof) : nlohmann::ordered_json(nullptr);
}

std::string dof_text(double dof, int digits = 3) { return std::isfinite(dof) ? number(dof, digits) : "inf"; }

// The statement's line (JCGM 100 §7.2.6): U to two significant digits, the estimate and the interval's ends
// to the same decimal place.
std::string statement_line(const CoefficientStatement& c, const std::string& pct) {
  const double U = c.expanded;
  std::string estimate = number(c.corrected, 8), expanded = number(U, 2), low = number(c.low, 8),
              high = number(c.high, 8);
  if (U > 0 && std::isfinite(U)) {
    const int last = int(std::floor(std::log10(U))) - 1;  // the place of U's second digit
    const double step = std::pow(10.0, last);
    const int decimals = last < 0 ? -last : 0;
    const auto at = [&](double v) { return fmt::format("{:.{}f}", std::round(v / step) * step, decimals); };
    estimate = at(c.corrected);
    expanded = at(U);
    low = at(c.low);
    high = at(c.high);
  }
  return fmt::format("  {} = ({} ± {}) {}, k = {:.3f}, p = {}: [{}, {}]", c.input.coefficient, estimate,
                     expanded, c.input.unit, c.coverage_factor, pct, low, high);
}

}  // namespace

nlohmann::ordered_json statement_json(const verbs::CalibrationStatement& st) {
  nlohmann::ordered_json j;
  j["budget_config"] = st.budget_config;
  j["mode"] = mode_name(st.mode);
  j["coverage_probability"] = st.coverage_probability;
  j["known_errors"] = st.known_errors;
  j["compensated"] = st.compensated;
  nlohmann::ordered_json coefficients = nlohmann::ordered_json::object();
  for (const CoefficientStatement& c : st.coefficients) {
    nlohmann::ordered_json o;
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
    coefficients[c.input.coefficient] = o;
  }
  j["coefficients"] = coefficients;
  return j;
}

std::string statement_text(const verbs::CalibrationStatement& st, std::size_t width) {
  const std::string pct = fmt::format("{:g} %", 100 * st.coverage_probability);
  std::string out = wrap_words(
      fmt::format(
          "Calibration statement (JCGM 100 §7): Type A from the fit, Type B from the tolerances of {} "
          "({} mode), u_c² = u_A² + u_B², nu_eff by Welch-Satterthwaite, k from Student's t at "
          "p = {}; known [errors]: {}.",
          st.budget_config, mode_name(st.mode), pct,
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
  Table parts({"coefficient", "u_A (fit)", "nu_A", "u_B (budget)", "u_c", "nu_eff", "k", "U"});
  parts.gap(2);
  for (const CoefficientStatement& c : st.coefficients)
    parts.add_row({c.input.coefficient, number(c.input.type_a.u, 4), dof_text(c.input.type_a.dof),
                   number(c.input.type_b.u, 4), number(c.combined, 4), dof_text(c.effective_dof),
                   fmt::format("{:.3f}", c.coverage_factor), number(c.expanded, 3)});
  out += parts.render("  ", width);
  for (const CoefficientStatement& c : st.coefficients)
    out += wrap_words(statement_line(c, pct), width, "    ");
  return out;
}

}  // namespace ccal::render
