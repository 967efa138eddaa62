#pragma once
// The tolerance of an error source, as the budget, the Monte Carlo and the allocation read it: a bound, the
// distribution it bounds (GUM terms), a correlation group and a cost (docs/config.md, docs/model.md §10).

#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/options.hpp"

namespace ccal {

// How the tolerance of an error source is distributed (GUM terms).
enum class Distribution {
  normal,      // bound = standard deviation σ
  uniform,     // bound = half-width a: uniform on [−a, a], σ = a/√3
  triangular,  // bound = half-width a: triangular on [−a, a], σ = a/√6
  arcsine,     // bound = amplitude a: a·sin(uniform phase), σ = a/√2 (harmonic amplitudes)
};

std::string_view distribution_name(Distribution d) noexcept;
// The divisor of a bound: σ = bound / divisor(d), i.e. 1 (normal), √3 (uniform), √6 (triangular), √2
// (arcsine). The one table of the distributions' σ: standard_uncertainty and every budget's divisor column
// read it.
double divisor(Distribution d) noexcept;
// Standard deviation of a tolerance with the given bound and distribution: bound / divisor(d).
double standard_uncertainty(double bound, Distribution d) noexcept;

// The correlation groups of a list of sources (Tolerance::group of each, or none at all): sources with the
// same non-empty group share one index, every other source has one of its own; indices 0…count−1 in the
// order of first appearance. The budget, the Monte Carlo and the allocation all draw and add by it.
struct CorrelationGroups {
  std::vector<int> of;  // index of each source
  int count = 0;        // indices in all
  int named = 0;        // of them, named groups
};
CorrelationGroups correlation_groups(const std::vector<std::string>& group_of_each, std::size_t sources);
// The same for a list of sources that carry their group (Tolerance and the results built on it).
template <class Source>
requires requires(const Source& s) { std::string(s.group); }
CorrelationGroups correlation_groups(const std::vector<Source>& sources) {
  std::vector<std::string> group_of_each;
  group_of_each.reserve(sources.size());
  for (const Source& s : sources) group_of_each.push_back(s.group);
  return correlation_groups(group_of_each, sources.size());
}

// Φ⁻¹ of the error function's argument: √2 erf⁻¹(x), x ∈ (−1, 1), in double precision. The normal
// quantile of a probability u is normal_erf_quantile(2u − 1); the coverage factor of a symmetric normal
// interval of probability p is normal_erf_quantile(p).
double normal_erf_quantile(double x);

// The accepted relative cost weight of a tolerance ([tolerances] cost, Tolerance::cost): in an allocation the
// objective Σ cost_s / λ_s stays finite and its ratios meaningful.
inline constexpr OptionRange kToleranceCostRange = OptionRange::between(1e-6, 1e6).e_g("1.0");

// Tolerance of one error parameter, for the error budget.
struct Tolerance {
  int parameter = 0;  // index in the centrifuge's ErrorLayout
  std::string id;     // parameter id, e.g. "dthz5", "dx3_c1"
  double bound = 0;   // SI unit of the parameter (rad, m, rad/s, m/(rad/s)²); meaning set by distribution
  Distribution distribution = Distribution::normal;
  std::string group;  // sources with the same non-empty group are fully correlated (same draw, same sign)
  double cost = 1.0;  // relative cost weight for tolerance allocation, in kToleranceCostRange
  double floor = 0;   // the machine's best achievable bound, SI, 0 < floor ≤ bound; 0: none. The allocation
                      // never tightens the bound below it (scale ≥ floor/bound).
  std::string unit;   // the unit the bound was written in ("um", "arcsec"), for display only; "": SI
};

// A correlation the lab knows between the errors of two tolerances ([[correlations]], docs/config.md): the
// correlation coefficient r ∈ [−1, 1] of the two inputs (JCGM 100 §5.2.2). A group is r = 1 between its
// members.
struct Correlation {
  std::string first, second;  // parameter ids, both in [tolerances]
  double r = 0;
};

// An input of the budget that a test measured (docs/model.md §10.5, §13.3): the calibration statement charges the
// uncertainty of that measurement in place of the input's tolerance, and says so in its table of inputs.
struct MeasuredInput {
  std::string id;                   // its parameter id, a [tolerances] id: domega, dOmega, ripple1_c1, …
  double standard_uncertainty = 0;  // u of the measurement, SI (> 0)
  bool resolved = true;  // false: a ripple harmonic below the fit's resolution, charged as uniform within it
  std::string how;       // what measured it, in words, e.g. "main-axis encoder: rate of each run"
};

}  // namespace ccal
