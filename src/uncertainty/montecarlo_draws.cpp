// The Monte Carlo's generator and draws (montecarlo_draws.hpp).
#include "montecarlo_draws.hpp"

#include <cmath>

#include "draw_quantiles.hpp"

namespace ccal::mc_draws {
namespace {

constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

// xoshiro256** (Blackman & Vigna, ACM TOMS 47(4), 2021): a 256-bit xor/shift/rotate linear engine with the
// "**" scrambler (multiply by 5, rotate by 7, multiply by 9). The generator of trial i starts from words
// 4i+1 … 4i+4 of the SplitMix64 sequence whose state starts at `key`: distinct trials get distinct words of
// one full-period Weyl sequence, and as mix64 is a bijection the four words are never all zero.
class TrialGenerator {
 public:
  TrialGenerator(std::uint64_t key, std::uint64_t trial) {
    const std::uint64_t base = key + 4 * trial * kGolden;  // arithmetic mod 2⁶⁴
    for (std::uint64_t k = 0; k < 4; ++k) s_[k] = mix64(base + (k + 1) * kGolden);
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  // u = (k + ½)·2⁻⁵², k the top 52 bits: exactly representable, in (0, 1), and 1 − u is on the same grid.
  double uniform() { return (double(next() >> 12) + 0.5) * 0x1p-52; }

 private:
  std::uint64_t s_[4];
};

// F⁻¹ of a distribution of bound 1 (montecarlo.hpp) for n uniforms on the grid above (so that 2u − 1 and u − ½
// are exact and every F⁻¹ is exactly odd about u = ½), in SIMD lanes by IEEE operations alone
// (draw_quantiles.hpp): the same bits everywhere.
void quantiles_of(Distribution d, const double* u, double* x, std::size_t n) {
  switch (d) {
    case Distribution::normal:
      return draws::normal_quantiles(u, x, n);
    case Distribution::uniform:
      for (std::size_t i = 0; i < n; ++i) x[i] = 2.0 * u[i] - 1.0;
      return;
    case Distribution::triangular:
      return draws::triangular_quantiles(u, x, n);
    case Distribution::arcsine:
      return draws::arcsine_quantiles(u, x, n);
  }
}

}  // namespace

SlotPlan plan_slots(const std::vector<Tolerance>& sources) {
  const CorrelationGroups g = correlation_groups(sources);
  return {g.of, g.count, g.named};
}

BatchDrawer::BatchDrawer(const std::vector<Tolerance>& sources, const SlotPlan& plan, const GaussianCopula* copula)
    : sources_(sources), plan_(plan), copula_(copula) {
  for (std::size_t j = 0; j < sources.size(); ++j) of_distribution_[int(sources[j].distribution)].push_back(j);
  if (copula) {
    z_.resize(copula->factor.cols());
    w_.resize(z_.size());
  }
}

void BatchDrawer::draw(std::uint64_t key, std::uint64_t first, std::size_t n, std::vector<double>& draws) {
  const std::size_t n_sources = sources_.size();
  draws.resize(n * n_sources);
  const auto slots = std::size_t(plan_.slots);
  u_.resize(n * slots);
  for (std::size_t t = 0; t < n; ++t) {
    TrialGenerator generator(key, first + t);
    for (std::size_t s = 0; s < slots; ++s) u_[t * slots + s] = generator.uniform();
  }
  if (copula_) {  // z = Φ⁻¹(u) per slot, y = Pᵀ L z (L lower triangular), x = bound · G_D(y_slot)
    scores_.resize(n * slots);
    draws::normal_quantiles(u_.data(), scores_.data(), n * slots);
    for (std::size_t t = 0; t < n; ++t) {
      z_ = Eigen::Map<const Eigen::VectorXd>(scores_.data() + t * slots, Eigen::Index(slots));
      w_.noalias() = copula_->factor.triangularView<Eigen::Lower>() * z_;
      for (std::size_t j = 0; j < n_sources; ++j) {
        const auto row = copula_->row_of_slot[std::size_t(plan_.slot[j])];
        draws[t * n_sources + j] = sources_[j].bound * standard_value_of_score(sources_[j].distribution, w_[row]);
      }
    }
    return;
  }
  // Each distribution's F⁻¹ for all its sources of the whole batch at once, in lanes.
  for (int d = 0; d < kDistributions; ++d) {
    const std::vector<std::size_t>& of = of_distribution_[d];
    const std::size_t m = of.size();
    if (m == 0) continue;
    in_.resize(n * m);
    out_.resize(n * m);
    for (std::size_t t = 0; t < n; ++t)
      for (std::size_t k = 0; k < m; ++k) in_[t * m + k] = u_[t * slots + std::size_t(plan_.slot[of[k]])];
    quantiles_of(Distribution(d), in_.data(), out_.data(), n * m);
    for (std::size_t t = 0; t < n; ++t)
      for (std::size_t k = 0; k < m; ++k) draws[t * n_sources + of[k]] = sources_[of[k]].bound * out_[t * m + k];
  }
}

}  // namespace ccal::mc_draws
