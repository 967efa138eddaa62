#include "ccal/setup/input_correlation.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ccal {

namespace {

Eigen::Index index_of(const std::vector<Tolerance>& tolerances, const std::string& id) {
  for (std::size_t s = 0; s < tolerances.size(); ++s)
    if (tolerances[s].id == id) return Eigen::Index(s);
  throw std::invalid_argument("correlation of '" + id + "', which has no tolerance");
}

}  // namespace

InputCorrelation input_correlation(const std::vector<Tolerance>& tolerances,
                                   const std::vector<Correlation>& correlations) {
  const auto n = Eigen::Index(tolerances.size());
  const CorrelationGroups groups = correlation_groups(tolerances);
  InputCorrelation out;
  out.matrix = Eigen::MatrixXd::Identity(n, n);
  for (Eigen::Index a = 0; a < n; ++a)
    for (Eigen::Index b = 0; b < n; ++b)
      if (groups.of[std::size_t(a)] == groups.of[std::size_t(b)]) out.matrix(a, b) = 1;
  // A pair with a grouped source correlates the other with the whole group, which moves as one (r = 1
  // within it): every member pairs alike, or R would not be a correlation matrix.
  std::vector<std::vector<Eigen::Index>> members(std::size_t(groups.count));
  for (Eigen::Index s = 0; s < n; ++s) members[std::size_t(groups.of[std::size_t(s)])].push_back(s);
  for (const Correlation& c : correlations) {
    const auto ga = std::size_t(groups.of[std::size_t(index_of(tolerances, c.first))]);
    const auto gb = std::size_t(groups.of[std::size_t(index_of(tolerances, c.second))]);
    for (const Eigen::Index a : members[ga])
      for (const Eigen::Index b : members[gb]) out.matrix(a, b) = out.matrix(b, a) = c.r;
    out.partial = true;
  }
  if (!out.partial) {
    out.factor = Eigen::MatrixXd::Zero(n, groups.count);
    for (Eigen::Index s = 0; s < n; ++s) out.factor(s, groups.of[std::size_t(s)]) = 1;
    out.smallest_eigenvalue = 0;  // a group of two or more is singular; none: 1 (not needed by anyone)
    return out;
  }
  // R = V Λ Vᵀ; F = V Λ^{1/2} over the eigenvalues above round-off (a group's repeated rows give zeros).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(out.matrix);
  const Eigen::VectorXd& lambda = eigen.eigenvalues();  // ascending
  out.smallest_eigenvalue = lambda[0];
  const Eigen::VectorXd weakest = eigen.eigenvectors().col(0);
  for (Eigen::Index s = 0; s < n; ++s)
    if (std::abs(weakest[s]) >= 0.25 * weakest.cwiseAbs().maxCoeff())
      out.along.push_back(tolerances[std::size_t(s)].id);
  const double tiny = 1e-12 * std::max(1.0, lambda[n - 1]);
  Eigen::Index kept = 0;
  for (Eigen::Index i = 0; i < n; ++i) kept += lambda[i] > tiny ? 1 : 0;
  out.factor.resize(n, kept);
  for (Eigen::Index i = n - kept, c = 0; i < n; ++i, ++c)
    out.factor.col(c) = eigen.eigenvectors().col(i) * std::sqrt(lambda[i]);
  return out;
}

}  // namespace ccal
