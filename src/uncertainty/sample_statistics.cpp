#include "sample_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal {
namespace sample_stats {

double mean_of(std::span<const double> v) {
  Sum s;
  for (double x : v) s.add(x);
  return s.value() / double(v.size());
}

double co_moment(std::span<const double> a, double mean_a, std::span<const double> b, double mean_b) {
  Sum s;
  for (std::size_t i = 0; i < a.size(); ++i) s.add((a[i] - mean_a) * (b[i] - mean_b));
  return s.value();
}

// q of §7.7.2: pM if that is an integer, else ⌊pM + ½⌋.
std::uint64_t rounded_points(std::uint64_t M, double p) {
  const double pm = p * double(M);
  return std::uint64_t(pm == std::floor(pm) ? pm : std::floor(pm + 0.5));
}

// At most M − 1 so that an interval has two ends (run_monte_carlo refuses an M for which q would be M).
std::uint64_t interval_points(std::uint64_t M, double p) {
  return std::min<std::uint64_t>(rounded_points(M, p), M - 1);
}

// [y_(r), y_(r+q)] with r = (M − q)/2 if an integer, else ⌊(M − q + 1)/2⌋ (1-based): in both cases
// r = ⌊(M − q + 1)/2⌋.
Interval symmetric_interval(std::span<const double> sorted, std::uint64_t q) {
  const std::uint64_t r = (sorted.size() - q + 1) / 2;
  return {sorted[r - 1], sorted[r - 1 + q]};
}

// Puts in place the order statistics the intervals of q + 1 points read: the M − q lowest and the M − q
// highest values, each block sorted (the middle stays unordered). Both intervals only look at those, so the
// result is that of a full sort at a fraction of its cost (two O(M) selections and sorts of 2(1 − p)M
// values).
namespace {

// The tails by thresholds, for a large sample: a strided subsample's order statistics give a value `low` with
// at least `tail` values below it and one, `high`, with at least `tail` above it (with overwhelming
// probability: the subsample's rank is a binomial's mean plus 4σ and 8 beyond the tail's share); two
// in-place partitions move the values below `low` to the front and those above `high` to the back, so that
// only those few are selected and sorted, where nth_element would pass over all M values several times.
// Every value of the `tail` smallest is below `low` when `tail` values are (the tail-th smallest is), so the
// result is the exact one. False, with v only permuted, when a threshold holds fewer than `tail` values.
bool tails_by_thresholds(std::span<double> v, std::size_t tail) {
  constexpr std::size_t kSample = 4096;
  const std::size_t M = v.size();
  if (M < 4 * kSample) return false;
  std::vector<double> sample(kSample);
  const std::size_t stride = M / kSample;
  for (std::size_t i = 0; i < kSample; ++i) sample[i] = v[i * stride];
  const double expected = double(kSample) * double(tail) / double(M);
  const auto rank = std::min(kSample / 2 - 1, std::size_t(expected + 4 * std::sqrt(expected) + 8));
  std::nth_element(sample.begin(), sample.begin() + std::ptrdiff_t(rank), sample.end());
  const double low = sample[rank];
  std::nth_element(sample.begin(), sample.end() - 1 - std::ptrdiff_t(rank), sample.end());
  const double high = sample[kSample - 1 - rank];
  if (!(low < high)) return false;
  const auto below = std::partition(v.begin(), v.end(), [low](double x) { return x < low; });
  if (std::size_t(below - v.begin()) < tail) return false;
  const auto above = std::partition(below, v.end(), [high](double x) { return !(x > high); });
  if (std::size_t(v.end() - above) < tail) return false;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(tail), below);
  std::sort(v.begin(), v.begin() + std::ptrdiff_t(tail));
  std::nth_element(above, v.end() - std::ptrdiff_t(tail), v.end());
  std::sort(v.end() - std::ptrdiff_t(tail), v.end());
  return true;
}

}  // namespace

void sort_tails(std::span<double> v, std::uint64_t q) {
  const std::size_t M = v.size(), tail = M - q;
  if (2 * tail >= M) {
    std::sort(v.begin(), v.end());
    return;
  }
  if (tails_by_thresholds(v, tail)) return;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(tail), v.end());
  std::sort(v.begin(), v.begin() + std::ptrdiff_t(tail));
  std::nth_element(v.begin() + std::ptrdiff_t(tail), v.begin() + std::ptrdiff_t(q), v.end());
  std::sort(v.begin() + std::ptrdiff_t(q), v.end());
}

Interval shortest_interval(std::span<const double> sorted, std::uint64_t q) {
  std::size_t best = 0;
  double width = std::numeric_limits<double>::infinity();
  for (std::size_t r = 0; r + q < sorted.size(); ++r) {
    const double w = sorted[r + q] - sorted[r];
    if (w < width) {
      width = w;
      best = r;
    }
  }
  return {sorted[best], sorted[best + q]};
}

// Numerical tolerance of §7.9.2: u = c·10ˡ with c an integer of n_dig digits, δ = ½·10ˡ (0 for u = 0).
double tolerance_of(double u, int n_dig) {
  if (!(u > 0) || !std::isfinite(u)) return 0.0;
  int l = int(std::floor(std::log10(u))) - n_dig + 1;
  const double top = std::pow(10.0, n_dig);
  // log10 may be off by one near a power of ten, and rounding c may carry into an extra digit.
  if (std::round(u / std::pow(10.0, l)) >= top) ++l;
  if (std::round(u / std::pow(10.0, l)) < top / 10) --l;
  return 0.5 * std::pow(10.0, l);
}

// Standard deviation of the average of h values (§7.9.4 f): sqrt(Σ (v − v̄)² / (h(h − 1))).
double spread_of_average(const std::vector<double>& v) {
  const std::size_t h = v.size();
  if (h < 2) return 0.0;
  const double m = mean_of(v);
  Sum s;
  for (double x : v) s.add((x - m) * (x - m));
  return std::sqrt(s.value() / double(h * (h - 1)));
}

std::vector<std::uint64_t> histogram_counts(std::span<const double> v, double lowest, double highest,
                                            int bins) {
  const double width = highest - lowest;
  if (!(width > 0) || bins < 1) return {std::uint64_t(v.size())};
  std::vector<std::uint64_t> counts(std::size_t(bins), 0);
  const double per_unit = double(bins) / width;
  for (double x : v) {
    const auto b = std::clamp<std::int64_t>(std::int64_t((x - lowest) * per_unit), 0, bins - 1);
    ++counts[std::size_t(b)];
  }
  return counts;
}

double order_statistic_std_error(std::span<const double> sorted_tails, std::uint64_t r, std::uint64_t first,
                                 std::uint64_t last) {
  const double M = double(sorted_tails.size());
  const auto k = std::uint64_t(std::ceil(std::sqrt(double(r) * (M - double(r)) / M)));
  const std::uint64_t below = r > first + k ? r - k : first, above = std::min(r + k, last);
  if (above <= below) return 0.0;
  // Scaled to the width of a window of 2k ranks when the window was cut at an end.
  return (sorted_tails[above - 1] - sorted_tails[below - 1]) * double(k) / double(above - below);
}

}  // namespace sample_stats

using namespace sample_stats;

std::uint64_t coverage_points(std::uint64_t M, double p) {
  if (M < 2 || !(p > 0 && p < 1)) throw InputError("coverage interval: needs M ≥ 2 values and p in (0, 1)");
  return interval_points(M, p);
}

std::pair<double, double> symmetric_coverage_interval(std::span<const double> sorted, double p) {
  const Interval i = symmetric_interval(sorted, coverage_points(sorted.size(), p));
  return {i.low, i.high};
}

std::pair<double, double> shortest_coverage_interval(std::span<const double> sorted, double p) {
  const Interval i = shortest_interval(sorted, coverage_points(sorted.size(), p));
  return {i.low, i.high};
}

double numerical_tolerance(double u, int n_dig) { return tolerance_of(u, n_dig); }

}  // namespace ccal
