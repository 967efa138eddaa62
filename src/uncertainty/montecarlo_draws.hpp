#pragma once
// The Monte Carlo's draws (montecarlo.hpp), private to the library: each trial's generator, and the draws of
// a batch of consecutive trials, computed together so that each distribution's quantiles of the whole batch run
// in SIMD lanes (draw_quantiles.hpp). A trial's draws depend on the seed and its index alone, never on the batch it is
// drawn in: draw_sources (one trial) gives the bits run_monte_carlo uses.
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "ccal/uncertainty/gaussian_copula.hpp"
#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal::mc_draws {

constexpr std::uint64_t kGolden = 0x9E3779B97F4A7C15ULL;  // 2⁶⁴/φ, the SplitMix64 increment

// The SplitMix64 output function (Steele, Lea & Flood, OOPSLA 2014; the variant with the multipliers found by
// D. Stafford, "Better bit mixing", 2011, mix 13): a bijection of 64-bit words with full avalanche.
constexpr std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// Which uniform each source takes: one slot per ungrouped source and one per group, in order of first
// appearance.
struct SlotPlan {
  std::vector<int> slot;  // per source
  int slots = 0;
  int groups = 0;
};
SlotPlan plan_slots(const std::vector<Tolerance>& sources);

// The draws (SI, one per source) of trials first … first + n − 1 of the run keyed `key` (mix64 of the seed),
// trial-major: draws[t · sources + j]. One drawer per thread: it holds the scratch of its batches.
class BatchDrawer {
 public:
  BatchDrawer(const std::vector<Tolerance>& sources, const SlotPlan& plan, const GaussianCopula* copula);
  void draw(std::uint64_t key, std::uint64_t first, std::size_t n, std::vector<double>& draws);

 private:
  const std::vector<Tolerance>& sources_;
  const SlotPlan& plan_;
  const GaussianCopula* copula_;  // partly correlated sources: the scores' factor L; null: independent slots
  static constexpr int kDistributions = 4;  // Distribution's values
  std::vector<std::size_t> of_distribution_[kDistributions];  // the sources of each distribution
  std::vector<double> u_, in_, out_, scores_;
  Eigen::VectorXd z_, w_;
};

}  // namespace ccal::mc_draws
