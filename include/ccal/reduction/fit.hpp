#pragma once
// Linear least squares with diagnostics.
//
// Observations y_j (one per run) are modelled as y_j = sum_k X_k H_jk + noise, each column of H
// belonging to a named term (a stable id such as "K0", "K2" or "K_pp"). Columns of a calibration
// design differ by many orders of magnitude, so the normal equations are never formed: the design is
// scaled column by column to (nearly) unit norm, factorised by column-pivoting Householder QR (or SVD)
// and the solution is unscaled. Problems that a test plan cannot resolve are reported, not solved.
//
// To differentiate the fitted coefficients with Eigen's AutoDiff module, include <Eigen/Dense> (or
// this header) before <unsupported/Eigen/AutoDiff> and call solve_least_squares<AutoDiffScalar<...>>.

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/core/value_of.hpp"

namespace ccal {

struct FitProblem {
  std::vector<std::string> term_names;  // one per column of H, unique and non-empty
  Eigen::MatrixXd H;                    // rows = observations
  Eigen::VectorXd y;
  Eigen::VectorXd weights;              // empty = unit weights; else 1/sigma^2 per row, > 0 and finite
  std::map<std::string, double> fixed;  // term name -> known value (column removed, y -= H_col * value)
  std::vector<std::string> row_labels;  // optional (empty or one per row), e.g. run names, for messages
};

enum class FitMethod { qr, svd };

struct FitOptions {
  FitMethod method = FitMethod::qr;
  // Singular values of the column-scaled design at or below this are treated as zero.
  // 0 = automatic: max(rows, free terms) * machine epsilon * largest singular value.
  double rank_tolerance = 0;
  // |correlation| between two estimates above which they are reported as near-aliased (a warning).
  double alias_correlation = 0.999;
  // |correlation| beyond which the fit is refused (IllPosedFit naming the pair): the data then fix only a
  // combination of the two terms, whatever the condition number says.
  double refuse_correlation = 0.99999;
  // Condition number of the column-scaled design above which the fit is refused (IllPosedFit).
  double max_condition = 1e12;
  // Steps of iterative refinement of the augmented system [I A; A^T 0][r; x] = [b; 0], with its residuals
  // accumulated in double-double. One step already brings the NIST StRD problems to their certified
  // values to 9+ digits where the data allow (see tests/reduction/fit_test.cpp); 0 disables refinement.
  int refinement_steps = 1;
};

struct FitResult {
  std::vector<std::string> names;  // free terms, in the order of FitProblem::term_names
  Eigen::VectorXd value, std_error;
  Eigen::MatrixXd covariance, correlation;
  Eigen::VectorXd residuals;  // y - H x in the units of y (fixed terms included, weights not applied)
  // Unweighted: sqrt(RSS / dof). Weighted: sqrt(chi2 / dof), the scale of the normalised residuals.
  double residual_std = 0;
  int dof = 0;                  // rows - free terms
  double chi2 = 0;              // sum w r^2 (w = 1 when unweighted)
  double chi2_per_dof = 0;      // chi2 / dof (0 when dof == 0)
  double condition_number = 0;  // of the column-scaled (and weighted) design; 0 when nothing is free
  int rank = 0;
  std::vector<std::string> warnings;
};

// Solve the problem and report diagnostics.
//
// Covariance: with weights (taken as 1/sigma^2) it is (H^T W H)^-1; without weights it is
// s^2 (H^T H)^-1 with s^2 = RSS / dof. Either way it is obtained from the R factor (QR) or the singular
// value decomposition of the scaled design, never by forming H^T H. The correlation matrix does not
// depend on s^2 and is always reported.
//
// No degrees of freedom (rows == free terms): residual_std and chi2_per_dof are 0 and a warning says
// so. Without weights the standard errors are undefined: std_error and covariance are filled with
// zeros and the warning says they are undefined. With weights the covariance comes from the weights
// and is valid.
//
// Throws std::invalid_argument for malformed input (sizes, non-finite values with their 1-based row
// and column, unknown or duplicate term names, bad weights or options) and IllPosedFit when the design
// cannot determine the free terms.
FitResult fit(const FitProblem& problem, const FitOptions& options = {});

// The IllPosedFit a verb throws when the fit of its test plan is ill-posed: "the test plan cannot identify
// the configured terms: " and the fit's message, naming the same terms. Use: throw plan_cannot_identify(e);
IllPosedFit plan_cannot_identify(const IllPosedFit& e);

// Columns x^0 .. x^degree. Each power is accumulated in double-double and rounded once.
Eigen::MatrixXd polynomial_design(const Eigen::VectorXd& x, int degree);
// "K0" .. "K<degree>".
std::vector<std::string> polynomial_term_names(int degree);

// Least-squares solution of H b ~= y for any Eigen scalar type, in particular Eigen::AutoDiffScalar,
// so that fitted coefficients can be differentiated with respect to parameters entering H and y.
// Columns are scaled to unit norm, the scaled design is factorised by (unpivoted) Householder QR, which
// works on AutoDiff scalars, and the solution is unscaled. This is the differentiable kernel only: it
// makes no diagnostics beyond refusing too few rows or (numerically) dependent columns; use fit() to
// examine a design.
template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1> solve_least_squares(
    const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& H,
    const Eigen::Matrix<Scalar, Eigen::Dynamic, 1>& y) {
  using Matrix = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  const Eigen::Index rows = H.rows();
  const Eigen::Index cols = H.cols();
  if (y.size() != rows) {
    throw std::invalid_argument(
        fmt::format("solve_least_squares: H has {} rows but y has {} entries", rows, y.size()));
  }
  if (rows < cols) {
    throw IllPosedFit(
        fmt::format("solve_least_squares: {} observations cannot determine {} terms", rows, cols));
  }
  Vector scale(cols);
  Matrix scaled(rows, cols);
  for (Eigen::Index k = 0; k < cols; ++k) {
    using std::sqrt;
    const Scalar norm = sqrt(H.col(k).squaredNorm());
    if (!(value_of(norm) > 0)) {
      throw IllPosedFit(fmt::format("solve_least_squares: column {} is zero", k + 1));
    }
    scale(k) = Scalar(1) / norm;
    scaled.col(k) = H.col(k) * scale(k);
  }
  const Eigen::HouseholderQR<Matrix> qr(scaled);
  double max_diag = 0;
  for (Eigen::Index k = 0; k < cols; ++k) {
    max_diag = std::max(max_diag, std::abs(value_of(qr.matrixQR()(k, k))));
  }
  const double tiny = static_cast<double>(std::max(rows, cols)) * 2.220446049250313e-16 * max_diag;
  for (Eigen::Index k = 0; k < cols; ++k) {
    if (!(std::abs(value_of(qr.matrixQR()(k, k))) > tiny)) {
      throw IllPosedFit(
          fmt::format("solve_least_squares: the columns are linearly dependent (column {} adds nothing to "
                      "the previous ones)",
                      k + 1));
    }
  }
  const Vector z = qr.solve(y);
  return (z.array() * scale.array()).matrix();
}

}  // namespace ccal
