#pragma once
// The calibration statement (JCGM 100 §7, docs/model.md §10.5) as `ccal reduce --statement` and `ccal identify
// --statement --config CONFIG` give it: per identified coefficient the estimate, the correction for known errors, the
// Type A part from the fit with its degrees of freedom, the Type B part from the centrifuge budget of the
// configuration, u_c, ν_eff, k from Student's t, U and the interval; the combined covariance of the coefficients
// and, from it, the uncertainty of the modelled output of each run.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/verbs/option_rows.hpp"
#include "ccal/uncertainty/statement.hpp"
#include "ccal/verbs/identification.hpp"

namespace ccal::verbs {

struct StatementOptions {
  double coverage_probability = 0.95;  // p of the intervals, in (0, 1)
  std::optional<ModelMode> mode;       // of the budget; unset: the configuration's
  // M of the Monte Carlo check (src/verbs/statement_montecarlo.hpp); 0: none, the Student-t intervals stated.
  std::int64_t statement_trials = kDefaultStatementTrials;
  std::uint64_t seed = 1;  // of the Monte Carlo check
  int threads = 0;         // of the Monte Carlo check; 0: the OpenMP default
};

// The statement's options of a verb that states one (reduce, identify): its fields of the same names.
template <class VerbOptions>
StatementOptions statement_options(const VerbOptions& o, std::optional<ModelMode> mode) {
  StatementOptions so;
  so.coverage_probability = o.coverage_probability;
  so.mode = mode;
  so.statement_trials = o.statement_trials;
  so.seed = o.seed;
  so.threads = o.threads;
  return so;
}

// The options' table (core/options.hpp): names, ranges and help of the fields a front end sets.
OptionTable<StatementOptions> options_of(std::type_identity<StatementOptions>);

struct CalibrationStatement {
  std::string budget_config;  // the configuration whose tolerances give the Type B part
  std::string config_sha256;  // of its text (Config::text_sha256)
  // The instrument and the date as its [certificate] names them ("" without it): what `ccal history add`
  // records the statement under.
  std::string instrument, serial_number, date_of_calibration;
  ModelMode mode = ModelMode::exact;
  double coverage_probability = 0.95;
  bool compensated = false;  // the model computed the regressors with the known [errors]
  int known_errors = 0;      // non-zero [errors] parameters
  std::vector<CoefficientStatement> coefficients;  // in the fit's order, in the fit's units
  // Covariance of the corrected estimates, in the fit's units (row and column i: coefficients[i]): Type A the
  // fit's, Type B the tolerances' LPU, Σ_g e_g e_gᵀ over the correlation groups of §10.1 (a group's effects added
  // with their signs), and their sum, whose diagonal is u_c². The correlation is u(K_i, K_j) / (u_c,i u_c,j).
  Eigen::MatrixXd covariance_a, covariance_b, covariance, correlation;
  // The modelled output of each run, ŷ = hᵀ(K̂ + b) (h the run's regressors of the free terms, the fixed terms'
  // part added, the known columns left out), stated like a coefficient: u_A² = hᵀC_A h with ν_A, u_B² = hᵀC_B h;
  // `coefficient` names the run, `unit` is the output's. g_levels: each run's A [g] in the configuration's plan
  // (NaN for a row that names no run of the plan).
  std::vector<CoefficientStatement> outputs;
  std::vector<double> g_levels;
  // The Monte Carlo check, when one was run (statement_trials > 0 and the configuration has tolerances): its M
  // and seed; each coefficient and output holds its statistics and verdict.
  std::uint64_t monte_carlo_trials = 0;
  std::uint64_t monte_carlo_seed = 0;
};

// Combines an identification with the budget of `config`. Type A: the fit's standard errors with its
// degrees of freedom (∞ for a weighted fit, whose σ are taken as known); Type B: the configuration's
// tolerances (the drives' rate noise is left out, the fit's scatter already holds it); correction: minus
// the shift of the known [errors] when the model does not compensate them. Then, unless statement_trials is 0,
// the Monte Carlo check of every interval (JCGM 101 §8), the Monte Carlo's interval stated where it fails. Throws OptionError naming
// `field` (the option that asked for the statement: statement, observations) when a fitted term is not a free
// term of the configuration, the units cannot be converted or the fit has no degrees of freedom, and naming
// coverage_probability when p is not in (0, 1).
CalibrationStatement calibration_statement(const Config& config, const Identification& identification,
                                           const StatementOptions& options, std::string_view field);

}  // namespace ccal::verbs
