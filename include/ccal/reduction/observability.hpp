#pragma once
// Observability of each free term of an identification (docs/model.md §14): how much the run means change per
// unit of the term's coefficient, set against what the data can resolve, and whether the plan sees the term
// at all.
//
// The scaled condition number of fit.hpp cannot tell: column scaling divides each column by its own norm, so
// a column that is pure round-off (⟨a_i³⟩ over whole revolutions of a counter-rotating platform is 1e-16 of
// a_i³) is scaled up to a unit vector of random digits and the design looks excellent. The measure here keeps
// the absolute size of each column:
//   sensitivity      s_k = ‖P⊥ h_k‖, h_k the term's column of run means with the other free columns projected
//                    out: the change of the run means [output SI, root-sum-square over runs] per unit change
//                    of the coefficient [output SI / unit of the regressor] that no other term can absorb;
//   natural size     n_k = ‖(x_j^d)_j‖, x_j the magnitude of the input in run j [g] and d the term's degree:
//   the
//                    size the regressor's integrand has before averaging;
//   resolution       σ_j² = (N/√T_j)² + (q/(T_j√12))² + (c·ε·m_j)² + σ_extra,j²: white noise of density N,
//                    a quantum q of the integrated output (uniform error of width q/T), the floating-point
//                    resolution of a mean computed from values of magnitude m_j, and any other scatter;
//   standard error   u_k = 1/‖P⊥ (h_k/σ)‖ (projection in the σ-weighted metric) = √[(HᵀΣ⁻¹H)⁻¹]_kk;
//   detectable       δK_k = k·u_k, the smallest coefficient change the plan could detect (k = 3 by default).
// Status: unobservable when s_k ≤ ρ·n_k (the column is round-off of its own integrand; the fit would return
// digits of noise), weak when a reference value is given and |reference| < δK_k (the plan cannot detect a
// coefficient of that size), ok otherwise.

#include <Eigen/Core>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/model/instrument.hpp"
#include "ccal/model/plan.hpp"
#include "ccal/reduction/observe.hpp"

namespace ccal {

// What is known of one run besides its regressors. Zeros mean "unknown".
struct RunResolutionInfo {
  double duration = 0;          // T [s]; 0: no noise or quantum term for this run
  double input_scale = 0;       // magnitude of the specific force during the run [g]; 0: inferred from H
  double rate_scale = 0;        // magnitude of the angular rate the rate regressor is built from [rad/s]
  double output_magnitude = 0;  // magnitude of the values the run mean was computed from [output SI]
  double extra_sigma = 0;  // further standard deviation of the run mean [output SI], e.g. a residual scatter
  bool counter_rotating = false;
  double platform_turns = 0;  // ΩT/2π: platform revolutions relative to the arm (counter-rotating runs)
};

struct ObservabilityProblem {
  std::vector<std::string> terms;  // free terms, one per column of H (term ids, instrument.hpp)
  Eigen::MatrixXd H;               // runs × free terms: run means of the regressors (SI: gⁿ, rad/s)
  // Columns of terms held fixed (runs × others), used only to infer the input's magnitude when it is not
  // given: the largest |⟨regressor⟩|^(1/degree) over all columns of degree ≥ 1.
  std::vector<std::string> other_terms;
  Eigen::MatrixXd others;
  std::vector<RunResolutionInfo> runs;  // one per row of H (empty: nothing known)
  double noise_density = 0;             // N [output SI/√Hz]
  double quantum = 0;                   // q [output SI·s]
  // Per free term: a coefficient value to compare the detection limit with (the fitted or configured value,
  // SI); empty or 0: no comparison, the term is then ok or unobservable only.
  Eigen::VectorXd reference;
};

struct ObservabilityOptions {
  double detection_factor = 3;  // k of δK = k·u
  double rounding_ulps = 4;     // c: floating-point resolution of a run mean, c·ε·m_j
  // ρ: a column whose projected norm is at most this fraction of its natural size is round-off. A mean of
  // values of size x^d carries a round-off of a few ε·x^d per accumulated node; 1e3·ε allows for thousands of
  // nodes and is still ten orders of magnitude below the paper plan's K3 (≈ 8e-5).
  double roundoff_fraction = 1e3 * std::numeric_limits<double>::epsilon();
  // A counter-rotating run lasts whole revolutions when |ΩT/2π − round(ΩT/2π)| is at most this.
  double whole_turn_tolerance = 1e-6;
};

enum class TermStatus { ok, weak, unobservable };
std::string_view term_status_name(TermStatus status) noexcept;

struct TermObservability {
  std::string term;
  int degree = 0;             // degree in the inputs (K3: 3; K_pp: 2; K_w: rate)
  double column_norm = 0;     // ‖h_k‖
  double natural_norm = 0;    // n_k
  double sensitivity = 0;     // s_k = ‖P⊥ h_k‖
  double fraction = 0;        // s_k / n_k: the part of the term's natural signal only it explains
  double standard_error = 0;  // u_k [coefficient SI]
  double min_detectable = 0;  // δK_k = k·u_k [coefficient SI]
  TermStatus status = TermStatus::ok;
  std::vector<std::string> aliased_with;  // other free terms that absorb the column, if that is the reason
  std::string reason;  // why the term is weak or unobservable (one clause, no final period); "" when ok
  std::string fix;     // what would make it observable; "" when ok
};

struct ObservabilityResult {
  std::vector<TermObservability> terms;  // in the order of ObservabilityProblem::terms
  Eigen::VectorXd resolution;            // σ_j per run [output SI]
  double detection_factor = 3;
  bool whole_revolutions = false;  // every run is counter-rotating and lasts whole revolutions

  // The first term with the given status, or nullptr.
  const TermObservability* first(TermStatus status) const;
};

// Degree of a term in the inputs: n for K_n, 2 for K_oq and the products, 1 for K_p and K_o, 1 for K_w (in
// the angular rate).
int term_degree(const TermSpec& term);

// The measure of every free term. Throws std::invalid_argument for inconsistent sizes, unknown term ids or
// negative/non-finite inputs.
ObservabilityResult assess_observability(const ObservabilityProblem& problem,
                                         const ObservabilityOptions& options = {});

// The problem of a plan's observations, all SI: the free and fixed columns of `obs` under `spec`, and per run
// (`runs` as reduced, `rates` their Ω [rad/s]) its duration, platform turns ΩT/2π, input magnitude √(A² + 1)
// g, rate magnitude Ω and a bound on the instrument's output, |ȳ| + |s_ω|Ω + Σ|K|·xᵈ; the instrument's noise
// density and quantum. No reference values.
ObservabilityProblem observability_problem(const Observations<double>& obs, const IdentificationSpec& spec,
                                           const InstrumentModel& instrument, const std::vector<Run>& runs,
                                           const std::vector<double>& rates);

// One line for a refusal: "the test plan cannot observe K3: <reason>; <fix>".
std::string unobservable_message(const TermObservability& term);

}  // namespace ccal
