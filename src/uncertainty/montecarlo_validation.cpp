// What a failed validation of the LPU (JCGM 101 §8) at a fixed M says: the sampling error of the interval
// ends against the excess of d over δ.
#include <algorithm>
#include <cmath>
#include <limits>

#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal {

namespace {
// n rounded up to 2 significant digits (e.g. 123 456 → 130 000), so that a suggested M reads as a round
// number.
std::uint64_t round_up_2_digits(double n) {
  if (!(n > 1)) return 1;
  const double scale = std::pow(10.0, std::floor(std::log10(n)) - 1);
  return std::uint64_t(std::ceil(n / scale - 1e-9) * scale);
}
}  // namespace

ValidationDiagnosis validation_diagnosis(const OutputSummary& s, std::uint64_t trials) {
  ValidationDiagnosis d;
  d.validated = s.validated;
  d.excess = std::max(s.d_low, s.d_high) - s.validation_delta;
  const double se = s.interval_end_std_error;
  d.excess_in_std_errors =
      se > 0 ? d.excess / se : (d.excess > 0 ? std::numeric_limits<double>::infinity() : 0.0);
  // Three standard errors: a sampling deviation this large has a probability of about 0.3 % (normal).
  d.explained_by_sampling = !s.validated && d.excess <= 3 * se;
  // The standard error falls as 1/√M: at M' = M (3 se/δ)² it is δ/3.
  if (s.validation_delta > 0 && se > 0)
    d.trials_needed = round_up_2_digits(double(trials) * std::pow(3 * se / s.validation_delta, 2));
  return d;
}

}  // namespace ccal
