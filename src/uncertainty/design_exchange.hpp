#pragma once
// The exchange step's scorer (private to the design search): the uncertainty objective of a plan in which one
// run is replaced by each candidate in turn, by rank-one updates of the other runs' sums instead of a new fit
// per candidate (docs/model.md §15). With H the plan's regressors, L its leak rows, V the run means'
// variances and N = HᵀH,
//     Cov = N⁻¹ (Hᵀ L Lᵀ H + Hᵀ V H) N⁻¹,
// and a candidate c (row h, leaks ℓ, variance v) changes the sums by
//     N = N₀ + h hᵀ,   Hᵀ L Lᵀ H = B₀B₀ᵀ + u hᵀ + h uᵀ + (ℓ·ℓ) h hᵀ,   Hᵀ V H = S₀ + v h hᵀ,   u = B₀ ℓ,
// with B₀ = H₀ᵀ L₀ of the other runs: O(p·G) per candidate (p free terms, G tolerance groups) where a new fit
// costs O(n·p·G). The well-posedness tests are those of the full scorer (design_search.cpp), on the same
// column-scaled normal matrix.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <vector>

#include "ccal/uncertainty/design_search.hpp"

namespace ccal::design_detail {

class ExchangeScorer {
 public:
  // `leak_norms`: ℓ·ℓ of every candidate's leak row (computed once per search).
  ExchangeScorer(const CandidateRows& rows, const Eigen::VectorXd& leak_norms,
                 const DesignCriterion& criterion);

  // Takes the plan with its run `position` left out: the sums of the other runs.
  void set_others(const std::vector<int>& plan, std::size_t position);
  // The objective of the plan with candidate c at the left-out position (infinity when it is ill-posed).
  double objective(int candidate);

 private:
  const CandidateRows& rows_;
  const Eigen::VectorXd& leak_norms_;
  const DesignCriterion& c_;
  bool others_ok_ = false;
  Eigen::MatrixXd N0_, B0_, BB0_, S0_;
  Eigen::VectorXd column_norm0_, natural_norm0_;  // Σ h_k², Σ x_k² of the other runs
  // Per-candidate workspace.
  Eigen::VectorXd h_, u_, scale_;
  Eigen::MatrixXd Ns_, Ninv_, M_, C_;
  Eigen::LDLT<Eigen::MatrixXd> ldlt_;
};

// ℓ·ℓ of every row's leaks.
Eigen::VectorXd leak_norms(const CandidateRows& rows);

}  // namespace ccal::design_detail
