#pragma once
// Drift and agreement of one coefficient over an instrument's calibrations (`ccal history show`;
// docs/model.md §16). Each calibration i gives a value x_i at the time t_i (years) with its expanded
// uncertainty U_i and coverage factor k_i, so u_i = U_i / k_i. Calibrations on one set-up share the errors of
// the machine inputs both charged at their tolerance: their covariance C_ij = Cov(x_i, x_j), i ≠ j
// (uncertainty/history_shared.hpp), is the off-diagonal of the points' covariance V, V_ii = u_i².
//
// Agreement of successive calibrations (ISO 13528 §9.7, the normalised error, with the shared part taken
// out):
//     E_n = (x_{i+1} − x_i) / √(U_i² + U_{i+1}² − 2 k_i k_{i+1} C_{i,i+1}),   |E_n| > 1: the two do not agree
//     within their uncertainties. The denominator is the standard deviation of k_i e_i − k_{i+1} e_{i+1} (e
//     the calibrations' errors): each calibration expanded at its own k, as ISO 13528's √(U_i² + U_{i+1}²),
//     which it is for C = 0; for k_i = k_{i+1} = k it is k u(x_{i+1} − x_i).
// Drift, from three calibrations on: the straight line x = a + b (t − t̄) by generalised least squares with
// the covariance V (X = [1, t − t̄]): (a, b) = (Xᵀ V⁻¹ X)⁻¹ Xᵀ V⁻¹ x, t̄ = 1ᵀV⁻¹t / 1ᵀV⁻¹1 (so that a and b are
// uncorrelated and Xᵀ V⁻¹ X is diagonal):
//     b = (t − t̄)ᵀ V⁻¹ x / S,  S = (t − t̄)ᵀ V⁻¹ (t − t̄),  u(b) = 1/√S,  a = 1ᵀ V⁻¹ x / 1ᵀ V⁻¹ 1,
//     u(a) = 1/√(1ᵀ V⁻¹ 1);
// for a diagonal V the weighted line with w_i = 1/u_i². The stated uncertainties are taken as known (u(a),
// u(b) do not depend on the scatter); the Birge ratio R_B = √(χ²/(n − 2)), χ² = rᵀ V⁻¹ r with r = x − a − b(t
// − t̄), says whether the scatter about the line exceeds them (R_B > 1: the instrument varies beyond its
// stated uncertainty, or drifts other than linearly). The prediction at a time t: a + b (t − t̄) with u² =
// u(a)² + (t − t̄)² u(b)².

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace ccal {

// The year of the history's times t (days / 365.25): a mean Julian year, the same for every calibration.
inline constexpr double kDaysPerYear = 365.25;

struct HistoryPoint {
  double years = 0;            // t_i: time of the calibration, in years (365.25 days) from any fixed origin
  double value = 0;            // x_i
  double expanded = 0;         // U_i
  double coverage_factor = 2;  // k_i > 0
};

struct NormalisedError {
  std::size_t from = 0, to = 0;  // the indices of the two calibrations, to = from + 1
  double value = 0;              // E_n; 0 where it is undefined (defined = false)
  // false: the difference has no uncertainty (both U = 0, or all of it shared), so E_n has no value; the two
  // then disagree unless their values are equal.
  bool defined = true;
  bool disagree = false;         // |E_n| > 1, or undefined with different values
  double shared_covariance = 0;  // C_{from,to}, taken out of the denominator
};

struct DriftLine {
  bool available = false;  // three calibrations or more, at two different times at least, V positive definite
  std::string unavailable;     // why not, in words, when not available
  bool correlated = false;     // V had off-diagonal terms (calibrations sharing machine errors)
  double reference_years = 0;  // t̄
  double value = 0;            // a: the line at t̄
  double std_value = 0;        // u(a)
  double slope = 0;            // b, per year
  double std_slope = 0;        // u(b)
  double chi_squared = 0;
  int dof = 0;             // n − 2
  double birge_ratio = 0;  // √(χ²/dof)
};

struct DriftPrediction {
  double years = 0;
  double value = 0;
  double std_uncertainty = 0;
};

// E_n between each calibration and the next (points in time order). shared: C (points × points; only the
// off-diagonal is read), empty: independent calibrations.
std::vector<NormalisedError> normalised_errors(const std::vector<HistoryPoint>& points,
                                               const Eigen::MatrixXd& shared = {});
// The generalised least-squares line; not available (available = false, unavailable saying why) with fewer
// than three points, all at one time, a point with u_i = 0, or a V that is not positive definite.
DriftLine drift_line(const std::vector<HistoryPoint>& points, const Eigen::MatrixXd& shared = {});
// The line's value at `years` and its standard uncertainty (line.available must be true).
DriftPrediction predict(const DriftLine& line, double years);

}  // namespace ccal
