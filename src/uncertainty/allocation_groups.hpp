#pragma once
// Sources merged into their correlation groups, as the allocation solves and reports them (private to the
// library): sources of one group share one draw, so their effects add before the group's cost is weighed.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace ccal {

// C_g = Σ cost, c_kg = Σ J_ks u_s0 over the sources s of group g; a source without a group is a group alone.
struct Groups {
  std::vector<int> of;  // group of each source
  Eigen::VectorXd cost;
  Eigen::MatrixXd effect;  // n_rows × n_groups
};

Groups merge_groups(const Eigen::MatrixXd& J, const Eigen::VectorXd& u0, const Eigen::VectorXd& cost,
                    const std::vector<std::string>& group);

struct AllocationProblem;
struct AllocationSolution;
// From each row's normalised value s_k at the allocated and at the configured scales: U_k = T_k √s_k of both,
// the rows that hold with equality (1 − s_k ≤ 1e-9) and the common scale min(λ_max, min_k T_k / U_k(1)) with
// its objective and U. Both solvers end with it.
void state_rows(const AllocationProblem& problem, const Eigen::VectorXd& allocated,
                const Eigen::VectorXd& configured, AllocationSolution& solution);

// The allocation with AllocationProblem::correlation (allocate.hpp): the barrier method in λ. The problem has
// passed solve_allocation's checks.
AllocationSolution solve_correlated_allocation(const AllocationProblem& problem);

}  // namespace ccal

namespace ccal {

// The allocation's normalised rows Σ_g a_kg x_g ≤ 1 against the bounds L_g ≤ x_g ≤ X_g of x_g = λ_g²
// (L_g = (largest least scale of the group's sources)², X_g = λ_max²). The least of Σ_g a_kg x_g over the
// box is at x = L: a row above 1 + 1e-12 there cannot be met (`unreachable`); a row within 1e-12 of 1 there
// whose groups all have L_g > 0 is met only with them at L, so they are pinned at L and the row drops out
// (its multiplier stays 0). The other rows keep their free groups: Σ_{g free} a_kg x_g ≤ capacity_k, with
// capacity_k = 1 − Σ_{g pinned} a_kg L_g > 0.
struct BoundedRows {
  Eigen::VectorXd L, X;           // per group
  std::vector<bool> pinned;       // per group: held at L_g
  std::vector<bool> dropped;      // per row: met with its groups pinned
  std::vector<bool> unreachable;  // per row: above 1 with every group at L_g
  Eigen::VectorXd at_floor;       // per row: Σ_g a_kg L_g
  Eigen::VectorXd capacity;       // per row
};
BoundedRows bound_rows(const Eigen::MatrixXd& a, const Groups& groups, const Eigen::VectorXd& min_scale,
                       double max_scale);

// The primal in y_g = ln x_g, a geometric program in convex form:
//     minimise Σ_g C_g e^(−y_g/2)   subject to   h_k(y) = ln Σ_g a_kg e^(y_g) ≤ 0 (k used),
//     ln L_g ≤ y_g ≤ ln X_g (the lower bound only where L_g > 0),
// by the barrier method (Boyd & Vandenberghe, "Convex Optimization", 2004, §11.3: centring by Newton's method
// with backtracking, t multiplied by 20 until the duality gap m/t is below 1e-10 of the objective). Slower
// than the dual iteration but robust from any start; its multipliers 1/(t (−h_k)) are those of h_k ≤ 0,
// equal to those of Σ_g a_kg x_g ≤ 1 where the constraint is active.
struct BarrierResult {
  Eigen::VectorXd y, mu;  // mu per row of a (0 for rows not used)
  double gap = 0;         // m/t at the end, relative to the objective
};

BarrierResult solve_barrier(const Eigen::MatrixXd& a, const Eigen::VectorXd& C, const Eigen::VectorXd& L,
                            const Eigen::VectorXd& X, const std::vector<bool>& use);

}  // namespace ccal
