#pragma once
// The coverage convention of every expanded uncertainty ccal states (docs/model.md §10.4): U = k u, and k
// comes from one coverage probability p (default 95 %) by the method that fits the quantity:
//   normal       the LPU total of the tolerances (ν = ∞): k = Φ⁻¹((1 + p)/2)             (JCGM 100 G.1.3)
//   student_t    a statement with a Type A part: k = t_{(1+p)/2}(⌊ν_eff⌋)              (G.3, G.4.1 note 1)
//   monte_carlo  the probabilistically symmetric 100p % interval of the trials         (JCGM 101 §7.7)
//   stated       a coverage factor k given by the user (e.g. k = 2 by contract); its p is that of a normal
//                quantity, 2Φ(k) − 1, and is printed as such.
// Every verb takes the same option, coverage_probability, so the same tolerances give the same U by the same
// method in `budget`, `allocate`, `design`, `report`, the library and Python.

#include <optional>
#include <string>
#include <string_view>

namespace ccal {

inline constexpr double kDefaultCoverageProbability = 0.95;
inline constexpr std::string_view kDefaultCoverageProbabilityText = "0.95";  // as a message shows it
// normal_coverage_factor(kDefaultCoverageProbability) as it computes it (1 ulp below the nearest double of
// Φ⁻¹(0.975)), for the defaults of structs; a test checks that the two are equal.
inline constexpr double kDefaultCoverageFactor = 1.9599639845400538;

enum class CoverageMethod { normal, student_t, monte_carlo, stated };

// "normal", "Student t", "Monte Carlo", "stated k": how a U was obtained, as outputs name it.
std::string_view coverage_method_name(CoverageMethod method);

// k_p = Φ⁻¹((1 + p)/2): the coverage factor of a normal quantity for p in (0, 1) (InputError otherwise).
double normal_coverage_factor(double p);
// 2Φ(k) − 1: the coverage probability of ±k u for a normal quantity, k > 0.
double normal_coverage_probability(double k);
// 2 F_t(k; ⌊ν⌋) − 1: the coverage probability of ±k u for a quantity of Student's t at ⌊ν⌋ degrees of freedom
// (ν ≥ 1; the normal's for ν = ∞), k > 0. Throws std::invalid_argument otherwise.
double student_coverage_probability(double k, double dof);
// k for coverage probability p in (0, 1) at ν degrees of freedom: Student's t quantile at (1 + p)/2 for
// ⌊ν⌋ (ν ≥ 1), normal_coverage_factor(p) for ν = ∞. Throws std::invalid_argument for p outside (0, 1) or
// ν < 1.
double student_coverage_factor(double p, double dof);

// The k and p of an expanded uncertainty and how they were obtained.
struct Coverage {
  double probability = kDefaultCoverageProbability;  // p
  double factor = 0;                                  // k
  CoverageMethod method = CoverageMethod::normal;
};

// The coverage of a normal quantity (an LPU total) at probability p, or at the stated factor k when given
// (then p = normal_coverage_probability(k) and the method is `stated`).
Coverage normal_coverage(double p, std::optional<double> stated_factor = std::nullopt);

// "k = 1.96, p = 95 %" (the method named after it when not normal: "k = 2 (stated), p = 95.45 %"), the
// words every output puts beside a U.
std::string coverage_text(const Coverage& coverage);

}  // namespace ccal
