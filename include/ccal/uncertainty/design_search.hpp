#pragma once
// The search of `ccal design` (docs/model.md §15): a test plan of n runs chosen from cached candidate runs,
// scored by linear algebra on their rows, improved by exchange from several seeded starts and refined
// locally in the continuous variables.
//
// A run j of a plan contributes its row of the design H (the model's run means of the free terms' regressors),
// its leak row L_j (the tolerance groups' effects on its output mean, Σ_{s∈G} ∂ȳ_j/∂e_s u_s, output SI), the
// variance v_j of its mean from Type A sources (the drives' rate noise, the instrument's noise and quantum)
// and its duration. With H⁺ = (HᵀH)⁻¹Hᵀ, the coefficients' covariance is the budget's (model.md §10.1, §3.2)
//     Cov(K̂) = H⁺ (L Lᵀ + diag v) H⁺ᵀ,
// and a plan costs nothing to rescore once its rows are cached. The objectives (DesignObjective):
//     uncertainty  F = Σ_k w_k (k_c √Cov_kk / R_k)²           (R_k: a target, or the configured plan's U_k)
//     d_optimal    F = −ln det(Hᵀ W H),   W = diag(1/σ_j²) of the instrument's noise alone (I when none)
//     a_optimal    F = Σ_k w_k [(Hᵀ W H)⁻¹]_kk / R_k²
// A plan whose free terms the runs cannot separate is never accepted (PlanScore::well_posed).

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <limits>
#include <string_view>
#include <vector>

#include "ccal/model/plan.hpp"
#include "ccal/setup/design_space.hpp"
#include "ccal/uncertainty/coverage.hpp"

namespace ccal {

// One candidate run: the variables a design sets.
struct DesignRun {
  double g_level = 0;   // A [g]
  double duration = 0;  // T [s]
  double phase = 0;     // the designed phase [rad]: ψ = γ(T) (terminal) or φ0 = γ(0) (initial)
  double arm_azimuth = 0;  // θ1(0) [rad]
  DesignPhase phase_kind = DesignPhase::terminal;
  Mounting mounting = Mounting::ia_horizontal;
  PlatformMode platform = PlatformMode::counter_rotating;
};

// The cached rows of a set of runs (one row per run).
struct CandidateRows {
  Eigen::MatrixXd regressors;  // runs × free terms (SI: gⁿ, rad/s)
  Eigen::MatrixXd leaks;       // runs × tolerance groups: Σ_{s∈G} ∂ȳ/∂e_s u_s [output SI]
  Eigen::VectorXd scatter;     // variance of the run mean from the drives' rate noise [output SI²]
  Eigen::VectorXd noise;       // variance of the run mean from the instrument's noise and quantum [output SI²]
  Eigen::MatrixXd natural;     // runs × free terms: x_jᵈ, the regressor's size before averaging (model.md §14)
  Eigen::VectorXd duration;    // T [s]

  Eigen::Index size() const { return regressors.rows(); }
  // The rows of the given runs, in that order.
  CandidateRows select(const std::vector<int>& runs) const;
  // Appends the rows of another set.
  void append(const CandidateRows& more);
};

// Rows of arbitrary runs (for the local refinement); must be deterministic.
using RowFunction = std::function<CandidateRows(const std::vector<DesignRun>&)>;

struct DesignCriterion {
  DesignObjective objective = DesignObjective::uncertainty;
  // Per free term: its weight w_k in the objective (0: not counted) and its reference R_k (> 0 where w_k > 0).
  Eigen::VectorXd weight, reference;
  double coverage_factor = kDefaultCoverageFactor;  // k_c of U = k_c u (the budget's, coverage.hpp)
  // A plan is well posed when every free term's column keeps more than this fraction of its natural size
  // after the others are projected out (1e6·ε: a thousand times model.md §14's round-off limit), and no two
  // estimates are correlated beyond max_correlation (the fit refuses 0.99999).
  double roundoff_fraction = 1e6 * std::numeric_limits<double>::epsilon();
  double max_correlation = 0.9999;
};

struct PlanScore {
  bool well_posed = false;
  double objective = std::numeric_limits<double>::infinity();
  Eigen::MatrixXd covariance;  // of the free coefficients (SI): tolerances + Type A (uncertainty objective)
  Eigen::VectorXd expanded;    // k_c √Cov_kk
};

// Scores the plan made of these rows.
PlanScore score_plan(const CandidateRows& plan, const DesignCriterion& criterion);

// How far each continuous variable of a run may be moved by the local refinement, and its first step
// (0: the variable is fixed).
struct Refinement {
  double g_step = 0, g_low = 0, g_high = 0;                     // [g]
  double duration_step = 0, duration_low = 0, duration_high = 0;  // [s]
  double phase_step = 0;                                        // [rad], periodic
  double azimuth_step = 0;                                      // [rad], periodic
  int halvings = 12;   // steps halved this often before stopping
  int max_moves = 1000;  // improving moves at most
};

// A further instrument of a test of several, run with the same candidate runs (docs/model.md §15.4): its own
// rows of those candidates (its lever arm, mounting and terms), its criterion, and its rows of any run.
struct DesignInstrument {
  CandidateRows rows;
  DesignCriterion criterion;
  RowFunction evaluate;  // set when the problem's own is
};

struct DesignProblem {
  int runs = 0;                                            // n
  double total_time = std::numeric_limits<double>::infinity();  // Σ T_j ≤ total_time [s]
  std::vector<DesignRun> candidates;
  CandidateRows rows;  // of the candidates
  DesignCriterion criterion;
  RowFunction evaluate;  // empty: no local refinement
  Refinement refinement;
  std::vector<std::vector<int>> initial_plans;  // starts besides the random ones (e.g. the configured plan)
  // Every plan keeps at least this many distinct g-levels, two levels being one when they round to the same
  // multiple of g_resolution [g] (0: when equal).
  int min_g_levels = 1;
  double g_resolution = 0;
  // A test of several instruments: the rows, criterion and evaluate above are the first instrument's, these the
  // others'; a plan is acceptable when it is well posed for every one, and scored by joint_objective. Empty for
  // one instrument.
  std::vector<DesignInstrument> others;
};

// The objective of a plan for all the instruments of a problem from each one's (the first's, then the others'):
// for one instrument, its objective itself; for several, the largest of F_i / Σ_k w_ik (uncertainty, a_optimal:
// each instrument's objective relative to what it scores when every counted U_k equals its reference), or the
// sum of the F_i (d_optimal: −ln of the product of the information determinants). Infinite when one is.
double joint_objective(const DesignProblem& problem, const std::vector<double>& objectives);

struct DesignSearchOptions {
  int starts = 6;  // random starts (besides the initial plans)
  std::uint64_t seed = 1;
  int max_sweeps = 50;  // exchange sweeps per start
  // Called after each start ("search", starts done, starts) and each halving of the refinement's steps
  // ("refinement", halvings done, halvings + 1), from the calling thread; may throw to stop the search.
  std::function<void(std::string_view stage, int done, int total)> on_progress;
};

struct DesignSearchResult {
  std::vector<DesignRun> runs;  // the best plan (refined)
  CandidateRows rows;           // its rows
  PlanScore score;  // of the first instrument; for several, its objective is the joint one
  std::vector<PlanScore> scores;  // a test of several instruments: each one's own score of the plan; else empty
  std::vector<CandidateRows> other_rows;  // and the other instruments' rows of it (`rows` is the first's)
  double grid_objective = 0;    // of the best plan before the refinement
  int start = -1;               // which start gave it (initial plans first)
  std::vector<double> start_objectives;  // the best objective of every start (after exchange)
  long long evaluations = 0;    // plans scored
  long long row_evaluations = 0;  // runs evaluated by the refinement
};

// The best plan found. Deterministic for a seed (any thread count). Throws InputError when no start gives a
// well-posed plan that meets the time budget (the message says why).
DesignSearchResult search_design(const DesignProblem& problem, const DesignSearchOptions& options = {});

}  // namespace ccal
