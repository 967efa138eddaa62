#include "design_exchange.hpp"

#include <cmath>
#include <limits>

namespace ccal::design_detail {

Eigen::VectorXd leak_norms(const CandidateRows& rows) { return rows.leaks.rowwise().squaredNorm(); }

ExchangeScorer::ExchangeScorer(const CandidateRows& rows, const Eigen::VectorXd& leak_norms,
                               const DesignCriterion& criterion)
    : rows_(rows), leak_norms_(leak_norms), c_(criterion) {}

void ExchangeScorer::set_others(const std::vector<int>& plan, std::size_t position) {
  const Eigen::Index p = rows_.regressors.cols(), groups = rows_.leaks.cols();
  N0_ = Eigen::MatrixXd::Zero(p, p);
  S0_ = Eigen::MatrixXd::Zero(p, p);
  B0_ = Eigen::MatrixXd::Zero(p, groups);
  column_norm0_ = Eigen::VectorXd::Zero(p);
  natural_norm0_ = Eigen::VectorXd::Zero(p);
  for (std::size_t j = 0; j < plan.size(); ++j) {
    if (j == position) continue;
    const Eigen::Index r = plan[j];
    const Eigen::VectorXd h = rows_.regressors.row(r).transpose();
    N0_.noalias() += h * h.transpose();
    S0_.noalias() += (rows_.scatter[r] + rows_.noise[r]) * h * h.transpose();
    B0_.noalias() += h * rows_.leaks.row(r);
    column_norm0_ += h.array().square().matrix();
    natural_norm0_ += rows_.natural.row(r).transpose().array().square().matrix();
  }
  BB0_.noalias() = B0_ * B0_.transpose();
  others_ok_ = Eigen::Index(plan.size()) >= p;  // fewer runs than terms: never well posed
}

double ExchangeScorer::objective(int candidate) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  if (!others_ok_) return kInfinity;
  const Eigen::Index p = N0_.rows();
  h_ = rows_.regressors.row(candidate).transpose();
  // Column scaling, as the fit does (model.md §9).
  scale_.resize(p);
  for (Eigen::Index k = 0; k < p; ++k) {
    const double norm = std::sqrt(column_norm0_[k] + h_[k] * h_[k]);
    if (!(norm > 0) || !std::isfinite(norm)) return kInfinity;
    scale_[k] = 1.0 / norm;
  }
  Ns_.noalias() = scale_.asDiagonal() * (N0_ + h_ * h_.transpose()) * scale_.asDiagonal();
  ldlt_.compute(Ns_);
  if (ldlt_.info() != Eigen::Success) return kInfinity;
  Ninv_ = ldlt_.solve(Eigen::MatrixXd::Identity(p, p));
  // Well posed: ‖P⊥h_k‖ = 1/(s_k √[Ns⁻¹]_kk) above the round-off of its natural size, correlations below the
  // limit (model.md §14, §9).
  for (Eigen::Index k = 0; k < p; ++k) {
    const double d = Ninv_(k, k);
    if (!(d > 0) || !std::isfinite(d)) return kInfinity;
    const double projected = 1.0 / (scale_[k] * std::sqrt(d));
    const double x = rows_.natural(candidate, k);
    if (!(projected > c_.roundoff_fraction * std::sqrt(natural_norm0_[k] + x * x))) return kInfinity;
    for (Eigen::Index l = 0; l < k; ++l)
      if (std::abs(Ninv_(k, l)) > c_.max_correlation * std::sqrt(d * Ninv_(l, l))) return kInfinity;
  }
  // N⁻¹ = S Ns⁻¹ S; M = Hᵀ(L Lᵀ + V)H by the rank-one updates above.
  Ninv_ = scale_.asDiagonal() * Ninv_ * scale_.asDiagonal();
  u_.noalias() = B0_ * rows_.leaks.row(candidate).transpose();
  const double v = rows_.scatter[candidate] + rows_.noise[candidate];
  M_ = BB0_ + S0_;
  M_.noalias() += u_ * h_.transpose();
  M_.noalias() += h_ * u_.transpose();
  M_.noalias() += (leak_norms_[candidate] + v) * h_ * h_.transpose();
  C_.noalias() = Ninv_ * M_ * Ninv_;
  double f = 0;
  for (Eigen::Index k = 0; k < p; ++k)
    if (c_.weight[k] > 0)
      f += c_.weight[k] * c_.coverage_factor * c_.coverage_factor * C_(k, k) /
           (c_.reference[k] * c_.reference[k]);
  return f;
}

}  // namespace ccal::design_detail
