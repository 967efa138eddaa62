#include "ccal/verbs/statement.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"
#include "ccal/verbs/budget.hpp"

namespace ccal::verbs {
namespace {

// u_B of each coefficient from the tolerances alone: effects of a group added with their signs, groups in
// quadrature (docs/model.md §10.1), without the drives' rate noise.
Eigen::VectorXd type_b(const ccal::BudgetResult& b) {
  const CorrelationGroups groups = correlation_groups(b.sources);
  const auto nk = Eigen::Index(b.coefficients.size());
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(nk, groups.count);
  for (std::size_t s = 0; s < b.sources.size(); ++s) g.col(groups.of[s]) += b.sources[s].effect;
  return g.rowwise().norm();
}

// Factor from the budget's display unit of a coefficient to the fit's unit for it.
double unit_factor(const std::string& from, const std::string& to, const std::string& term,
                   std::string_view field) {
  if (from == to) return 1;
  try {
    const Quantity a = parse_unit(from), b = parse_unit(to);
    if (a.dim == b.dim) return a.value_si / b.value_si;
  } catch (const UnitError&) {
  }
  throw OptionError(std::string(field), "",
                    fmt::format("{} is in '{}' in the fit and in '{}' in the configuration's budget; "
                                "accepted: a fit whose output unit is the configuration's output_unit",
                                term, to, from));
}

constexpr OptionSpec<StatementOptions> kRows[] = {
    rows::coverage_probability(&StatementOptions::coverage_probability,
                               "Coverage probability p of the statement's intervals, in (0, 1)"),
    rows::mode<&StatementOptions::mode>("Kinematics of the statement's budget: exact or paper; default: the "
                                        "configuration's [identification] mode"),
};

}  // namespace

OptionTable<StatementOptions> options_of(std::type_identity<StatementOptions>) { return kRows; }

CalibrationStatement calibration_statement(const Config& config, const Identification& id,
                                           const StatementOptions& o, std::string_view field) {
  check_options(o, option_table<StatementOptions>());
  const FitResult& fit = id.fit;
  if (!id.weighted && fit.dof <= 0)
    throw OptionError(std::string(field), "",
                      fmt::format("the fit has no degrees of freedom ({} observations for {} free terms), so "
                                  "its Type A uncertainty is undefined; accepted: at least one observation more "
                                  "than free terms",
                                  fit.residuals.size(), fit.names.size()));
  BudgetOptions bo;
  bo.mode = o.mode;
  bo.compare_with_paper = false;
  const BudgetResult budget = verbs::budget(config, bo);
  const ccal::BudgetResult& b = budget.budget;
  const Eigen::VectorXd u_b = type_b(b);

  CalibrationStatement st;
  st.budget_config = config.source;
  st.mode = b.mode;
  st.coverage_probability = o.coverage_probability;
  st.compensated = config.identification.compensate;
  st.known_errors = int((config.centrifuge.errors.array() != 0.0).count());
  // The budget's sensitivities hold for its own free terms: the fit must free the same ones.
  std::vector<std::string> fitted = fit.names, budgeted = b.coefficients;
  std::sort(fitted.begin(), fitted.end());
  std::sort(budgeted.begin(), budgeted.end());
  if (fitted != budgeted)
    throw OptionError(std::string(field), "",
                      fmt::format("the fit's free terms ({}) are not those of {} ({}); accepted: a "
                                  "configuration whose [identification] terms are the fit's",
                                  fmt::join(fit.names, ", "), config.source, fmt::join(b.coefficients, ", ")));
  for (std::size_t k = 0; k < fit.names.size(); ++k) {
    const auto found = std::find(b.coefficients.begin(), b.coefficients.end(), fit.names[k]);
    const auto j = std::size_t(found - b.coefficients.begin());
    const auto i = Eigen::Index(k);
    // SI → the budget's display unit → the fit's unit.
    const double to_fit = b.display_scale[j] * unit_factor(b.units[j], id.units[k], fit.names[k], field);
    StatementInput in;
    in.coefficient = fit.names[k];
    in.unit = id.units[k];
    in.estimate = fit.value[i];
    in.correction = budget.known_error_bias.size() ? -budget.known_error_bias[Eigen::Index(j)] * to_fit : 0.0;
    in.type_a = {fit.std_error[i], id.weighted ? kInfiniteDof : double(fit.dof)};
    in.type_b = {u_b[Eigen::Index(j)] * to_fit, kInfiniteDof};
    st.coefficients.push_back(state_coefficient(in, o.coverage_probability));
  }
  return st;
}

}  // namespace ccal::verbs
