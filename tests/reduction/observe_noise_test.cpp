// Simulated measurement noise of the run means (observe.hpp, add_output_noise), against its closed forms:
// white output noise of density N gives a run mean with variance N²/T; an integrated output counted in whole
// steps q (e.g. a PIGA's pulse weight) gives a mean off by a uniform error of width q/T, variance (q/T)²/12,
// never beyond ±q/(2T). Checked over many seeds within the sampling error of a variance estimate.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ccal/reduction/observe.hpp"
#include "experiment_support.hpp"

namespace ccal::test {
namespace {

// The paper's six runs with durations 100, 250, …, 850 s, so that the 1/T law is visible.
Experiment noisy_experiment(double density, double quantum) {
  Experiment ex = paper_experiment(false);
  for (std::size_t j = 0; j < ex.plan.runs.size(); ++j) ex.plan.runs[j].duration = 100.0 + 150.0 * double(j);
  ex.instrument.noise_density = density;
  ex.instrument.quantum = quantum;
  return ex;
}

// The noise added to zero run means, for `seeds` seeds, as deviations per run (rows) and seed (columns).
Eigen::MatrixXd noise_samples(const Experiment& ex, int seeds) {
  const auto n = Eigen::Index(ex.plan.runs.size());
  Eigen::MatrixXd d(n, seeds);
  for (int s = 0; s < seeds; ++s) {
    Observations<double> obs;
    obs.output = Eigen::VectorXd::Zero(n);
    add_output_noise(obs, ex, std::uint64_t(1000 + s));
    d.col(s) = obs.output;
  }
  return d;
}

TEST(SimulatedNoise, QuantisedOutputErrsUniformlyByQOverT) {
  // q = 1e-4 rad (a PIGA pulse weight of ≈ 20 arcsec). 4000 seeds × 6 runs. Each deviation must lie within
  // ±q/(2T) (exactly: round-off margin 1e-12 relative). The variance of all 24 000 deviations, each divided
  // by its (q/T)²/12, is 1 within sampling error: a uniform variable has kurtosis 1.8, so the sample variance
  // has relative standard error √(0.8/n) = 0.58 %: 5 of them, 2.9 %. Per run (n = 4000): 1.4 %, 5 of them 7
  // %. A noise of width q instead of q/T would be 100–850 times too wide.
  const double q = 1e-4;
  const Experiment ex = noisy_experiment(0.0, q);
  const int seeds = 4000;
  const Eigen::MatrixXd d = noise_samples(ex, seeds);
  double pooled = 0;
  for (Eigen::Index j = 0; j < d.rows(); ++j) {
    const double T = ex.plan.runs[std::size_t(j)].duration;
    const double var = std::pow(q / T, 2) / 12;
    EXPECT_LE(d.row(j).cwiseAbs().maxCoeff(), q / (2 * T) * (1 + 1e-12)) << "run " << j;
    const double run_var = d.row(j).squaredNorm() / seeds;  // known mean 0
    EXPECT_NEAR(run_var / var, 1.0, 5 * std::sqrt(0.8 / seeds)) << "run " << j;
    EXPECT_NEAR(d.row(j).mean(), 0.0, 5 * std::sqrt(var / seeds)) << "run " << j;
    pooled += run_var / var;
  }
  pooled /= double(d.rows());
  EXPECT_NEAR(pooled, 1.0, 5 * std::sqrt(0.8 / (seeds * double(d.rows()))));
}

TEST(SimulatedNoise, WhiteNoiseMeanHasVarianceNSquaredOverT) {
  // N = 2e-3 rad/s/√Hz: σ = N/√T. A normal sample variance has relative standard error √(2/n): 0.91 % pooled
  // over 24 000 deviations (5 of them: 4.6 %), 2.2 % per run (5 of them: 11 %). With both noises on, the
  // variances add.
  const double N = 2e-3, q = 1e-4;
  const int seeds = 4000;
  for (bool with_quantum : {false, true}) {
    const Experiment ex = noisy_experiment(N, with_quantum ? q : 0.0);
    const Eigen::MatrixXd d = noise_samples(ex, seeds);
    double pooled = 0;
    for (Eigen::Index j = 0; j < d.rows(); ++j) {
      const double T = ex.plan.runs[std::size_t(j)].duration;
      const double var = N * N / T + (with_quantum ? std::pow(q / T, 2) / 12 : 0.0);
      const double run_var = d.row(j).squaredNorm() / seeds;
      EXPECT_NEAR(run_var / var, 1.0, 5 * std::sqrt(2.0 / seeds)) << "run " << j;
      pooled += run_var / var;
    }
    pooled /= double(d.rows());
    EXPECT_NEAR(pooled, 1.0, 5 * std::sqrt(2.0 / (seeds * double(d.rows())))) << with_quantum;
  }
}

TEST(SimulatedNoise, SameSeedSameNoiseAndNoneWithoutNoise) {
  const Experiment ex = noisy_experiment(2e-3, 1e-4);
  EXPECT_EQ(noise_samples(ex, 3), noise_samples(ex, 3));
  EXPECT_TRUE(noise_samples(noisy_experiment(0.0, 0.0), 3).isZero(0.0));
}

}  // namespace
}  // namespace ccal::test
