#pragma once
// The error budget (docs/model.md §10): how much each centrifuge error source biases each identified
// coefficient, and in total.
//
// The identified coefficients are a function of the true errors e through the whole pipeline:
//     K̂(e) = H⁺ (ȳ(e) − s_ω⟨ω_IA⟩ − Σ_fixed K Z),   ȳ_j(e) = ⟨instrument output⟩ over run j (exact chain)
// with the design H, the known rate term and the fixed terms from the analyst's model (zero errors, or the
// measured ones when compensating), which do not depend on e. The sensitivity J = ∂K̂/∂e is computed by
// forward-mode automatic differentiation through kinematics, reduction and least squares (ccal::Dual, in
// passes of kDualWidth sources), at the configured error values.
//
// Totals follow the law of propagation of uncertainty (GUM §5): the standard uncertainty u_s of each source
// (bound and distribution), contribution c_ks = J_ks u_s, fully correlated sources of a group added with
// their signs, groups added in quadrature; the coefficient covariance is Σ_groups g gᵀ.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/options.hpp"
#include "ccal/reduction/observe.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/coverage.hpp"
#include "ccal/uncertainty/rate_noise.hpp"

namespace ccal {

// How ∂ȳ/∂e is obtained. Both are exact (they agree to round-off, tests/uncertainty/budget_test.cpp):
//   automatic:  forward-mode AD (ccal::Dual) through kinematics and reduction, in passes of kDualWidth
//   sources; linearised: at zero errors, the closed-form linearisation of the chain (exact_first_order,
//   itself checked
//               against AD) contracted with the output's gradient at each quadrature node, AD for the drive
//               errors only — an order of magnitude faster; used only where valid (exact mode, truth errors
//               all zero), otherwise automatic.
enum class DerivativeMethod { automatic, linearised };

// The options of a budget: of `ccal budget` (its table below: mode, coverage_probability, coverage_factor,
// derivatives) and of the engines that budget (the rest).
struct BudgetOptions {
  std::optional<ModelMode> mode;  // kinematics; unset: the configuration's [identification] mode
  // U = k u with k = Φ⁻¹((1 + p)/2) of the normal LPU total (coverage.hpp), or the stated k when given.
  // Unset: kDefaultCoverageProbability; optional so that a p given beside a stated k is refused.
  std::optional<double> coverage_probability;
  std::optional<double> coverage_factor;
  bool compare_with_paper = true;    // in exact mode, also compute the paper's sensitivities per source
  double disagreement_factor = 2.0;  // flag sources whose exact and paper effects differ by more than this
  ReductionOptions reduction;
  DerivativeMethod derivatives = DerivativeMethod::linearised;
};

// Sensitivities of the free coefficients (rows) to the given parameters (columns), SI per SI unit, split
// into the specific-force path (the instrument's rate gain set to zero) and the angular-rate path (the rest).
struct SensitivityTable {
  std::vector<std::string> coefficients;
  std::vector<int> parameters;
  Eigen::MatrixXd total, force_path, rate_path;
  DerivativeMethod method = DerivativeMethod::automatic;  // the one used
};

// ∂ȳ_j/∂e_s of every run's output mean (runs × parameters, output SI per SI unit of the error), split by
// path: the sensitivity table below is H⁺ times these rows, and each row depends on its own run only, so the
// design search (uncertainty/design_candidates.hpp) caches one per candidate run. `method` as for
// sensitivities (linearised only in exact mode at zero truth errors); with split = false the paths are not
// computed separately (force_path and rate_path empty).
struct OutputJacobian {
  Eigen::MatrixXd total, force_path, rate_path;
  DerivativeMethod method = DerivativeMethod::automatic;  // the one used
};
OutputJacobian output_jacobian(const Experiment& ex, const IdentificationSpec& spec,
                               const std::vector<int>& parameters, const Eigen::VectorXd& at, ModelMode mode,
                               const ReductionOptions& reduction = {},
                               DerivativeMethod method = DerivativeMethod::automatic, bool split = true);

// J at the truth errors `at` (indexed by the layout), with the model's errors `known`.
SensitivityTable sensitivities(const Experiment& ex, const IdentificationSpec& spec,
                               const std::vector<int>& parameters, const Eigen::VectorXd& at,
                               const Eigen::VectorXd& known, ModelMode mode,
                               const ReductionOptions& reduction = {},
                               DerivativeMethod method = DerivativeMethod::automatic);

// One tolerance's line of the budget: the tolerance as configured (its parameter, id, bound in SI,
// distribution, group, cost and the unit it was written in), then what it costs each coefficient.
struct SourceBudget : Tolerance {
  double standard_uncertainty = 0;  // u_s, SI
  Eigen::VectorXd sensitivity;      // ∂K/∂e per coefficient, SI per SI unit
  Eigen::VectorXd effect;           // J u_s per coefficient (signed), coefficient SI units
  Eigen::VectorXd effect_force;     // of which through the specific force
  Eigen::VectorXd effect_rate;      // and through the angular rate
  Eigen::VectorXd share;            // c_ks² / u_k² per coefficient (0…1)
  Eigen::VectorXd paper_effect;     // the paper-mode effect at the same u_s (empty if not computed)
  std::vector<bool> disagrees;      // exact vs paper beyond the disagreement factor, per coefficient
  bool paper_counterpart = true;    // false where the paper's rules have no such error (the drives' ripple)
  int rank = 0;                     // 1 = largest contributor (by the largest share over coefficients)
};

// A modelling choice rather than an uncertain quantity: the bias of the coefficients when the analyst's model
// leaves an effect out that the truth has (Earth rate sensed by the instrument; the Coriolis force).
struct CompensationChoice {
  std::string id;  // "earth_rate", "coriolis"
  std::string description;
  Eigen::VectorXd bias;        // K̂(effect not modelled) − K̂(modelled), SI, in the budget's mode
  Eigen::VectorXd paper_bias;  // the same in paper mode (empty unless compared)
};

// The compensation-choice rows (empty if the site's Earth rotation is off).
std::vector<CompensationChoice> compensation_choices(const Experiment& ex, const IdentificationSpec& spec,
                                                     const Eigen::VectorXd& at, const Eigen::VectorXd& known,
                                                     ModelMode mode, bool with_paper,
                                                     const ReductionOptions& reduction = {});

// The random rate noise of one drive (docs/model.md §3.2): a Type A component, independent from run to run,
// so its covariance is H⁺ diag(σ_j²) H⁺ᵀ rather than a signed effect.
struct RateNoiseBudget {
  std::string id;          // "main_rate_noise" or "platform_rate_noise"
  double density = 0;      // N [1/√Hz]
  Eigen::VectorXd run_sd;  // σ_j of each run's output mean [output SI]
  Eigen::VectorXd effect;  // u per coefficient (≥ 0, coefficient SI units)
  Eigen::VectorXd share;   // of the coefficient's variance (0…1)
  Eigen::MatrixXd covariance;
};

struct BudgetDetail {
  ModelMode mode = ModelMode::exact;
  DerivativeMethod derivatives = DerivativeMethod::automatic;  // used for the sensitivity table
  std::vector<std::string> coefficients;                       // free terms
  std::vector<std::string> units;                              // their display units (output unit per g^n)
  std::vector<double> display_scale;                           // SI → display unit factor per coefficient
  std::vector<SourceBudget> sources;                           // in tolerance order
  std::vector<RateNoiseBudget> rate_noise;                     // drives with rate noise (in the totals)
  Eigen::VectorXd standard_uncertainty;                        // u_k per coefficient (SI)
  Eigen::VectorXd expanded_uncertainty;                        // k u_k
  Coverage coverage;                                           // k and p of U
  Eigen::MatrixXd covariance;  // of the coefficients (SI)
  Eigen::MatrixXd correlation;
  std::vector<CompensationChoice> compensation;  // systematic, not in the totals
  // With [[correlations]]: the inputs' correlation matrix R (sources × sources, the groups' r = 1 in it) and
  // a factor F, R = F Fᵀ (setup/input_correlation.hpp); both empty when only groups correlate sources.
  Eigen::MatrixXd input_correlation, input_factor;
};

// The tolerances' effects as independent components (coefficients × m, SI): G with G Gᵀ = E R Eᵀ, the
// tolerances' part of the covariance (E: the sources' signed effects c u). Groups only: one column per group,
// its members' effects added with their signs; with [[correlations]]: E F.
Eigen::MatrixXd independent_effects(const BudgetDetail& budget);
// The same for any signed effects of the budget's sources (rows × sources, a column per source in its order),
// e.g. each run's output mean: E F, or per group the members' columns added.
Eigen::MatrixXd independent_effects(const BudgetDetail& budget, const Eigen::MatrixXd& effects);
// The part of u_k² that correlations between the sources make (coefficients, SI): u_k² from the tolerances
// less Σ_s (c_ks u_s)², negative when they cancel.
Eigen::VectorXd correlation_variance(const BudgetDetail& budget);

// The options' table (core/options.hpp): names, ranges and help of the fields a front end sets; compute_budget
// checks its options against it.
OptionTable<BudgetOptions> options_of(std::type_identity<BudgetOptions>);

// Throws OptionError naming the field for an option its table refuses, or a coverage factor with a coverage
// probability given (its default's value too).
BudgetDetail compute_budget(const Config& config, const BudgetOptions& options = {});

// The round-off floor of a contribution, relative to its coefficient's u_c: |u_i(y)| < kRoundOffFloor u_c is
// round-off of the derivatives, not a number of the budget (the tables show it as 0; JSON and CSV keep it
// and state the floor). A sensitivity is a sum, over every run's quadrature nodes and then through H⁺, of
// terms as large as the coefficient's largest paths (of order u_c and above), so its round-off is some
// 1e-16 of those, amplified by the fit's conditioning: the two derivative methods, which share nothing but
// H⁺, agree to 1.3e-15 u_c on every source of the bundled example, and a source that cannot act (dthx4,
// a tilt of the base plane about the instrument's IA) comes out of the linearised method at 1e-18 u_c
// rather than 0. 1e-12 stays three orders of magnitude above that and is far below any contribution that
// matters (a share of u_c² under 1e-24).
inline constexpr double kRoundOffFloor = 1e-12;

}  // namespace ccal
