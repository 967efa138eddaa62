#pragma once
// The correlation matrix of the tolerances' errors (docs/model.md §10.1): 1 on the diagonal, 1 between the
// members of a group, r for each [[correlations]] pair (for every member of a group a pair names: the group
// moves as one), 0 elsewhere; and a factor F with R = F Fᵀ, through
// which every consumer adds the sources' effects: the budget's covariance E R Eᵀ = (E F)(E F)ᵀ, the design's
// leak rows, the statement's Type B part.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "ccal/setup/config.hpp"
#include "ccal/setup/tolerance.hpp"

namespace ccal {

struct InputCorrelation {
  Eigen::MatrixXd matrix;  // R (sources × sources, tolerance order)
  // F (sources × m), R = F Fᵀ: the group indicator (one column per group or lone source) when there are no
  // [[correlations]], else the eigenvectors of R scaled by the square roots of its positive eigenvalues.
  Eigen::MatrixXd factor;
  bool partial = false;            // some pair has |r| < 1 besides the groups
  double smallest_eigenvalue = 1;  // of R; < 0: not a correlation matrix
  std::vector<std::string> along;  // the sources that carry most of that eigenvalue's eigenvector
};

// Throws std::invalid_argument for a pair naming a source that has no tolerance (the configuration reader
// refuses it first, with its line).
InputCorrelation input_correlation(const std::vector<Tolerance>& tolerances,
                                   const std::vector<Correlation>& correlations);

// Negative eigenvalues of R down to this are round-off (R's entries are given to at most 17 digits); below
// it the matrix is refused as no joint distribution's.
inline constexpr double kCorrelationEigenvalueFloor = -1e-12;

}  // namespace ccal
