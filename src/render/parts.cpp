#include "parts.hpp"

#include <fmt/format.h>

#include <cmath>

#include "ccal/render/identification.hpp"
#include "ccal/render/table.hpp"

namespace ccal::render {

using verbs::Identification;
using verbs::ObservabilityReport;

nlohmann::ordered_json observability_json(const ObservabilityReport& report) {
  const ObservabilityResult& r = report.result;
  nlohmann::ordered_json j;
  j["detection_factor"] = r.detection_factor;
  j["resolution_basis"] = report.basis;
  j["run_resolution"] = std::vector<double>(r.resolution.data(), r.resolution.data() + r.resolution.size());
  j["whole_revolutions"] = r.whole_revolutions;
  nlohmann::ordered_json terms = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < r.terms.size(); ++k) {
    const TermObservability& t = r.terms[k];
    nlohmann::ordered_json x;
    x["status"] = term_status_name(t.status);
    x["sensitivity"] = t.sensitivity;
    x["fraction"] = t.fraction;
    x["standard_error"] = t.standard_error;
    x["min_detectable"] = t.min_detectable;
    x["unit"] = report.units[k];
    if (!t.reason.empty()) {
      x["reason"] = t.reason;
      x["fix"] = t.fix;
    }
    terms[t.term] = x;
  }
  j["terms"] = terms;
  j["warnings"] = report.warnings;
  return j;
}

std::string observability_text(const ObservabilityReport& report) {
  const ObservabilityResult& r = report.result;
  std::string out =
      fmt::format("  observability (resolution of the run means: {}; detectable = {:g} sigma)\n",
                  report.basis, r.detection_factor);
  Table table({"term", "sensitivity", "fraction", "std error", "min detectable", "unit", "status"});
  for (std::size_t k = 0; k < r.terms.size(); ++k) {
    const TermObservability& t = r.terms[k];
    table.add_row({t.term, number(t.sensitivity, 4), number(t.fraction, 3), number(t.standard_error, 3),
                   number(t.min_detectable, 3), report.units[k], std::string(term_status_name(t.status))});
  }
  out += table.render();
  out +=
      "  (sensitivity: run-mean change per unit coefficient, root-sum-square over runs, in the regressor's "
      "unit;\n   fraction: of the regressor's size before averaging, what only this term explains)\n";
  for (const auto& w : report.warnings) out += "  - warning: " + w + "\n";
  return out;
}

// A statistic of the fit that is undefined (NaN: no degrees of freedom): "n/a" in the text.
namespace {
std::string defined_number(double v, int digits) { return std::isnan(v) ? "n/a" : number(v, digits); }
}  // namespace

nlohmann::ordered_json identification_json(const Identification& id) {
  const FitResult& r = id.fit;
  nlohmann::ordered_json j;
  nlohmann::ordered_json coefficients = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < r.names.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    coefficients[r.names[k]] = {{"value", r.value[i]}, {"std_error", r.std_error[i]}, {"unit", id.units[k]}};
  }
  j["coefficients"] = coefficients;
  nlohmann::ordered_json fixed = nlohmann::ordered_json::object();
  for (const auto& f : id.fixed) fixed[f.id] = {{"value", f.value}, {"unit", f.unit}};
  j["fixed"] = fixed;
  j["known"] = id.known;
  j["terms"] = r.names;
  j["residual_std"] = r.residual_std;
  j["dof"] = r.dof;
  j["chi2_per_dof"] = r.chi2_per_dof;
  j["condition_number"] = r.condition_number;
  nlohmann::ordered_json correlation = nlohmann::ordered_json::array();
  for (Eigen::Index a = 0; a < r.correlation.rows(); ++a) {
    nlohmann::ordered_json row = nlohmann::ordered_json::array();
    for (Eigen::Index b = 0; b < r.correlation.cols(); ++b) row.push_back(r.correlation(a, b));
    correlation.push_back(row);
  }
  j["correlation"] = correlation;
  nlohmann::ordered_json residuals = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < id.row_labels.size(); ++k)
    residuals[id.row_labels[k]] = r.residuals[static_cast<Eigen::Index>(k)];
  j["residuals"] = residuals;
  j["weighted"] = id.weighted;
  j["warnings"] = r.warnings;
  j["observability"] = observability_json(id.observability);
  j["output_unit"] =
      id.output_unit.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(id.output_unit);
  return j;
}

std::string identification_text(const Identification& id) {
  const FitResult& r = id.fit;
  std::string out;
  Table coefficients({"coefficient", "value", "std error", "unit"});
  for (std::size_t k = 0; k < r.names.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(k);
    coefficients.add_row(
        {r.names[k], number(r.value[i], 12), defined_number(r.std_error[i], 3), id.units[k]});
  }
  for (const auto& f : id.fixed) coefficients.add_row({f.id + " (fixed)", number(f.value, 12), "", f.unit});
  out += coefficients.render();
  if (!id.known.empty()) {
    std::string known;
    for (const auto& k : id.known) known += (known.empty() ? "" : ", ") + k;
    out += fmt::format("  known contributions subtracted from the output: {}\n", known);
  }
  out += "\n";

  Table stats({"fit", "value"});
  stats.add_row({id.weighted ? "residual std (normalised by sigma)"
                             : fmt::format("residual std [{}]", id.residual_unit),
                 defined_number(r.residual_std, 6)});
  stats.add_row({"degrees of freedom", std::to_string(r.dof)});
  stats.add_row({"chi2/dof", defined_number(r.chi2_per_dof, 6)});
  stats.add_row({"condition number (scaled design)", number(r.condition_number, 6)});
  out += stats.render() + "\n";
  out += observability_text(id.observability) + "\n";

  Table residuals({"run", fmt::format("residual [{}]", id.residual_unit)});
  for (std::size_t k = 0; k < id.row_labels.size(); ++k)
    residuals.add_row({id.row_labels[k], number(r.residuals[static_cast<Eigen::Index>(k)], 6)});
  out += residuals.render() + "\n";

  std::vector<std::string> header{"correlation"};
  header.insert(header.end(), r.names.begin(), r.names.end());
  Table correlation(header);
  for (Eigen::Index a = 0; a < r.correlation.rows(); ++a) {
    std::vector<std::string> row{r.names[static_cast<std::size_t>(a)]};
    for (Eigen::Index b = 0; b < r.correlation.cols(); ++b)
      row.push_back(fmt::format("{:.6f}", r.correlation(a, b)));
    correlation.add_row(row);
  }
  out += correlation.render();

  if (!r.warnings.empty()) {
    out += "\n  warnings:\n";
    for (const auto& w : r.warnings) out += "  - " + w + "\n";
  }
  return out;
}

}  // namespace ccal::render

namespace ccal::render {

std::string text(const verbs::Identification& id) { return identification_text(id); }
std::string json(const verbs::Identification& id) { return identification_json(id).dump(2); }

nlohmann::ordered_json dof_json(double dof) {
  return std::isfinite(dof) ? nlohmann::ordered_json(dof) : nlohmann::ordered_json(nullptr);
}

// The covariance of several instruments' coefficients: rows "<id> <term>", each matrix by rows, and the
// correlation of the LPU's (0 where a coefficient does not vary).
nlohmann::ordered_json instrument_part_json(const std::string& id, const nlohmann::ordered_json& whole) {
  nlohmann::ordered_json x;
  x["id"] = id;
  for (auto it = whole.begin(); it != whole.end(); ++it)
    if (it.key() != "command" && it.key() != "ccal_version" && it.key() != "config") x[it.key()] = *it;
  return x;
}

nlohmann::ordered_json covariance_json(const verbs::InstrumentCovariance& c) {
  auto rows = [](const Eigen::MatrixXd& m) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      std::vector<double> row(std::size_t(m.cols()));
      for (Eigen::Index j = 0; j < m.cols(); ++j) row[std::size_t(j)] = m(i, j);
      out.push_back(row);
    }
    return out;
  };
  Eigen::MatrixXd correlation = c.lpu;
  for (Eigen::Index i = 0; i < c.lpu.rows(); ++i)
    for (Eigen::Index j = 0; j < c.lpu.cols(); ++j) {
      const double scale = std::sqrt(c.lpu(i, i) * c.lpu(j, j));
      correlation(i, j) = scale > 0 ? c.lpu(i, j) / scale : 0.0;
    }
  nlohmann::ordered_json j;
  j["what"] = "the tolerances' covariance of every instrument's coefficients (the statements' units); the Type A "
              "parts, independent between instruments, are not in it";
  j["coefficients"] = c.names;
  j["units"] = c.units;
  j["lpu"] = rows(c.lpu);
  j["lpu_correlation"] = rows(correlation);
  if (c.trials > 0) {
    j["monte_carlo"] = rows(c.monte_carlo);
    j["monte_carlo_trials"] = c.trials;
    j["monte_carlo_seed"] = c.seed;
  }
  return j;
}

std::string covariance_text(const verbs::InstrumentCovariance& c) {
  std::string out = "  correlation of the instruments' coefficients through the machine's errors (LPU";
  out += c.trials > 0 ? fmt::format("; Monte Carlo of {} trials in brackets)\n", c.trials) : ")\n";
  std::vector<std::string> head{""};
  for (const std::string& n : c.names) head.push_back(n);
  Table t(head);
  for (Eigen::Index i = 0; i < c.lpu.rows(); ++i) {
    std::vector<std::string> row{c.names[std::size_t(i)]};
    for (Eigen::Index j = 0; j < c.lpu.cols(); ++j) {
      auto rho = [&](const Eigen::MatrixXd& m) {
        const double scale = std::sqrt(m(i, i) * m(j, j));
        return scale > 0 ? m(i, j) / scale : 0.0;
      };
      std::string cell = fmt::format("{:.3f}", rho(c.lpu));
      if (c.trials > 0) cell += fmt::format(" ({:.3f})", rho(c.monte_carlo));
      row.push_back(cell);
    }
    t.add_row(row);
  }
  return out + t.render();
}

}  // namespace ccal::render
