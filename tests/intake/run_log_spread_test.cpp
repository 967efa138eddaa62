// One wild value among a log's samples (src/intake/run_log_spread.cpp): found where it is, beyond 20 standard
// deviations of the others and beyond its floor, and never in a steady run's noise, ripple or drift.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../../src/intake/run_log_spread.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

using detail::SampleSpread;

TEST(SampleSpread, NoiseRippleAndDriftAreNoWildValue) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.88, 0.002);
  SampleSpread normal, ripple, drift;
  for (int k = 0; k < 100000; ++k) {
    normal.add(noise(rng), k + 2, 0);
    ripple.add(0.88 + 0.3 * std::sin(2 * kPi * k / 86.0), k + 2, 0);
    drift.add(0.88 + 1e-3 * k, k + 2, 0);
  }
  EXPECT_FALSE(normal.wild());
  EXPECT_FALSE(ripple.wild());
  EXPECT_FALSE(drift.wild());
}

TEST(SampleSpread, OneWildValueIsFoundAtItsLineAgainstTheOthers) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.88, 0.002);
  SampleSpread lost_digit, near;
  for (int k = 0; k < 6000; ++k) {
    const double x = noise(rng);
    lost_digit.add(k == 97 ? 87.9 : x, k + 2, 0);  // a decimal point lost: 0.879 read as 87.9
    near.add(k == 97 ? 0.88 + 15 * 0.002 : x, k + 2, 0);
  }
  const auto w = lost_digit.wild();
  ASSERT_TRUE(w);
  EXPECT_EQ(w->line, 99);
  EXPECT_EQ(w->value, 87.9);
  // The others' mean and standard deviation without it: the sample's, to its sampling error (0.002/√6000
  // for the mean, 0.002/√12000 relative for the deviation: 5 of each).
  EXPECT_NEAR(w->others_mean, 0.88, 5 * 0.002 / std::sqrt(6000.0));
  EXPECT_NEAR(w->others_sd, 0.002, 5 * 0.002 / std::sqrt(12000.0));
  EXPECT_NEAR(w->departure, 87.9 - w->others_mean, 1e-12);
  // 15 standard deviations is a rare reading, not a wild one.
  EXPECT_FALSE(near.wild());
}

TEST(SampleSpread, AValueWithinItsFloorIsNoWildValue) {
  // A steady count of 637 counts a step, once 638: beyond 20 standard deviations of the others (all 637), but
  // within the floor of 10 counts; 700 is beyond both.
  SampleSpread steady, glitch;
  for (int k = 0; k < 1000; ++k) {
    steady.add(k == 500 ? 638 : 637, k + 3, 10);
    glitch.add(k == 999 ? 700 : 637, k + 3, 10);
  }
  EXPECT_FALSE(steady.wild());
  const auto w = glitch.wild();
  ASSERT_TRUE(w);
  EXPECT_EQ(w->line, 1002);
  EXPECT_EQ(w->others_sd, 0);
  // A floor for every value (an output's resolution) holds as the value's own does.
  SampleSpread coarse;
  for (int k = 0; k < 1000; ++k) coarse.add(k == 500 ? 0.881 : 0.880, k + 2, 0);
  EXPECT_TRUE(coarse.wild());
  EXPECT_FALSE(coarse.wild(10 * 0.001));
  // Fewer than three values have no others to be set against.
  SampleSpread two;
  two.add(1, 2, 0);
  two.add(1e6, 3, 0);
  EXPECT_FALSE(two.wild());
}

}  // namespace
}  // namespace ccal::test
