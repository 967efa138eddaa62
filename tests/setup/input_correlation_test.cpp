// The inputs' correlation matrix (setup/input_correlation.hpp) against matrices written here: groups give 1
// between their members, pairs their r; the factor reproduces R; a matrix that no joint distribution has is
// found by its smallest eigenvalue, with the sources it lies along.
#include "ccal/setup/input_correlation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>
#include <vector>

#include "ccal/core/errors.hpp"

namespace ccal {
namespace {

std::vector<Tolerance> sources(const std::vector<std::pair<std::string, std::string>>& id_and_group) {
  std::vector<Tolerance> out;
  for (const auto& [id, group] : id_and_group) {
    Tolerance t;
    t.id = id;
    t.group = group;
    t.bound = 1;
    out.push_back(t);
  }
  return out;
}

TEST(InputCorrelation, GroupsAndPairsMakeTheMatrixAndTheFactorReproducesIt) {
  const auto t = sources({{"a", ""}, {"b", "g"}, {"c", "g"}, {"d", ""}});
  const InputCorrelation ic = input_correlation(t, {{"a", "d", 0.6}, {"a", "b", -0.3}, {"a", "c", -0.3}});
  Eigen::Matrix4d want;
  want << 1, -0.3, -0.3, 0.6,  //
      -0.3, 1, 1, 0,           //
      -0.3, 1, 1, 0,           //
      0.6, 0, 0, 1;
  EXPECT_TRUE(ic.partial);
  EXPECT_EQ(ic.matrix, Eigen::MatrixXd(want));
  // R = F Fᵀ to round-off of an eigen-decomposition of a 4×4 matrix of order 1 (1e-14); the group's two rows
  // are one direction, so F has 3 columns.
  EXPECT_LT((ic.factor * ic.factor.transpose() - want).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_EQ(ic.factor.cols(), 3);
  EXPECT_GE(ic.smallest_eigenvalue, kCorrelationEigenvalueFloor);
}

TEST(InputCorrelation, GroupsAloneKeepTheirIndicator) {
  const auto t = sources({{"a", "g"}, {"b", ""}, {"c", "g"}});
  const InputCorrelation ic = input_correlation(t, {});
  EXPECT_FALSE(ic.partial);
  Eigen::MatrixXd indicator(3, 2);
  indicator << 1, 0, 0, 1, 1, 0;
  EXPECT_EQ(ic.factor, indicator);  // exactly: the budget's sums of effects, unchanged
  EXPECT_EQ(ic.matrix, indicator * indicator.transpose());
}

TEST(InputCorrelation, AMatrixNoDistributionHasIsFoundAlongItsSources) {
  // r_ab = r_ac = 0.9 and r_bc = −0.9: eigenvalues of [[1, .9, .9], [.9, 1, −.9], [.9, −.9, 1]] are 1.9, 1.9
  // and 1 − 1.8 = −0.8 (eigenvector (−1, 1, 1)/√3, along all three); d is apart.
  const auto t = sources({{"a", ""}, {"b", ""}, {"c", ""}, {"d", ""}});
  const InputCorrelation ic = input_correlation(t, {{"a", "b", 0.9}, {"a", "c", 0.9}, {"b", "c", -0.9}});
  EXPECT_NEAR(ic.smallest_eigenvalue, -0.8, 1e-14);
  EXPECT_EQ(ic.along, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_THROW(input_correlation(t, {{"a", "e", 0.5}}), std::invalid_argument);
}

}  // namespace
}  // namespace ccal
