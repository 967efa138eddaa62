#pragma once
// First-order (linear in the errors) closed forms of the sensed input, to set beside the exact chain.
//
// exact_first_order: the linearisation of the exact chain at zero errors, derived by small-twist perturbation
//   (docs/model.md §5.2). An error rotation δθ about local axis n of link k turns everything downstream about
//   the link's pivot o_k by Θ = R_P n δθ (R_P: the link's parent frame); a translation moves it by D = R_P n
//   δ. With ℓ = r − o_k (r: instrument origin) and the parent frame turning at ω_P:
//     Θ̇ = ω_P × Θ + R_P n δθ̇,   Θ̈ = ω̇_P × Θ + ω_P × Θ̇ + ω_P × (R_P n δθ̇) + R_P n δθ̈
//     δr̈ = Θ̈ × ℓ + 2 Θ̇ × ℓ̇ + Θ × ℓ̈,   δṙ = Θ̇ × ℓ + Θ × ℓ̇
//     δf₅ = R₅ᵀ (δr̈ + 2 ω_ie × δṙ − Θ × f) / g,   δω₅ = R₅ᵀ (R_P n δθ̇ + Θ × (ω₅ − ω_P) − Θ × ω₅ⁱ)
//   The drive errors Δω, ΔΩ change the joint rates and, through them, the joint angles at time t.
//
// paper_first_order: the paper's Eq.(9)/(10)/(14) form as reconstructed in model.md §2.2 (the "frozen-γ"
//   treatment: dynamic errors as their value at the current angle, constant Coriolis term, constant Δx5 term,
//   levelling averaged away), with the lever-arm terms (L+l)θ and lΔθy4 as an option.

#include <Eigen/Core>

#include "ccal/model/centrifuge.hpp"
#include "ccal/model/kinematics.hpp"
#include "ccal/model/site.hpp"

namespace ccal {

// Row order of a sensitivity matrix: specific force on IA, PA, OA [g per unit of the parameter], then
// inertial angular rate about IA, PA, OA [rad/s per unit].
using SensitivityMatrix = Eigen::Matrix<double, 6, Eigen::Dynamic>;

struct FirstOrderResult {
  Eigen::Matrix<double, 6, 1> nominal;  // the error-free exact values (same row order)
  SensitivityMatrix sensitivity;        // one column per parameter of the layout, SI units of the parameter
};

// Linearisation of the exact chain about zero errors at time t of a run (the run's joint motion must be the
// error-free one: errors enter only through `sensitivity`).
FirstOrderResult exact_first_order(const Geometry& geometry, const ErrorLayout& layout, const Site& site,
                                   const RunMotion<double>& nominal_run, PlatformMode mode, double t);

struct PaperFormOptions {
  bool lever_arms = true;  // include (L+l)θx, (L+l)θy and lΔθy4 (model.md A9); the paper omits them
  bool constant_coriolis = true;  // −2ω_e R Ω sin φ / g as a constant (the paper) instead of × cos γ
};

// The paper's first-order IA input and IA rate (model.md §2.2, §2.4), per parameter, at joint state j with
// centripetal amplitude A = R0 θ̇1² / g. Rows 0 (a_i, g) and 3 (ω_IA, rad/s) are filled; the others are zero.
FirstOrderResult paper_first_order(const Geometry& geometry, const ErrorLayout& layout, const Site& site,
                                   const JointState<double>& j, const PaperFormOptions& options = {});

}  // namespace ccal
