#pragma once
// The Type A part of a calibration statement (docs/model.md §10.5): from the noise model of the instrument and
// the drives when the configuration states one, with the fit's residuals tested against what that noise and
// the Type B inputs' between-run effects predict; else from the fit's scatter.

#include <Eigen/Core>
#include <vector>

#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/verbs/identification.hpp"
#include "ccal/verbs/statement.hpp"

namespace ccal::verbs {

struct TypeAParts {
  TypeAEvaluation evaluation;
  // The coefficients' Type A covariance in two parts, in the fit's units: the noise model's (ν = ∞; a weighted
  // fit's own covariance, its σ taken as known) and the part estimated from the residuals (ν = `dof`): the
  // fit's scatter when there is no noise model, the charged excess when the residuals exceed it.
  Eigen::MatrixXd known, estimated;
  double dof = kInfiniteDof;
};

// budget: the statement's (measured inputs credited), for the drives' rate noise per run and the Type B
// inputs' standard uncertainties and groups; durations: T per row of the identification (empty: the plan's).
TypeAParts evaluate_type_a(const Config& config, const Identification& id, const ccal::BudgetDetail& budget,
                           const std::vector<double>& durations);

// σ_j of the mean of each plan run rows[j] (in units of unit_si SI): the instrument's white output noise and
// pulse quantum over the run's duration (durations[j], or the plan's when durations does not match rows) and
// each drive's rate noise of the budget.
Eigen::VectorXd run_noise(const Config& config, const ccal::BudgetDetail& budget, const std::vector<std::size_t>& rows,
                          const std::vector<double>& durations, double unit_si);
// The budget's Type B inputs' effects on the mean of each plan run rows[j] as independent components (rows ×
// components, in units of unit_si SI), at the configured errors.
Eigen::MatrixXd run_effects(const Config& config, const ccal::BudgetDetail& budget, const std::vector<std::size_t>& rows,
                            double unit_si);

// ν of the Type A part u_A² = a + e (a known, ν = ∞; e estimated with ν = dof), by Welch–Satterthwaite.
double type_a_dof(double known_variance, double estimated_variance, double dof);

}  // namespace ccal::verbs
