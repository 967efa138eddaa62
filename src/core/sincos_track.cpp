#include "ccal/core/sincos_track.hpp"

#include <algorithm>
#include <cstring>
#include <iterator>

#include "cloned_loops.hpp"

namespace ccal {

namespace {

constexpr std::size_t kLanes = lanes::kWidth;
using Lanes = lanes::Doubles;
using lanes::load;
using lanes::store;

// Pairs of whole lanes: angle k turned by h[k] from its anchor's cos c0[k] and sin s0[k], as small_turn and
// next(double) compute it lane by lane (the two polynomials of small_turn side by side, then
// P − (q·P + sin H·R) with R = (sin α₀, −cos α₀)).
CCAL_CLONED void turn_lanes(const double* h, const double* c0, const double* s0, double* cos_out,
                            double* sin_out, std::size_t n) {
  for (std::size_t k = 0; k < n; k += kLanes) {
    const Lanes hv = load<Lanes>(h + k), c = load<Lanes>(c0 + k), s = load<Lanes>(s0 + k);
    const Lanes z = hv * hv;
    Lanes ps = Lanes{} + kTurnSin[0], pq = Lanes{} + kTurnOneMinusCos[0];
    for (std::size_t i = 1; i < std::size(kTurnSin); ++i) {
      ps = ps * z + kTurnSin[i];
      pq = pq * z + kTurnOneMinusCos[i];
    }
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
