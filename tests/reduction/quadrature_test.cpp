// The spectral run-mean rule (quadrature.hpp, model.md §8) on single harmonics of the fast phase, against
// the closed form of their mean over a run of duration T that ends in a partial revolution:
//     (1/T) ∫₀ᵀ cos(m Ω t) dt = sin(mΩT)/(mΩT),   (1/T) ∫₀ᵀ sin(m Ω t) dt = (1 − cos(mΩT))/(mΩT).
// With M fast nodes the rule is exact for every harmonic m < M/2 and, through the Nyquist term of its weights
// (taken once), for cos(Mθ/2) too; sin(Mθ/2) vanishes at every node and cannot be represented.
#include <gtest/gtest.h>

#include <cmath>

#include "ccal/model/kinematics.hpp"
#include "ccal/reduction/quadrature.hpp"

namespace ccal {
namespace {

double rule_mean(const RunQuadrature<double>& q, int m, bool sine) {
  double sum = 0;
  for (std::size_t n = 0; n < q.nodes.size(); ++n) {
    const double x = m * q.nodes[n].theta1;
    sum += q.weights[n] * (sine ? std::sin(x) : std::cos(x));
  }
  return sum;
}

TEST(SpectralRule, IntegratesEveryHarmonicUpToNyquistExactly) {
  // Ω = 8.85 rad/s, T = 450.3 s: ΩT/2π = 634.2 revolutions, so every harmonic's mean is of order 1/(mΩT)
  // ≈ 1e-4…2.5e-4, not zero. Tolerance 1e-14: round-off of weights that sum to 1 (the Nyquist cosine alone
  // has mean ≈ 1.1e-5 at M = 12, 16, 32; a rule without the Nyquist term gives 0 for it).
  const double rate = 8.85, T = 450.3;
  const Eigen::VectorXd no_errors = Eigen::VectorXd::Zero(ErrorLayout(1).size());
  for (PlatformMode mode : {PlatformMode::fixed, PlatformMode::counter_rotating})
    for (int M : {12, 16, 32}) {
      const RunMotion<double> motion = run_motion<double>(rate, 0.0, 0.4, mode, 0.0, no_errors);
      const RunQuadrature<double> q = run_quadrature<double>(motion, T, mode, 0.0, {M, 0, 1e-16});
      ASSERT_EQ(q.fast_nodes, M);
      for (int m = 0; m <= M / 2; ++m) {
        const double k = m * rate * T;
        const double want_cos = m == 0 ? 1.0 : std::sin(k) / k;
        EXPECT_NEAR(rule_mean(q, m, false), want_cos, 1e-14) << "cos, m = " << m << ", M = " << M;
        if (m < M / 2) {
          const double want_sin = m == 0 ? 0.0 : (1.0 - std::cos(k)) / k;
          EXPECT_NEAR(rule_mean(q, m, true), want_sin, 1e-14) << "sin, m = " << m << ", M = " << M;
        }
      }
      // The Nyquist cosine's mean is not negligible against the tolerance: the check above bites.
      EXPECT_GT(std::abs(std::sin(M / 2 * rate * T) / (M / 2 * rate * T)), 1e-6) << M;
    }
}

}  // namespace
}  // namespace ccal
