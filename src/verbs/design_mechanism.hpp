#pragma once
// What a designed plan does differently from the configured one, in words (docs/model.md §15.3): per counted
// coefficient, how much of its gain comes from a stronger signal and how much from errors cancelling, and its
// largest contributors before and after; and whether the runs at each g-level balance their input-axis
// headings.

#include <Eigen/Core>
#include <string>

#include "ccal/setup/config.hpp"
#include "ccal/verbs/design.hpp"

namespace ccal::verbs {

// U_k from the tolerances alone: k √(E R Eᵀ)_kk, the budget's independent components added in quadrature
// (model.md §10.1), SI.
Eigen::VectorXd tolerance_expanded(const ccal::BudgetDetail& budget);

// How far the input axis's inertial headings ψ_IA = θ1(0) + φ0 of the runs at each g-level fail to balance:
// the largest |Σ e^{iψ}| / count over the levels (0: opposite headings in pairs, 1: all alike).
double heading_imbalance(const Config& config);

// The mechanism lines of a design result (r.config, r.designed, r.targets, r.before, r.after and the
// tolerance-only U filled in), one paragraph per line.
std::string mechanism_text(const DesignResult& r);

}  // namespace ccal::verbs
