#include "ccal/uncertainty/history_trend.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace ccal {

std::vector<NormalisedError> normalised_errors(const std::vector<HistoryPoint>& points) {
  std::vector<NormalisedError> out;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const HistoryPoint &a = points[i], &b = points[i + 1];
    const double difference = b.value - a.value, scale = std::hypot(a.expanded, b.expanded);
    NormalisedError e;
    e.from = i;
    e.to = i + 1;
    e.value = scale > 0         ? difference / scale
              : difference == 0 ? 0.0
                                : std::copysign(std::numeric_limits<double>::infinity(), difference);
    e.disagree = std::abs(e.value) > 1;
    out.push_back(e);
  }
  return out;
}

DriftLine drift_line(const std::vector<HistoryPoint>& points) {
  DriftLine line;
  const std::size_t n = points.size();
  if (n < 3) return line;
  double sw = 0, swt = 0, swx = 0;
  for (const HistoryPoint& p : points) {
    const double u = p.coverage_factor > 0 ? p.expanded / p.coverage_factor : 0.0;
    if (!(u > 0)) return line;
    const double w = 1 / (u * u);
    sw += w;
    swt += w * p.years;
    swx += w * p.value;
  }
  const double t_bar = swt / sw, a = swx / sw;
  double s = 0, sxy = 0;
  for (const HistoryPoint& p : points) {
    const double u = p.expanded / p.coverage_factor, w = 1 / (u * u), dt = p.years - t_bar;
    s += w * dt * dt;
    sxy += w * dt * p.value;
  }
  if (!(s > 0)) return line;  // every calibration at one time: no slope
  line.available = true;
  line.reference_years = t_bar;
  line.value = a;
  line.std_value = 1 / std::sqrt(sw);
  line.slope = sxy / s;
  line.std_slope = 1 / std::sqrt(s);
  for (const HistoryPoint& p : points) {
    const double u = p.expanded / p.coverage_factor;
    const double r = (p.value - a - line.slope * (p.years - t_bar)) / u;
    line.chi_squared += r * r;
  }
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
