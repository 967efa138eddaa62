#include "ccal/render/identify.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "budget_parts.hpp"
#include "ccal/version.hpp"
#include "parts.hpp"
#include "statement_part.hpp"

namespace ccal::render {

std::string text(const verbs::IdentifyResult& r) {
  const TableFitSpec& spec = r.spec;
  const verbs::Identification& id = r.identification;
  std::string subtracted;
  for (const auto& k : spec.known) subtracted += " - " + k;
  std::string out = fmt::format("ccal identify: {}, {} rows; {}{} fitted on {}{}\n\n", r.source, r.rows,
                                spec.output, subtracted, fmt::join(id.fit.names, ", "),
                                spec.weight.empty() ? "" : fmt::format(" (weights 1/{}^2)", spec.weight));
  out += identification_text(id);
  if (r.statement) {
    out += '\n';
    out += statement_text(*r.statement);
  }
  return out;
}

std::string json(const verbs::IdentifyResult& r) {
  const TableFitSpec& spec = r.spec;
  const verbs::Identification& id = r.identification;
  nlohmann::ordered_json j;
  j["command"] = "identify";
  j["ccal_version"] = version();
  j["file"] = r.source;
  j["rows"] = r.rows;
  j["input"] = spec.input;
  j["output"] = spec.output;
  j["weight"] = spec.weight.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(spec.weight);
  const nlohmann::ordered_json fit = identification_json(id);
  for (const auto& [key, value] : fit.items()) j[key] = value;
  if (r.statement) j["statement"] = statement_json(*r.statement);
  return j.dump(2) + "\n";
}

// One row per free term: the estimate with its standard error, and with the statement its parts, U and the
// interval (every number to 17 digits, so that the file reads back to the same doubles; ν = ∞ is "inf"). An
// undefined standard error (no degrees of freedom, unweighted) is an empty cell.
std::string csv(const verbs::IdentifyResult& r) {
  const verbs::Identification& id = r.identification;
  std::string out = "coefficient,unit,value,std_error";
  if (r.statement)
    out += ",correction,corrected,u_a,dof_a,u_b,u_c,nu_eff,coverage_probability,k,expanded,low,high";
  out += '\n';
  for (std::size_t k = 0; k < id.fit.names.size(); ++k) {
    const auto i = Eigen::Index(k);
    const double se = id.fit.std_error[i];
    out += fmt::format("{},{},{:.17g},{}", id.fit.names[k], budget_parts::csv_field(id.units[k]),
                       id.fit.value[i], std::isnan(se) ? std::string() : fmt::format("{:.17g}", se));
    if (r.statement) {
      const CoefficientStatement& c = r.statement->coefficients[k];
      out += fmt::format(
          ",{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
          "{:.17g},{:.17g}",
          c.input.correction, c.corrected, c.input.type_a.u, c.input.type_a.dof, c.input.type_b.u, c.combined,
          c.effective_dof, r.statement->coverage_probability, c.coverage_factor, c.expanded, c.low, c.high);
    }
    out += '\n';
  }
  return out;
}

}  // namespace ccal::render
