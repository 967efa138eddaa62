#pragma once
// The sample statistics of a Monte Carlo run (private to the library): compensated sums, moments, and the
// coverage intervals of JCGM 101 §7.7 (probabilistically symmetric) and §7.7.2 (shortest) from order
// statistics, the numerical tolerance of §7.9.2.
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace ccal::sample_stats {

// Neumaier's compensated summation (Z. Angew. Math. Mech. 54, 1974): the rounding error of every addition
// is accumulated separately, so the error of a sum of M terms does not grow with M.
class Sum {
 public:
  void add(double x) {
    const double t = s_ + x;
    c_ += std::abs(s_) >= std::abs(x) ? (s_ - t) + x : (x - t) + s_;
    s_ = t;
  }
  double value() const { return s_ + c_; }

 private:
  double s_ = 0;
  double c_ = 0;
};

struct Interval {
  double low = 0;
  double high = 0;
};

double mean_of(std::span<const double> v);
double co_moment(std::span<const double> a, double mean_a, std::span<const double> b, double mean_b);
// q = round(pM) of §7.7.2, and the same at most M − 1.
std::uint64_t rounded_points(std::uint64_t M, double p);
std::uint64_t interval_points(std::uint64_t M, double p);
Interval symmetric_interval(std::span<const double> sorted, std::uint64_t q);
// v permuted so that its M − q smallest values come first and its M − q largest last, each in ascending order
// (the middle in no order): what the intervals and the order statistics read. The same values in those places
// as a full sort gives.
void sort_tails(std::span<double> v, std::uint64_t q);
Interval shortest_interval(std::span<const double> sorted, std::uint64_t q);
double tolerance_of(double u, int n_dig);
double spread_of_average(const std::vector<double>& v);

// Counts of M values in `bins` equal bins spanning [lowest, highest] (the last bin closed); one bin when all
// values are equal. `lowest`, `highest`: the extreme values.
std::vector<std::uint64_t> histogram_counts(std::span<const double> v, double lowest, double highest,
                                            int bins);

// Distribution-free standard error of the order statistic y_(r) (1-based) of M values: the number of values
// below a quantile is binomial with standard deviation k = √(r(M − r)/M), so y_(r) moves by about
// (y_(r+k) − y_(r−k))/2 from one sample to the next (H. A. David, H. N. Nagaraja, "Order statistics", 3rd
// ed., 2003, §7.1). Reads only y_(first) … y_(last), which must be sorted; the window is cut to them.
double order_statistic_std_error(std::span<const double> sorted_tails, std::uint64_t r, std::uint64_t first,
                                 std::uint64_t last);

}  // namespace ccal::sample_stats
