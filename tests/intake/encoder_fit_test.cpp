// The encoder fit (intake/encoder_fit.hpp) with its harmonics' cos α, sin α turned from sample to sample
// (core/sincos_track.hpp) against the same fit with std::cos, std::sin at every sample, as it was before:
// the turned pairs are within 6.7e-16 of the true ones, a millionth of what the readings' own 1e-9 rad
// rounding puts into them, so the fits agree to far below 1e-12 of each result (1e-12 of the harmonics'
// amplitude for the harmonics, which are noise-sized where the drive has no ripple).
#include "ccal/intake/encoder_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "test_constants.hpp"

namespace ccal::test {
namespace {

// A 2 kHz encoder as the benchmark's log has it: 8.86 rad/s (or −8.86, the counter-rotating platform)
// with a 10 ppm once-per-revolution ripple, read to 1e-9 rad and wrapped to [0, 2π), unwrapped as the
// reducer does; fitted with harmonic order `order`, the pairs turned up to `max_turn` from their anchors.
EncoderFitResult fit_encoder(int order, double max_turn, double rate, int samples) {
  EncoderFit fit(order, max_turn);
  double unwrapped = 0, previous = 0;
  for (int k = 0; k < samples; ++k) {
    const double t = 5e-4 * k, angle = 0.3 + rate * t + 1e-5 * std::sin(rate * t);
    const double reading = std::round(std::fmod(std::fmod(angle, 2 * kPi) + 2 * kPi, 2 * kPi) * 1e9) / 1e9;
    unwrapped = k == 0 ? reading : unwrapped + std::remainder(reading - previous, 2 * kPi);
    previous = reading;
    fit.add(t, unwrapped, reading);
  }
  return fit.result();
}

double norm(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x * x;
  return std::sqrt(s);
}

TEST(EncoderFit, TurnedHarmonicsFitAsStdCosSinDo) {
  for (const double rate : {8.86, -8.86})
    for (const int order : {1, 2}) {
      const EncoderFitResult turned = fit_encoder(order, SinCosTrack::kMaxTurn, rate, 400000);
      const EncoderFitResult exact = fit_encoder(order, 0, rate, 400000);
      for (auto [a, b] : {std::pair{turned.slope, exact.slope},
                          {turned.start, exact.start},
                          {turned.end, exact.end},
                          {turned.rms, exact.rms},
                          {turned.harmonic_sigma, exact.harmonic_sigma}})
        EXPECT_NEAR(a, b, 1e-12 * std::abs(b)) << rate << " " << order;
      ASSERT_EQ(turned.harmonics.size(), std::size_t(2 * order));
      std::vector<double> difference(turned.harmonics.size());
      for (std::size_t i = 0; i < difference.size(); ++i)
        difference[i] = turned.harmonics[i] - exact.harmonics[i];
      EXPECT_LE(norm(difference), 1e-12 * norm(exact.harmonics)) << rate << " " << order;
      EXPECT_NEAR(std::hypot(exact.harmonics[0], exact.harmonics[1]), 1e-5, 1e-8);  // the ripple is there
    }
}

// An angle that is exactly the fit's model, 0.3 + 8.8 τ + C cos α + S sin α with α the wrapped nominal angle
// (the reading), over 10,001 samples: past the 4096 of the reference line and through the 256-sample batches,
// the last one partial. Order 1 (its sums unrolled in registers) and order 2 (the general sums, in memory)
// recover C, S to the angle's own rounding: 45 rad at ε, ~1e-14 rad per sample, so 1e-13 of headroom; the
// second harmonic of order 2 is zero to the same; the line to the same over 5 s.
TEST(EncoderFit, BothSumPathsRecoverAnAngleThatIsTheModel) {
  constexpr double kC = 2e-5, kS = -3e-5;
  for (const int order : {1, 2}) {
    EncoderFit fit(order, 0);
    for (int k = 0; k <= 10000; ++k) {
      const double t = 5e-4 * k, nominal = 0.3 + 8.8 * t;
      const double reading = std::fmod(nominal, 2 * kPi);
      fit.add(t, nominal + kC * std::cos(reading) + kS * std::sin(reading), reading);
    }
    const EncoderFitResult r = fit.result();
    ASSERT_EQ(r.harmonics.size(), std::size_t(2 * order)) << order;
    EXPECT_NEAR(r.harmonics[0], kC, 1e-13) << order;
    EXPECT_NEAR(r.harmonics[1], kS, 1e-13) << order;
    for (std::size_t i = 2; i < r.harmonics.size(); ++i) EXPECT_NEAR(r.harmonics[i], 0, 1e-13) << order;
    EXPECT_NEAR(r.slope, 8.8, 1e-13) << order;
    EXPECT_NEAR(r.start, 0.3, 1e-13) << order;
    EXPECT_LT(r.rms, 1e-13) << order;
    EXPECT_EQ(r.samples, 10001u);
  }
}

}  // namespace
}  // namespace ccal::test
