#pragma once
// One wild value among a log's output samples, or among a pulse count's step rates (private to io/): a lost
// digit, a glitch, a cell edited by hand, which would move the run's mean with nothing to show for it (a
// count's first or last cell sets the mean alone). Streamed: the values' count, mean and sum of squared
// departures (Welford), and the highest and the lowest with their lines; at the end each extreme is set
// against the others, their mean and standard deviation without it (docs/model.md §13).
#include <cstddef>
#include <limits>
#include <optional>

namespace ccal::detail {

// How far an extreme may depart from the other values, in their standard deviations. A normal sample of 10^7
// values reaches 5.9, a sinusoid √2, a linear drift √3: 20 is no value of a run's steady output.
inline constexpr double kWildSpread = 20;

struct WildValue {
  double value = 0;       // the extreme as added
  int line = 0;           // its line
  double others_mean = 0;  // the other values' mean and standard deviation
  double others_sd = 0;
  double departure = 0;   // |value − others_mean|
};

class SampleSpread {
 public:
  // A value at its line; floor: the least departure that counts for it (the resolution of what it is read
  // from, e.g. ten counts over its step's time for a count's step rate).
  void add(double value, int line, double floor) {
    ++n_;
    const double delta = value - mean_;
    mean_ += delta / double(n_);
    m2_ += delta * (value - mean_);
    if (value > high_.value) high_ = {value, line, floor};
    if (value < low_.value) low_ = {value, line, floor};
  }
  // The extreme that departs from the others by more than kWildSpread of their standard deviations and more
  // than its floor (and than extra_floor, a floor for every value), the farther of the two; none otherwise.
  std::optional<WildValue> wild(double extra_floor = 0) const;

 private:
  struct Extreme {
    double value;
    int line;
    double floor;
  };
  std::optional<WildValue> departs(const Extreme& e, double extra_floor) const;
  std::size_t n_ = 0;
  double mean_ = 0, m2_ = 0;
  Extreme high_{-std::numeric_limits<double>::infinity(), 0, 0};
  Extreme low_{std::numeric_limits<double>::infinity(), 0, 0};
};

}  // namespace ccal::detail
