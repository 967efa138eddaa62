#pragma once
// Drift and agreement of one coefficient over an instrument's calibrations (`ccal history show`;
// docs/model.md §16). Each calibration i gives a value x_i at the time t_i (years) with its expanded
// uncertainty U_i and coverage factor k_i, so u_i = U_i / k_i.
//
// Agreement of successive calibrations (ISO 13528 §9.7, the normalised error):
//     E_n = (x_{i+1} − x_i) / √(U_i² + U_{i+1}²),   |E_n| > 1: the two do not agree within their
//     uncertainties.
// Drift, from three calibrations on: the straight line x = a + b (t − t̄) by weighted least squares with
// weights w_i = 1/u_i², t̄ = Σ w_i t_i / Σ w_i (so that a and b are uncorrelated):
//     b = Σ w_i (t_i − t̄) x_i / S,  S = Σ w_i (t_i − t̄)²,   u(b) = 1/√S,   a = Σ w_i x_i / Σ w_i,  u(a) =
//     1/√Σ w_i,
// with the stated uncertainties taken as known (u(a), u(b) do not depend on the scatter); the Birge ratio
// R_B = √(χ²/(n − 2)), χ² = Σ w_i (x_i − a − b(t_i − t̄))², says whether the scatter about the line exceeds
// them (R_B > 1: the instrument varies beyond its stated uncertainty, or drifts other than linearly). The
// prediction at a time t: a + b (t − t̄) with u² = u(a)² + (t − t̄)² u(b)².

#include <cstddef>
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
  double value = 0;              // E_n; 0 where both U are 0 and the values equal, ±∞ where they differ
  bool disagree = false;         // |E_n| > 1
};

struct DriftLine {
  bool available = false;      // three calibrations or more, at two different times at least, every u_i > 0
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

// E_n between each calibration and the next (points in time order).
std::vector<NormalisedError> normalised_errors(const std::vector<HistoryPoint>& points);
// The weighted straight line; not available (available = false) with fewer than three points, all at one
// time, or a point with u_i = 0.
DriftLine drift_line(const std::vector<HistoryPoint>& points);
// The line's value at `years` and its standard uncertainty (line.available must be true).
DriftPrediction predict(const DriftLine& line, double years);

}  // namespace ccal
