#pragma once
// cos α and sin α of a sequence of angles that move by small steps (an encoder read many times per
// revolution), mostly without calling cos and sin: each sample's pair is the previous one turned by the step
// h = αₙ − αₙ₋₁ (angle addition),
//     cos αₙ = cos αₙ₋₁ − (q cos αₙ₋₁ + sin h · sin αₙ₋₁),
//     sin αₙ = sin αₙ₋₁ − (q sin αₙ₋₁ − sin h · cos αₙ₋₁),     q = 1 − cos h,
// with sin h and q from their Taylor series (small_turn). Written as the pair less a correction of size |h|,
// each turn rounds the pair once (ε) and the correction (~2|h|ε); the pair is anchored — taken from std::cos
// and std::sin — at the first sample, after a step beyond kMaxStep (a wrap to the other end of [0, 2π), a
// gap), and after kAnchorInterval turns, so that these roundings add up over at most kAnchorInterval turns.
//
// Error bound (ε = 2⁻⁵³, |h| ≤ 1/16), for the error vector e = (cos, sin) computed − true: at an anchor
// |e| ≤ 2√2 ε (std::cos, std::sin within one ulp, ≤ 2ε, of the true values). A turn is a rotation up to
// O(ε), so it keeps |e|, and adds at most ε (the final roundings) + 2√2·0.065ε (the correction's products
// and sum) + 2ε|h| (sin h rounded, and h = αₙ − αₙ₋₁ itself rounded) + 4ε·q (q rounded) < 1.35ε. So each
// component is within kErrorBound = (3 + 1.35·kAnchorInterval)·ε ≈ 2.7e-15 of the true cos αₙ, sin αₙ, where
// std::cos, std::sin give them to 2.2e-16. An encoder's angle is read to ~1e-9 rad (a 32-bit encoder's step):
// its cos and sin are uncertain by 1e-9, six orders above this bound.
#include <cmath>
#include <limits>

namespace ccal {

struct SinCos {
  double cos = 1;
  double sin = 0;
};

// sin h and q = 1 − cos h for |h| ≤ SinCosTrack::kMaxStep by their Taylor series, with z = h²:
//   sin h = h − h³/3! + h⁵/5! − h⁷/7! + h⁹/9!   (the next term, h¹¹/11!, is below 2e-21 ≪ ε|h|),
//   q     = z/2! − z²/4! + z³/6! − z⁴/8!        (the next term, h¹⁰/10!, is below 3e-19 ≪ ε).
// sin h is h plus a correction below h³/6, rounded once (to ε|h|, and the correction's own roundings far
// below); q is z times a sum near 1/2, three roundings (to 3ε·q).
struct SmallTurn {
  double sin = 0;
  double one_minus_cos = 0;
};
inline SmallTurn small_turn(double h) {
  const double z = h * h;
  const double sin = h + h * z * (-1.0 / 6 + z * (1.0 / 120 + z * (-1.0 / 5040 + z * (1.0 / 362880))));
  const double q = z * (0.5 + z * (-1.0 / 24 + z * (1.0 / 720 + z * (-1.0 / 40320))));
  return {sin, q};
}

class SinCosTrack {
 public:
  static constexpr double kMaxStep = 0.0625;  // rad: 2 kHz logs of joints up to 125 rad/s
  static constexpr int kAnchorInterval = 16;  // turns between anchors
  static constexpr double kErrorBound =
      (3 + 1.35 * kAnchorInterval) * std::numeric_limits<double>::epsilon() / 2;

  // max_turns: turns between anchors (0: every pair from std::cos and std::sin).
  explicit SinCosTrack(int max_turns = kAnchorInterval) : max_turns_(max_turns) {}

  // cos and sin of the next angle of the sequence [rad].
  SinCos next(double angle) {
    const double h = angle - angle_;
    if (turns_ < max_turns_ && std::abs(h) <= kMaxStep) {  // false for the first angle: h is NaN
      const SmallTurn t = small_turn(h);
      const double c = pair_.cos, s = pair_.sin;
      pair_.cos = c - (t.one_minus_cos * c + t.sin * s);
      pair_.sin = s - (t.one_minus_cos * s - t.sin * c);
      ++turns_;
    } else {
      pair_.cos = std::cos(angle);
      pair_.sin = std::sin(angle);
      turns_ = 0;
    }
    angle_ = angle;
    return pair_;
  }

 private:
  int max_turns_;
  int turns_ = 0;  // since the last anchor
  double angle_ = std::numeric_limits<double>::quiet_NaN();
  SinCos pair_;
};

}  // namespace ccal
