// The bounds of the allocation's scales against its rows (allocation_groups.hpp, docs/model.md §10.3).
#include <algorithm>

#include "allocation_groups.hpp"

namespace ccal {

BoundedRows bound_rows(const Eigen::MatrixXd& a, const Groups& groups, const Eigen::VectorXd& min_scale,
                       double max_scale) {
  const Eigen::Index nr = a.rows(), ng = a.cols();
  BoundedRows b;
  b.L = Eigen::VectorXd::Zero(ng);
  b.X = Eigen::VectorXd::Constant(ng, max_scale * max_scale);
  // Sources of one group share one λ: the group's least scale is the largest of its members'.
  for (Eigen::Index s = 0; s < min_scale.size(); ++s) {
    const int g = groups.of[std::size_t(s)];
    b.L[g] = std::max(b.L[g], min_scale[s] * min_scale[s]);
  }
  b.pinned.assign(std::size_t(ng), false);
  for (Eigen::Index g = 0; g < ng; ++g)
    if (b.L[g] >= b.X[g]) b.pinned[std::size_t(g)] = true;  // no room between the bounds
  b.dropped.assign(std::size_t(nr), false);
  b.unreachable.assign(std::size_t(nr), false);
  b.at_floor = a * b.L;
  for (Eigen::Index k = 0; k < nr; ++k) {
    if (b.at_floor[k] > 1 + 1e-12) {
      b.unreachable[std::size_t(k)] = true;
      continue;
    }
    if (b.at_floor[k] < 1 - 1e-12) continue;
    bool floored = true;
    for (Eigen::Index g = 0; g < ng; ++g)
      if (a(k, g) > 0 && !(b.L[g] > 0)) floored = false;
    if (!floored) continue;
    b.dropped[std::size_t(k)] = true;
    for (Eigen::Index g = 0; g < ng; ++g)
      if (a(k, g) > 0) b.pinned[std::size_t(g)] = true;
  }
  b.capacity = Eigen::VectorXd::Ones(nr);
  for (Eigen::Index k = 0; k < nr; ++k)
    for (Eigen::Index g = 0; g < ng; ++g)
      if (b.pinned[std::size_t(g)]) b.capacity[k] -= a(k, g) * b.L[g];
  // A row that keeps no room for its free groups (round-off at the edge of the above) cannot be met.
  for (Eigen::Index k = 0; k < nr; ++k)
    if (!b.dropped[std::size_t(k)] && !(b.capacity[k] > 0)) b.unreachable[std::size_t(k)] = true;
  return b;
}

}  // namespace ccal
