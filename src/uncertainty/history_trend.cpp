#include "ccal/uncertainty/history_trend.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ccal {

namespace {

double standard_uncertainty(const HistoryPoint& p) {
  return p.coverage_factor > 0 ? p.expanded / p.coverage_factor : 0.0;
}

// A power of two near the largest magnitude m (1 for none): dividing by it is exact, so the scaled figures
// give the same bits as unscaled ones wherever those did not overflow.
double power_of_two_scale(double m) { return m > 0 && std::isfinite(m) ? std::ldexp(1.0, std::ilogb(m)) : 1.0; }

double shared_between(const Eigen::MatrixXd& shared, std::size_t i, std::size_t j) {
  return shared.rows() > Eigen::Index(std::max(i, j)) ? shared(Eigen::Index(i), Eigen::Index(j)) : 0.0;
}

}  // namespace

std::vector<NormalisedError> normalised_errors(const std::vector<HistoryPoint>& points,
                                               const Eigen::MatrixXd& shared) {
  std::vector<NormalisedError> out;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const HistoryPoint &a = points[i], &b = points[i + 1];
    NormalisedError e;
    e.from = i;
    e.to = i + 1;
    e.shared_covariance = shared_between(shared, i, i + 1);
    // Every term divided by (a power of two near) the largest of |x_i|, |x_j|, U_i, U_j first: x = ±1e308 with U = 1e308 would
    // overflow the difference and the squares (E_n = −inf for −1.41), and E_n is the same ratio scaled.
    const double scale =
        power_of_two_scale(std::max({std::abs(a.value), std::abs(b.value), a.expanded, b.expanded}));
    const double difference = b.value / scale - a.value / scale;
    const double ua = a.expanded / scale, ub = b.expanded / scale;
    // U_i² + U_j² − 2 k_i k_j C: ≥ (U_i − U_j)² for a C within Cauchy–Schwarz, so ≥ 0 but for round-off.
    const double independent = ua * ua + ub * ub;
    const double variance =
        independent - 2 * a.coverage_factor * b.coverage_factor * (e.shared_covariance / scale / scale);
    // A variance below 1e-12 of U_i² + U_j² is the round-off (~1e-16 of it) of a cancellation, not a value.
    if (variance > 1e-12 * independent) {
      e.value = difference / std::sqrt(variance);
      e.disagree = std::abs(e.value) > 1;
    } else {
      e.defined = false;
      e.disagree = difference != 0;
    }
    out.push_back(e);
  }
  return out;
}

DriftLine drift_line(const std::vector<HistoryPoint>& points, const Eigen::MatrixXd& shared) {
  DriftLine line;
  const auto n = Eigen::Index(points.size());
  if (n < 3) {
    line.unavailable = "needs three calibrations at two dates at least";
    return line;
  }
  Eigen::MatrixXd v = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd t(n), x(n);
  // Values and uncertainties divided by the largest of them (as E_n's), so that their squares cannot overflow.
  double largest = 0;
  for (const HistoryPoint& p : points) largest = std::max({largest, std::abs(p.value), standard_uncertainty(p)});
  const double scale = power_of_two_scale(largest);
  for (Eigen::Index i = 0; i < n; ++i) {
    const HistoryPoint& p = points[std::size_t(i)];
    const double u = standard_uncertainty(p) / scale;
    if (!(u > 0)) {
      line.unavailable = "a calibration states U = 0, so the points cannot be weighted";
      return line;
    }
    v(i, i) = u * u;
    t[i] = p.years;
    x[i] = p.value / scale;
    for (Eigen::Index j = 0; j < n; ++j)
      if (j != i && shared.rows() == n && shared(i, j) != 0) {
        v(i, j) = shared(i, j) / scale / scale;
        line.correlated = true;
      }
  }
  const Eigen::LLT<Eigen::MatrixXd> factor(v);
  if (factor.info() != Eigen::Success) {
    line.unavailable =
        "the calibrations' covariance is not positive definite (they share more than their own "
        "uncertainty holds)";
    return line;
  }
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(n);
  const Eigen::VectorXd v_ones = factor.solve(ones);  // V⁻¹ 1
  const double sum_weights = ones.dot(v_ones);        // 1ᵀ V⁻¹ 1
  const double t_bar = t.dot(v_ones) / sum_weights;
  const Eigen::VectorXd dt = t.array() - t_bar;
  const Eigen::VectorXd v_dt = factor.solve(dt);  // V⁻¹ (t − t̄)
  const double s = dt.dot(v_dt);
  if (!(s > 0) || !std::isfinite(s) || !(sum_weights > 0)) {
    line.unavailable = "needs three calibrations at two dates at least";
    return line;
  }
  line.available = true;
  line.reference_years = t_bar;
  const double a = x.dot(v_ones) / sum_weights, b = x.dot(v_dt) / s;  // of the scaled values
  line.value = a * scale;
  line.std_value = scale / std::sqrt(sum_weights);
  line.slope = b * scale;
  line.std_slope = scale / std::sqrt(s);
  const Eigen::VectorXd r = x - Eigen::VectorXd::Constant(n, a) - b * dt;
  line.chi_squared = std::max(0.0, r.dot(factor.solve(r)));
  line.dof = int(n) - 2;
  line.birge_ratio = std::sqrt(line.chi_squared / line.dof);
  return line;
}

DriftPrediction predict(const DriftLine& line, double years) {
  if (!line.available) throw std::invalid_argument("predict: no drift line");
  const double dt = years - line.reference_years;
  return {years, line.value + line.slope * dt, std::hypot(line.std_value, dt * line.std_slope)};
}

}  // namespace ccal
