#pragma once
// cos α and sin α of a sequence of angles that move by small steps (an encoder read many times per
// revolution), mostly without calling cos and sin: each angle's pair is the pair of an earlier angle of the
// sequence, the anchor α₀, turned by H = α − α₀ (angle addition),
//     cos α = cos α₀ − (q cos α₀ + sin H · sin α₀),
//     sin α = sin α₀ − (q sin α₀ − sin H · cos α₀),     q = 1 − cos H,
// with sin H and q from their Taylor series (small_turn). The anchor's pair is std::cos and std::sin of it;
// an angle kMaxTurn or more from the anchor (a wrap to the other end of [0, 2π), a gap, or the sequence
// having moved on) becomes the next anchor. Each pair is one turn from an anchor: no error accumulates along
// the sequence, and the turns of different angles do not wait for each other.
//
// Error bound (ε = 2⁻⁵³, |H| < 1/4), for the error vector e = (cos, sin) computed − true: the anchor's pair
// is within one ulp of the true one in each component, |e| ≤ √2·2ε; a turn, a rotation up to O(ε), keeps
// |e| and adds at most ε (the final roundings) + √2·2ε·(1/32 + 1/4) (the correction's products and sum) +
// 2ε|H| (sin H rounded, and H = α − α₀ itself rounded) + 4ε·q (q rounded) < 2.4ε. So each component is
// within kErrorBound = 6ε ≈ 6.7e-16 of the true cos α, sin α, where std::cos, std::sin give them to
// 1.1e-16. An encoder's angle is read to ~1e-9 rad (a 32-bit encoder's step): its cos and sin are uncertain
// by 1e-9, six orders above this bound.
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>

namespace ccal {

struct SinCos {
  double cos = 1;
  double sin = 0;
};

// Two doubles operated on together (GCC's and Clang's vector extension; SSE2 on x86-64): each lane is IEEE
// arithmetic on its own, the same as the scalar operations.
using DoublePair = double __attribute__((vector_size(2 * sizeof(double))));

// sin H and q = 1 − cos H for |H| < SinCosTrack::kMaxTurn by their Taylor series, with z = H²:
//   sin H = H + H·z·(−1/3! + z/5! − z²/7! + z³/9! − z⁴/11! + z⁵/13!)   (the rest, below H¹⁵/15!, is 1e-21),
//   q     = z·(1/2! − z/4! + z²/6! − z³/8! + z⁴/10! − z⁵/12!)         (the rest, below H¹⁴/14!, is 5e-20),
// the two polynomials in z evaluated together (Horner, a pair of coefficients at each step). sin H is H plus
// a correction below H³/6, rounded once (to ε|H|, the correction's own roundings far below); q is z times a
// sum near 1/2, a few roundings (to 4ε·q).
struct SmallTurn {
  double sin = 0;
  double one_minus_cos = 0;
};
// The two polynomials' coefficients, the highest first (also turned eight at a time, sincos_track.cpp).
inline constexpr double kTurnSin[] = {1.0 / 6227020800, -1.0 / 39916800, 1.0 / 362880,
                                      -1.0 / 5040,      1.0 / 120,       -1.0 / 6};
inline constexpr double kTurnOneMinusCos[] = {-1.0 / 479001600, 1.0 / 3628800, -1.0 / 40320,
                                              1.0 / 720,        -1.0 / 24,     0.5};
inline SmallTurn small_turn(double h) {
  const double z = h * h;
  DoublePair p{kTurnSin[0], kTurnOneMinusCos[0]};
  for (std::size_t i = 1; i < std::size(kTurnSin); ++i)
    p = p * z + DoublePair{kTurnSin[i], kTurnOneMinusCos[i]};
  return {h + h * z * p[0], z * p[1]};
}

class SinCosTrack {
 public:
  static constexpr double kMaxTurn = 0.25;  // rad: 2 kHz logs anchor every 57 samples at 8.86 rad/s
  static constexpr double kErrorBound = 6 * std::numeric_limits<double>::epsilon() / 2;

  // max_turn: the largest turn from an anchor (0: every pair from std::cos and std::sin).
  explicit SinCosTrack(double max_turn = kMaxTurn) : max_turn_(max_turn) {}

  // cos and sin of the next angle of the sequence [rad].
  SinCos next(double angle) {
    const double h = angle - anchor_;
    if (!(std::abs(h) < max_turn_)) {  // also for the first angle: h is NaN
      anchor_ = angle;
      const double c = std::cos(angle), s = std::sin(angle);
      pair_ = DoublePair{c, s};
      rotated_ = DoublePair{s, -c};
      return {c, s};
    }
    // (cos α, sin α) = P − (q·P + sin H·R) for P = (cos α₀, sin α₀), R = (sin α₀, −cos α₀)
    const SmallTurn t = small_turn(h);
    const DoublePair turned = pair_ - (t.one_minus_cos * pair_ + t.sin * rotated_);
    return {turned[0], turned[1]};
  }
  // The pairs of n angles, the same bits as next() gives them one by one, into cos_out[k], sin_out[k]: the
  // anchors found first in order (a comparison per angle), then the turns eight at a time in SIMD lanes
  // (sincos_track.cpp).
  void next(const double* angles, double* cos_out, double* sin_out, std::size_t n);

 private:
  double max_turn_;
  double anchor_ = std::numeric_limits<double>::quiet_NaN();
  DoublePair pair_{1, 0}, rotated_{0, -1};  // the anchor's P and R
};

}  // namespace ccal
