#pragma once
// The calibration statement of JCGM 100 (GUM) §7 and Annex G, the number a laboratory reports for each
// coefficient (docs/model.md §10.5):
//
//   corrected estimate  y = K̂ + b,  b the correction for known systematic effects (GUM §3.2.4)
//   combined            u_c² = u_A² + u_B²   (the fit's scatter and the centrifuge budget are independent)
//   Welch–Satterthwaite ν_eff = u_c⁴ / (u_A⁴/ν_A + u_B⁴/ν_B)   (G.2b; ν = ∞ for a part known exactly)
//   coverage factor     k = t_{(1+p)/2}(⌊ν_eff⌋), Student's t (G.3, G.4.1 note 1: ν_eff truncated to an
//                       integer), the normal quantile for ν_eff = ∞
//   expanded            U = k u_c,  interval [y − U, y + U].

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/coverage.hpp"
#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal {

inline constexpr double kInfiniteDof = std::numeric_limits<double>::infinity();

// One component of a combined standard uncertainty: u_i with its degrees of freedom ν_i (∞: known exactly).
struct UncertaintyPart {
  double u = 0;
  double dof = kInfiniteDof;
};

// ν_eff of u_c² = Σ u_i² (G.2b); ∞ when every part with u_i > 0 has ν_i = ∞. Throws std::invalid_argument
// for a negative u_i or a ν_i ≤ 0 of a part with u_i > 0.
double welch_satterthwaite(const std::vector<UncertaintyPart>& parts);

// What goes into one coefficient's statement, in one unit.
struct StatementInput {
  std::string coefficient;
  std::string unit;
  double estimate = 0;     // K̂ as identified
  double correction = 0;   // b, added to the estimate
  UncertaintyPart type_a;  // from the fit: its standard error and degrees of freedom
  UncertaintyPart type_b;  // from the centrifuge budget (tolerances): ν = ∞
};

// How a statement's interval was obtained: y ∓ U with k from Student's t at ν_eff (the LPU), the Monte
// Carlo's probabilistically symmetric interval (JCGM 101 §7.7.2) where the §8 validation refused the former,
// or y ∓ k u_c with a coverage factor k the user stated (e.g. k = 2 by contract), whatever the check finds.
enum class IntervalMethod { student_t, monte_carlo, coverage_factor };
inline constexpr std::string_view kIntervalMethodNames[] = {"student_t", "monte_carlo",
                                                            "coverage_factor"};  // enumeration order

// The coverage probability a stated k gives: 2Φ(k) − 1 for a normal quantity, and 2 F_t(k; ⌊ν_eff⌋) − 1 for
// Student's t at the quantity's ν_eff (the normal's for ν_eff = ∞).
struct StatedCoverage {
  double normal = 0;
  double student_t = 0;
};

struct CoefficientStatement {
  StatementInput input;
  double corrected = 0;        // K̂ + b
  double combined = 0;         // u_c
  double effective_dof = 0;    // ν_eff (∞ possible)
  double dof_for_k = 0;        // ⌊ν_eff⌋, or ∞
  double coverage_factor = 0;  // k; with the Monte Carlo's interval U/u_c
  double expanded = 0;         // U = k u_c; with the Monte Carlo's interval half its width
  double low = 0, high = 0;    // corrected ∓ U; with the Monte Carlo's interval its ends (not centred on y)
  // The interval excludes zero: the value differs from 0 at probability p. A term whose interval holds 0 is
  // not resolved by the test (|K̂ + b| ≤ U); a plan of more or higher g-levels lowers its U (`ccal design`).
  bool significant = false;
  IntervalMethod method = IntervalMethod::student_t;
  std::optional<StatedCoverage> stated;  // with a stated k (method coverage_factor): the p it gives
  // The Monte Carlo of the same quantity, when one was run: its statistics and the §8 validation of the
  // Student-t interval (lpu_std = u_c, lpu_expanded = the Student-t U, validation_delta = δ of u_c with two
  // significant digits, d_low, d_high, validated); monte_carlo_trials its M.
  std::optional<OutputSummary> monte_carlo;
  std::uint64_t monte_carlo_trials = 0;
};

// The statement of one coefficient for coverage probability p (throws as the functions above); with a stated
// coverage factor k, U = k u_c exactly and the probabilities k gives (method coverage_factor).
CoefficientStatement state_coefficient(const StatementInput& input, double p,
                                       std::optional<double> stated_factor = std::nullopt);

// JCGM 101 §8 for a statement: its Student-t interval y ∓ U against the Monte Carlo's probabilistically
// symmetric interval of the same quantity (M = trials values, summarised in `mc`), d_low = |y − U − y_low|,
// d_high = |y + U − y_high|, validated when both are at most δ, the numerical tolerance of u_c with two
// significant digits (§7.9.2). Where it is not validated, and the excess over δ is beyond three standard
// errors of the Monte Carlo's ends (validation_diagnosis: within them M, not the LPU, may explain it, and the
// Student-t interval stays), the statement takes the Monte Carlo's interval: method = monte_carlo, [low, high]
// its ends, U half its width, k = U/u_c, and significance from those ends. A statement of a stated k keeps its
// interval y ∓ k u_c: the check is only reported.
void check_by_monte_carlo(CoefficientStatement& statement, OutputSummary mc, std::uint64_t trials);

// The M at which the check of this statement would have a verdict, or 0 when it has one at `trials`: the
// Student-t interval validated, or refused by more than three standard errors of the Monte Carlo's ends. An
// unsettled verdict gives validation_diagnosis's trials_needed (the M at which the sampling error is a third of
// δ). A statement of a stated k needs none (its interval does not depend on the verdict).
std::uint64_t trials_to_settle(const CoefficientStatement& statement, const OutputSummary& mc,
                               std::uint64_t trials);

// The figures of a statement as a certificate writes them (JCGM 100 §7.2.6): U to `digits` significant digits
// (rounded to nearest; a U that rounds up to a power of ten keeps `digits` digits, 0.0996 → 0.10), the estimate
// to the same decimal place, and the interval's ends as the written estimate ∓ the written U, so that the
// certificate's "y ± U" and "[low, high]" agree to the last digit. A U that is 0 or not finite (or an estimate
// beyond 10¹⁵ of U's last digit) leaves no place: every figure then has 8 significant digits and `place` is
// unset.
struct RoundedFigures {
  std::optional<int> place;  // power of ten of the last digit written (−3: thousandths)
  std::string estimate, expanded, low, high;
};
RoundedFigures round_figures(double estimate, double expanded, int digits = 2);
// As above, for an interval not centred on the estimate (the Monte Carlo's): the place from its half-width
// U = (high − low)/2, and each end rounded to it on its own.
RoundedFigures round_interval(double estimate, double low, double high, int digits = 2);
// The statement's figures, by its method.
RoundedFigures round_figures(const CoefficientStatement& statement);

// What the configuration's known [errors] do to the identified coefficients when the model leaves them out:
// K̂(truth with the [errors], model without) − K̂(truth and model without errors), SI, per free term. Empty
// when the configuration compensates them ([identification] compensate = true) or has none. Its negative is
// the correction for known errors; it equals the shift `ccal simulate` shows for the same [errors].
Eigen::VectorXd known_error_shift(const Config& config, ModelMode mode);

}  // namespace ccal
