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

}  // namespace ccal
