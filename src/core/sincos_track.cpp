#include "ccal/core/sincos_track.hpp"

#include <algorithm>
#include <cstring>

#include "cloned_loops.hpp"

namespace ccal {

namespace {

// Eight doubles in GCC's and Clang's vector extension (one AVX-512 register, two AVX2 ones): each lane is
// IEEE arithmetic on its own, the scalar operations of next(double) in the same order.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"  // the vectors pass between functions of this file only, inlined
#endif
constexpr std::size_t kLanes = 8;
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));

[[gnu::always_inline]] inline Lanes load(const double* p) {
  Lanes v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store(double* p, const Lanes& v) { std::memcpy(p, &v, sizeof v); }

// Pairs of whole lanes: angle k turned by h[k] from its anchor's cos c0[k] and sin s0[k], as small_turn and
// next(double) compute it lane by lane (the two polynomials of small_turn side by side, then
// P − (q·P + sin H·R) with R = (sin α₀, −cos α₀)).
CCAL_CLONED void turn_lanes(const double* h, const double* c0, const double* s0, double* cos_out,
                            double* sin_out, std::size_t n) {
  for (std::size_t k = 0; k < n; k += kLanes) {
    const Lanes hv = load(h + k), c = load(c0 + k), s = load(s0 + k);
    const Lanes z = hv * hv;
    Lanes ps = Lanes{} + 1.0 / 6227020800, pq = Lanes{} + -1.0 / 479001600;  // 1/13!, −1/12!
    ps = ps * z + -1.0 / 39916800, pq = pq * z + 1.0 / 3628800;
    ps = ps * z + 1.0 / 362880, pq = pq * z + -1.0 / 40320;
    ps = ps * z + -1.0 / 5040, pq = pq * z + 1.0 / 720;
    ps = ps * z + 1.0 / 120, pq = pq * z + -1.0 / 24;
    ps = ps * z + -1.0 / 6, pq = pq * z + 0.5;
    const Lanes sin_h = hv + hv * z * ps, q = z * pq;
    const Lanes minus_c = -c;
    store(cos_out + k, c - (q * c + sin_h * s));
    store(sin_out + k, s - (q * s + sin_h * minus_c));
  }
}

}  // namespace

void SinCosTrack::next(const double* angles, double* cos_out, double* sin_out, std::size_t n) {
  constexpr std::size_t kChunk = 256;
  // Each angle's turn and its anchor's pair, padded to whole lanes with turns of 0 from (1, 0).
  double h[kChunk], c0[kChunk], s0[kChunk], c[kChunk], s[kChunk];
  double anchor = anchor_, anchor_cos = pair_[0], anchor_sin = pair_[1];
  for (std::size_t first = 0; first < n; first += kChunk) {
    const std::size_t m = std::min(kChunk, n - first);
    for (std::size_t k = 0; k < m; ++k) {
      const double angle = angles[first + k];
      if (!(std::abs(angle - anchor) < max_turn_)) {  // as next(double): also for the first angle
        anchor = angle;
        anchor_cos = std::cos(angle);
        anchor_sin = std::sin(angle);
      }
      // An anchor's own turn is 0 (or NaN with it): P − (q·P + sin H·R) with q = sin H = ±0 is P exactly.
      h[k] = angle - anchor;
      c0[k] = anchor_cos;
      s0[k] = anchor_sin;
    }
    const std::size_t padded = (m + kLanes - 1) / kLanes * kLanes;
    for (std::size_t k = m; k < padded; ++k) h[k] = 0, c0[k] = 1, s0[k] = 0;
    turn_lanes(h, c0, s0, c, s, padded);
    std::memcpy(cos_out + first, c, m * sizeof(double));
    std::memcpy(sin_out + first, s, m * sizeof(double));
  }
  anchor_ = anchor;
  pair_ = DoublePair{anchor_cos, anchor_sin};
  rotated_ = DoublePair{anchor_sin, -anchor_cos};
}

}  // namespace ccal
