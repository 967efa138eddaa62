// cos and sin of a slowly moving angle by angle addition (core/sincos_track.hpp) against long double sinl,
// cosl (64-bit mantissa: 2048 times finer than a double's ulp): the Taylor turn to its rounding, the turned
// pairs within kErrorBound over millions of angles, the anchors where the header puts them.
#include "ccal/core/sincos_track.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "portable_uniform.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon() / 2;  // ε = 2⁻⁵³, the unit round-off

TEST(SinCosTrack, SmallTurnIsRoundedOnce) {
  // sin H to ε|H| (the truncated series' rest and the correction's own roundings far below), q = 1 − cos H
  // to 4ε·q, over the whole range of turns, both signs, down to tiny ones. The reference q is 2 sin²(H/2),
  // free of the cancellation in 1 − cos H.
  PortableUniform u{7};
  double worst_sin = 0, worst_q = 0;
  auto check = [&](double h) {
    const SmallTurn t = small_turn(h);
    const long double half = std::sin(0.5L * h), q = 2 * half * half;
    worst_sin = std::max(worst_sin, double(std::abs(t.sin - std::sin((long double)h)) / std::abs(h)));
    worst_q = std::max(worst_q, double(std::abs(t.one_minus_cos - q) / q));
  };
  for (int k = 0; k < 200000; ++k) check((2 * u() - 1) * SinCosTrack::kMaxTurn * (k % 10 == 0 ? 1e-4 : 1.0));
  check(std::nextafter(SinCosTrack::kMaxTurn, 0.0));  // the ends, where the series' rest is largest
  check(-std::nextafter(SinCosTrack::kMaxTurn, 0.0));
  EXPECT_LE(worst_sin, 1.05 * kEps);
  EXPECT_LE(worst_q, 4 * kEps);
}

// The largest error of either component of a SinCosTrack over `n` angles starting at `start`, each step
// drawn by `step`, wrapped to [0, 2π) as an encoder reads them.
template <class Step>
double worst_error(int n, double start, Step step) {
  SinCosTrack track;
  double angle = start, worst = 0;
  for (int k = 0; k < n; ++k) {
    const SinCos p = track.next(angle);
    const long double a = angle;
    worst = std::max({worst, double(std::abs(p.cos - std::cos(a))), double(std::abs(p.sin - std::sin(a)))});
    angle += step(k);
    if (angle >= 2 * kPi) angle -= 2 * kPi;
    if (angle < 0) angle += 2 * kPi;
  }
  return worst;
}

TEST(SinCosTrack, StaysWithinItsBound) {
  // An encoder read at 2 kHz at 8.86 rad/s with a 10 ppm ripple and 1e-9 rad steps of its reading; a random
  // walk of steps up to kMaxTurn/8 (turns of every size, both directions); steps of kMaxTurn/3 (the largest
  // turns), two million angles in all: each component within kErrorBound of the true cos, sin.
  PortableUniform u{11};
  const double encoder = worst_error(1000000, 0.3, [](int k) {
    const double t = 5e-4 * k;
    return std::round((8.86 * 5e-4 + 1e-5 * 8.86 * 5e-4 * std::cos(8.86 * t)) * 1e9) / 1e9;
  });
  const double walk =
      worst_error(500000, 1.0, [&](int) { return (2 * u() - 1) * SinCosTrack::kMaxTurn / 8; });
  const double largest = worst_error(500000, 2.0, [](int) { return -SinCosTrack::kMaxTurn / 3; });
  EXPECT_LE(encoder, SinCosTrack::kErrorBound);
  EXPECT_LE(walk, SinCosTrack::kErrorBound);
  EXPECT_LE(largest, SinCosTrack::kErrorBound);
  // the bound adds up the worst case of every rounding
  RecordProperty("worst_error", fmt::format("{:.3g} {:.3g} {:.3g}", encoder, walk, largest));
}

TEST(SinCosTrack, AnchorsAtTheFirstAngleAndWhereTheTurnWouldReachKMaxTurn) {
  // The anchored pairs are std::cos, std::sin to the bit: the first angle, each angle kMaxTurn or more from
  // the anchor before it (a wrap, a jump, or the sequence having moved on), every angle when the largest turn
  // is 0. The others are turned.
  auto same_bits = [](SinCos p, double a) {
    return std::bit_cast<std::uint64_t>(p.cos) == std::bit_cast<std::uint64_t>(std::cos(a)) &&
           std::bit_cast<std::uint64_t>(p.sin) == std::bit_cast<std::uint64_t>(std::sin(a));
  };
  SinCosTrack track, exact(0);
  int anchors = 0, turned_differ = 0;
  double anchor = 0;
  for (int k = 0; k < 2000; ++k) {
    const double a = 0.1 + 0.0123456789 * k;
    const bool same = same_bits(track.next(a), a);
    if (k == 0 || std::abs(a - anchor) >= SinCosTrack::kMaxTurn) {
      anchor = a;
      ++anchors;
      EXPECT_TRUE(same) << k;
    }
    turned_differ += !same;  // a turned pair may round as std::cos, std::sin do, but not all of them
    EXPECT_TRUE(same_bits(exact.next(a), a)) << k;
  }
  EXPECT_EQ(anchors, 96);  // every 21st angle: 20 steps of 0.0123 rad stay below 1/4 rad
  EXPECT_GT(turned_differ, 0);
  for (const double jump : {6.2, -6.2, SinCosTrack::kMaxTurn, -SinCosTrack::kMaxTurn, 1.0}) {
    SinCosTrack t;
    t.next(0.5);
    t.next(0.51);
    EXPECT_TRUE(same_bits(t.next(0.5 + jump), 0.5 + jump)) << jump;
  }
}

TEST(SinCosTrack, BatchGivesTheOneByOneBits) {
  // The batch's anchors found first and its turns in SIMD lanes: the same pairs, bit for bit, as next(angle)
  // one at a time, and the same state after it. Angles as an encoder reads them (small steps, wraps), jumps
  // beyond the largest turn, repeats, a NaN (a new anchor, its pair NaN), batches of every length around the
  // eight lanes and the 256-sample chunks, and a track that anchors at every angle (max_turn 0).
  PortableUniform u{99};
  for (const double max_turn : {SinCosTrack::kMaxTurn, 0.0}) {
    SinCosTrack one(max_turn), batch(max_turn);
    double angle = 1.0;
    for (int round = 0; round < 300; ++round) {
      const auto n = std::size_t(u() * 600);
      std::vector<double> angles(n), c(n), s(n);
      for (double& a : angles) {
        const double r = u();
        angle += r < 0.02 ? 2.0 : r < 0.05 ? 0.0 : 0.005 * (u() - 0.3);
        if (angle >= 2 * kPi) angle -= 2 * kPi;
        a = r > 0.9995 ? std::numeric_limits<double>::quiet_NaN() : angle;
      }
      batch.next(angles.data(), c.data(), s.data(), n);
      for (std::size_t k = 0; k < n; ++k) {
        const SinCos p = one.next(angles[k]);
        if (std::isnan(angles[k])) {
          ASSERT_TRUE(std::isnan(c[k]) && std::isnan(s[k]));
          continue;
        }
        ASSERT_EQ(std::bit_cast<std::uint64_t>(c[k]), std::bit_cast<std::uint64_t>(p.cos)) << angles[k];
        ASSERT_EQ(std::bit_cast<std::uint64_t>(s[k]), std::bit_cast<std::uint64_t>(p.sin)) << angles[k];
      }
    }
  }
}

}  // namespace
}  // namespace ccal::test
