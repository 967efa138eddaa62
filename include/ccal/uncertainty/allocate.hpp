#pragma once
// Tolerance allocation (docs/model.md §10.3): the largest centrifuge tolerances for which every target on the
// expanded uncertainty of an identified coefficient holds — the inverse of the error budget.
//
// Model. The LPU of the budget (ccal/uncertainty/budget.hpp) with the AD sensitivities J (coefficients ×
// sources) at the configured errors, and the configured standard uncertainties u_s0. Every tolerance is
// scaled, u_s = λ_s u_s0 with λ_s > 0 (sources of one correlation group share one λ). With c_kg = Σ_{s∈g}
// J_ks u_s0 the 1-sigma effect of group g on coefficient k at the configured tolerances, the expanded
// uncertainty of k is
//     U_k(λ) = k_p · √(Σ_g λ_g² c_kg²),   k_p = Φ⁻¹((1 + p)/2)  (1.95996 for p = 95 %),
// and the allocation solves
//     minimise Σ_s cost_s / λ_s   subject to   U_k(λ) ≤ T_k for every row k,   λ_min,s ≤ λ_s ≤ λ_max,
// i.e. tightening a tolerance by a factor costs in proportion to the factor, weighted by Tolerance::cost.
// The rows are the targets and (allocate_tolerances, unless let_others_grow) every other free coefficient
// with T_k = U_k(1), its configured value: the same kind of row. λ_min,s = floor_s / bound_s (0 without a
// floor; a group takes the largest of its members').
//
// Solution. With x_g = λ_g² the problem is convex: Σ_g C_g x_g^(−1/2) (C_g = Σ_{s∈g} cost_s) is strictly
// convex and the constraints Σ_g a_kg x_g ≤ 1, a_kg = (k_p c_kg / T_k)², are linear. Its Lagrange dual has
// one multiplier μ_k ≥ 0 per target; for given μ the minimiser is explicit,
//     x_g(μ) = clamp((C_g / (2 b_g))^(2/3), λ_min,g², λ_max²),   b_g = Σ_k μ_k a_kg   (λ_max² when b_g = 0),
// and the dual function D(μ) = Σ_g (C_g x_g^(−1/2) + b_g x_g) − Σ_k μ_k is concave and continuously
// differentiable with ∂D/∂μ_k = Σ_g a_kg x_g − 1. solve_allocation maximises D over μ ≥ 0 by a projected
// Newton method (Bertsekas 1982) in multipliers scaled by their single-target values, with an exact line
// search (bisection on the directional derivative: D is far from quadratic near b = 0, where it grows like
// b^(1/3)); at the maximum the constraints with μ_k > 0 hold with equality to round-off and x(μ) is the
// unique primal optimum (strong duality: Slater's condition holds). On badly scaled problems where that
// iteration stalls, a barrier (interior-point) method on the primal in ln x, a geometric program, gives the
// starting multipliers instead (AllocationSolution::method). A source with no sensitivity to any target gets
// λ_max; a target met even with every tolerance at λ_max has μ_k = 0. Σ_g a_kg x_g is least at x = λ_min²:
// a row above 1 there cannot be met (AllocationSolution::unreachable, no allocation); a row at 1 there whose
// groups all have floors holds only with them at their floors, which are then fixed (the row drops out, the
// other rows keep the capacity 1 − Σ_{fixed g} a_kg x_g). Without floors every target can be met (λ → 0 is
// allowed), so a solution always exists for targets > 0.
//
// Partly correlated sources (AllocationProblem::correlation): U_k(λ) = k_p √(λᵀ Q_k λ) with Q_k = Gᵀ
// diag(E_k) R diag(E_k) G (E_k = J_k u_0 per source, G the group indicator). The cross terms make the rows
// nonlinear in x = λ², but each is a convex quadratic in λ (Q_k is positive semi-definite) and Σ_g C_g/λ_g is
// convex, so the problem is convex in λ: solved by the barrier method in λ
// (src/uncertainty/allocate_correlated.cpp, AllocationSolution::method "barrier (partly correlated sources)",
// duality gap below 1e-11 of the objective). A row is judged at the least scales as above: loosening a source
// whose error cancels another's is not sought to meet a target the floors otherwise prevent.
//
// The simple alternative is one common scale for every source, λ = min(λ_max, min_k T_k / U_k(1)).
//
// Verification: a Monte Carlo run (ccal/uncertainty/montecarlo.hpp, exact nonlinear pipeline) on the
// allocated tolerances; per target the half-width max(y_high − y, y − y_low) of the symmetric 100p % interval
// about the Monte Carlo mean y, against the target. Its sampling error is judged for a normal output: the
// relative standard error of an interval end is √(p'(1 − p'))/(k_p φ(k_p) √M), p' = (1 + p)/2 (1.36/√M for p
// = 95 %), that of a standard deviation about 1/√(2M). A half-width up to 3 such standard errors above the
// target passes "within sampling error"; one beyond fails.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/options.hpp"
#include "ccal/setup/coefficient_target.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/coverage.hpp"
#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal {

// The allocation as a mathematical problem, in SI.
struct AllocationProblem {
  Eigen::MatrixXd sensitivity;           // n_targets × n_sources: ∂K_k/∂e_s
  Eigen::VectorXd target;                // T_k, allowed expanded uncertainty per row, > 0
  Eigen::VectorXd standard_uncertainty;  // u_s0 per source, ≥ 0
  Eigen::VectorXd cost;                  // per source, > 0
  std::vector<std::string> group;        // per source; "" = independent (empty vector: all independent)
  double coverage_factor = kDefaultCoverageFactor;  // k_p
  double max_scale = 10.0;                          // λ_max > 0
  Eigen::VectorXd min_scale;  // λ_min,s per source, 0 ≤ λ_min,s ≤ λ_max (floor_s / bound_s); empty: all 0
  // R of the sources (sources × sources, input_correlation.hpp: 1 within a group, [[correlations]]' r);
  // empty: the groups alone. With it the rows are λᵀQ_kλ ≤ 1, solved by a barrier method in λ (see below).
  Eigen::MatrixXd correlation;
};

struct AllocationSolution {
  Eigen::VectorXd scale;       // λ_s per source (the same for the members of a group)
  Eigen::VectorXd multiplier;  // μ_k ≥ 0 per target, of the normalised constraint Σ_g a_kg x_g ≤ 1
  Eigen::VectorXd expanded;    // U_k(λ) at the allocated scales
  Eigen::VectorXd configured_expanded;  // U_k(1), at the configured tolerances
  std::vector<bool> active;             // U_k(λ) = T_k (relative slack in the variance ≤ 1e-9)
  double objective = 0;                 // Σ cost_s / λ_s
  double dual_gap = 0;                  // primal − dual objective at the end (≥ 0 up to round-off)
  double common_scale = 0;              // min(λ_max, min_k T_k / U_k(1))
  double common_objective = 0;          // Σ cost_s / common_scale
  Eigen::VectorXd common_expanded;      // U_k(common_scale)
  int iterations = 0;                   // Newton iterations on the dual
  // "dual Newton"; "barrier, then dual Newton" when the dual iteration alone failed; "barrier" when that
  // failed too (the barrier's feasible point, within 1e-10 of the optimum).
  std::string method;
  // The dual iteration reached a KKT residual (largest slack of a constraint with μ_k > 0, largest violation
  // of one with μ_k = 0) of 1e-12; or the barrier's duality gap is 1e-9 of the objective.
  bool converged = false;
  // Per row: the row cannot be met even with every source at its least scale (then nothing else is
  // filled: no allocation), and U_k with every source at its least scale (0 where no source has one).
  std::vector<bool> unreachable;
  Eigen::VectorXd least_expanded;
};

// Solves the allocation. Throws InputError for inconsistent sizes, a target ≤ 0 or non-finite, a cost ≤ 0, a
// negative standard uncertainty, a max_scale ≤ 0 or a min_scale outside [0, max_scale].
AllocationSolution solve_allocation(const AllocationProblem& problem);


// The factor by which the allocation may loosen (max_scale) or tighten (a target's fraction of its
// configured U) the tolerances, at most: a million-fold either way keeps every scaled bound, variance and
// cost/scale term of the solver and the verification finite and normal for the bounds of a real centrifuge
// (1e308 squared overflows, 1e-300 squared underflows to an allocated tolerance of 0).
inline constexpr double kAllocationScaleLimit = 1e6;
// The accepted max_scale, one home for the verb's option table and allocate_tolerances.
inline constexpr OptionRange kMaxScaleRange =
    OptionRange::between(1 / kAllocationScaleLimit, kAllocationScaleLimit).e_g("10");


// The options of an allocation (`ccal allocate`, Python allocate(), the report's allocation section), with
// their table (options_of): the one home of each option's name, default, range and help.
struct AllocateOptions {
  // Targets "<coefficient>=<U> [unit]", e.g. "K3=2e-3" (in the coefficient's display unit) or
  // "K3=2e-3 deg/s/g^3" (parse_allocation_target); at least one.
  std::vector<std::string> targets;
  double coverage_probability = kDefaultCoverageProbability;  // p of the expanded uncertainties (the targets)
  // Kinematics of the sensitivities and the verification; unset: the configuration's [identification] mode.
  std::optional<ModelMode> mode;
  double max_scale = 10.0;  // λ_max
  // false: every free coefficient without a target is held at its configured U (U_k(λ) ≤ U_k(1)); true:
  // only the targets constrain the allocation, and the others may grow (the result names each that does).
  bool let_others_grow = false;
  std::uint64_t verify_trials = 2000;  // M of the Monte Carlo verification; 0: none
  std::uint64_t seed = 1;
  int threads = 0;               // 0: the OpenMP default
  bool progress = false;         // progress bar of the verification (only on a terminal)
  ProgressCallback on_progress;  // of the verification; may throw Cancelled to stop (core/progress.hpp)
};

// The options' table (core/options.hpp); allocate_tolerances checks it.
OptionTable<AllocateOptions> options_of(std::type_identity<AllocateOptions>);

// One tolerance as configured (bound in SI, cost, group …) and as allocated.
struct AllocatedSource : Tolerance {
  double standard_uncertainty = 0;  // configured u_s0, SI
  double scale = 1;                 // λ_s
  double allocated_bound = 0;       // λ_s · bound
  double allocated_standard_uncertainty = 0;
  double least_scale = 0;  // floor / bound (0: no floor)
  bool at_floor = false;   // the allocation tightened it to its floor
  Eigen::VectorXd share;   // per target: (J_ks u_s)² / u_k² at the allocated tolerances (0…1)
};

enum class Verdict { not_checked, pass, pass_within_sampling, fail };
std::string_view verdict_name(Verdict v) noexcept;  // "not checked", "pass", "pass within sampling", "fail"

// One free coefficient.
struct AllocatedCoefficient {
  std::string id;
  std::string unit;          // display unit
  double display_scale = 1;  // SI → display
  bool has_target = false;
  double target = 0;               // T_k, SI (has_target)
  double configured_expanded = 0;  // k_p u_k at the configured tolerances
  double allocated_expanded = 0;   // k_p u_k at the allocated ones
  double common_expanded = 0;      // k_p u_k at the common scale
  double multiplier = 0;           // μ_k (has_target)
  double price = 0;                // ∂(objective)/∂(ln T_k) = −2 μ_k: what loosening the target saves
  bool active = false;             // the target holds with equality (has_target)
  bool held = false;               // no target, held at its configured U (AllocateOptions::let_others_grow)
  bool grew = false;               // no target, allocated U above the configured U (beyond 1e-9 of it)

  // Monte Carlo on the allocated tolerances (verification.trials > 0).
  double mc_mean = 0, mc_std = 0, mc_low = 0, mc_high = 0;
  double mc_half_width = 0;                // max(mc_high − mc_mean, mc_mean − mc_low)
  double lpu_std = 0;                      // u_k at the allocated tolerances
  // The cross terms' share of u_k² at the allocated tolerances (correlation groups and [[correlations]]:
  // correlation_variance of the budget at those tolerances; negative where they cancel): what the sources'
  // own shares leave of u_k² besides the rate noise.
  double correlation_share = 0;
  Verdict verdict = Verdict::not_checked;  // has_target only
};

struct AllocationVerification {
  std::uint64_t trials = 0;  // 0: not run
  std::uint64_t seed = 0;
  int threads = 0;
  double seconds = 0;
  double half_width_rel_error = 0;  // relative standard error of the half-width (normal output)
  double std_rel_error = 0;         // 1/√(2M)
  double allowance = 0;             // a half-width up to target·(1 + allowance) passes within sampling error
  bool passed = false;              // no target failed
  std::string notes;                // the engine's notes
};

struct AllocationDetail {
  ModelMode mode = ModelMode::exact;  // of the sensitivities and the verification
  double coverage_probability = kDefaultCoverageProbability;
  double coverage_factor = 0;
  double max_scale = 10;
  bool let_others_grow = false;
  std::vector<AllocatedSource>
      sources;  // sorted by λ, smallest (tightened most) first; catalogue order on ties
  std::vector<AllocatedCoefficient> coefficients;  // every free term, in identification order
  std::vector<std::size_t> targets;  // indices into coefficients of the targets, in the order given
  double objective = 0;              // Σ cost/λ
  double configured_objective = 0;   // Σ cost (λ = 1)
  double common_scale = 0;
  double common_objective = 0;
  int iterations = 0;
  std::string method;
  bool converged = false;
  double dual_gap = 0;
  AllocationVerification verification;
};

// Allocates the tolerances of a configuration (sensitivities in the options' mode at the configured errors) for
// the targets (parsed by parse_allocation_target, in the coefficients' display units), and verifies the result
// by Monte Carlo. Every free coefficient without a target is one more row, U_k(λ) ≤ U_k(1), unless
// options.let_others_grow; every tolerance with a floor has λ_s ≥ floor/bound. Throws OptionError naming the
// field for an option its table refuses, InputError for no tolerances, no or duplicate targets, a target on a
// coefficient that is not free, a target that cannot be met with every floored source at its floor (naming
// each such target, the least U the floors allow and the factor it is above the target), a floor above
// max_scale × bound, or an ill-posed identification.
AllocationDetail allocate_tolerances(const Config& config, const AllocateOptions& options);

}  // namespace ccal
