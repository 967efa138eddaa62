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
#include "ccal/io/observation_csv.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/option_rows.hpp"
#include "ccal/uncertainty/statement.hpp"
#include "ccal/verbs/identification.hpp"

namespace ccal::verbs {

struct StatementOptions {
  std::optional<double> coverage_probability;  // p of the intervals; unset: kDefaultCoverageProbability
  // A stated k (e.g. 2 by contract): U = k u_c for every quantity, p that of a normal quantity; exclusive with a
  // coverage_probability given.
  std::optional<double> coverage_factor;
  std::optional<ModelMode> mode;  // of the budget; unset: the configuration's
  // M of the Monte Carlo check (src/verbs/statement_montecarlo.hpp); 0: none, the Student-t intervals stated.
  // Unset: kDefaultStatementTrials. Optional, as the seed and threads are, so that one given at its default
  // value without a statement asked for is refused as any other value is (refuse_statement_options_unasked).
  std::optional<std::int64_t> statement_trials;
  std::optional<std::uint64_t> seed;  // of the Monte Carlo check; unset: kDefaultSeed
  std::optional<int> threads;         // of the Monte Carlo check; unset or 0: the OpenMP default

  std::int64_t trials() const { return statement_trials.value_or(kDefaultStatementTrials); }
};

// The statement's rows, the one home of its options: a verb that states one (reduce, identify) holds a
// StatementOptions and lifts these rows into its own table (core/options.hpp lifted_rows), in this order.
inline constexpr OptionSpec<StatementOptions> kStatementRows[] = {
    rows::coverage_probability(&StatementOptions::coverage_probability,
                               "Coverage probability p of the statement's intervals, in {range}"),
    rows::coverage_factor(&StatementOptions::coverage_factor),
    rows::mode<&StatementOptions::mode>("Kinematics of the statement's budget: exact or paper; default: the "
                                        "configuration's [identification] mode"),
    rows::statement_trials(&StatementOptions::statement_trials),
    rows::seed(&StatementOptions::seed, "Seed of the statement's Monte Carlo check"),
    rows::threads(&StatementOptions::threads),
};
// The position of the mode's row: a verb whose own mode is the statement's (reduce) lifts the rows around it.
inline constexpr std::size_t kStatementModeRow = 2;

// The options' table (core/options.hpp): names, ranges and help of the fields a front end sets.
OptionTable<StatementOptions> options_of(std::type_identity<StatementOptions>);

// One input of the statement's Type B part, as its table of inputs (the GUM table) lists it.
struct StatementSource {
  std::string id;                   // the [tolerances] id
  std::string unit;                 // the unit it is shown in: as its tolerance was written, else its own
  double unit_si = 1;               // SI size of one `unit`
  double standard_uncertainty = 0;  // u of the input, SI
  bool measured = false;            // measured in this test (its tolerance replaced), else from its tolerance
  std::string basis;                // how u was obtained, in words
  std::vector<double> effect;       // u_i(K) = c u per coefficient, signed, in the fit's units
  std::string group;                // its tolerance's correlation group; "": none (a measured input has none)
};

// How the Type A part was evaluated, and the residuals tested against it (docs/model.md §10.5).
struct TypeAEvaluation {
  // From the noise model: each run mean's σ_j from the instrument's noise density and quantum and the drives'
  // rate noise, propagated through the fit (ν = ∞). Else (no noise stated, or runs the plan does not name):
  // the fit's scatter, ν = n − p.
  bool from_noise_model = false;
  std::vector<double> run_sd;  // σ_j per row, in the residuals' unit (noise model only)
  // The residuals against that prediction: S = Σ r_j²/σ_j², its expectation and p-value under the noise and
  // the Type B inputs' between-run effects (a scaled χ² of the same mean and variance).
  double statistic = 0, expected = 0, p_value = 1;
  int dof = 0;  // n − p
  // S beyond the prediction at kResidualCheckLevel: the excess τ² = (S − E)/tr(W M) per run mean (residuals'
  // unit²), charged as a Type A part with ν = n − p.
  bool excess = false;
  double excess_variance = 0;
};
// The p-value below which the residuals' excess over the prediction is charged.
inline constexpr double kResidualCheckLevel = 0.01;

struct CalibrationStatement {
  std::string budget_config;  // the configuration whose tolerances give the Type B part
  std::string config_sha256;  // of its text (Config::text_sha256)
  std::string setup_sha256;   // of its machine's and lab's tables (Config::setup_sha256): one set-up, shared errors
  // The instrument and the date as its [certificate] names them ("" without it): what `ccal history add`
  // records the statement under.
  std::string instrument, serial_number, date_of_calibration;
  // The certificate's number, revision and the number of the certificate it replaces ("" when not set): what
  // ties an amended certificate to the one it supersedes.
  std::string certificate_number, revision, replaces;
  ModelMode mode = ModelMode::exact;
  double coverage_probability = kDefaultCoverageProbability;  // p; with a stated k, 2Φ(k) − 1
  std::optional<double> coverage_factor;  // k when the user stated it (a contract), else unset
  bool compensated = false;  // the model computed the regressors with the known [errors]
  int known_errors = 0;      // non-zero [errors] parameters
  std::vector<CoefficientStatement> coefficients;  // in the fit's order, in the fit's units
  std::vector<StatementSource> inputs;             // the Type B part's inputs, in tolerance order
  // The [[correlations]] pairs among the inputs charged at their tolerance (a measured input leaves its
  // pairs).
  std::vector<Correlation> input_correlations;
  TypeAEvaluation type_a;
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
  // M is the requested (statement_trials) or more: the check goes on while a verdict is within the sampling
  // error (settled false: still so at the cap, kStatementTrialsCap × the requested M).
  std::uint64_t monte_carlo_trials = 0;
  std::uint64_t monte_carlo_requested_trials = 0;
  bool monte_carlo_settled = true;
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
// `measured`: inputs the test measured (intake/measured_inputs.hpp), charged at their measurement's uncertainty in
// place of their tolerances (a measured input leaves its group and its [[correlations]]); `durations`: T of
// each row of the identification [s] (empty: its run's in the plan).
CalibrationStatement calibration_statement(const Config& config, const Identification& identification,
                                           const StatementOptions& options, std::string_view field,
                                           const std::vector<MeasuredInput>& measured = {},
                                           const std::vector<double>& durations = {});

// A statement's option given without the statement asked for (`field`, e.g. statement) would be passed over in
// silence: OptionError naming it, unless it is at its default. `with_mode`: the mode is the statement's alone
// (identify), not also the verb's own (reduce).
void refuse_statement_options_unasked(const StatementOptions& options, std::string_view field, bool with_mode);

// What an observations file's header says of its test (`ccal reduce` writes it): the inputs the logs measured
// and, per row of the identification, the logged span (empty unless the file records every row's), for
// calibration_statement.
struct TestEvidence {
  std::vector<MeasuredInput> measured;
  std::vector<double> durations;
};
TestEvidence test_evidence(const std::optional<ObservationsHeader>& header, const Identification& identification);

// The statement a test of the configuration's plan is expected to give, by the very method of
// calibration_statement (its Type A part, ν, k and interval): the plan simulated without noise (the machine with
// the [errors]), the inputs its declared encoders will measure credited (intake/measured_inputs.hpp,
// expected_measured_inputs), no Monte Carlo check. `ccal design`'s "Expected if run as written". Throws as
// calibration_statement (a plan of no more runs than free terms has no Type A evaluation).
CalibrationStatement expected_statement(const Config& config, double coverage_probability,
                                        std::optional<ModelMode> mode = std::nullopt);

// The configuration with the measured inputs' tolerances replaced by their measurements' (normal, u as bound,
// no group, no correlation pairs): what the statement's Type B part and its Monte Carlo draw.
Config with_measured_inputs(const Config& config, const std::vector<MeasuredInput>& measured);

}  // namespace ccal::verbs
