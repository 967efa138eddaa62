// The run-mean kernel's batch of trials in SIMD lanes (src/reduction/run_means_batch.cpp) against its
// one-trial path, bit for bit: each lane must take that trial's operations in the same order, whatever the
// trials beside it, so that the Monte Carlo's trial i has the same bits however its trials are batched.
#include <gtest/gtest.h>

#include <random>

#include "ccal/io/config_file.hpp"
#include "ccal/reduction/run_means.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "experiment_support.hpp"

namespace ccal::test {
namespace {

// The batch's means of `trials` (one error vector each) and each trial's means alone, bit for bit.
void expect_batch_is_one_by_one(const RunMeanKernel& kernel, const std::vector<Eigen::VectorXd>& trials,
                                std::size_t runs, const std::string& label) {
  ASSERT_FALSE(trials.empty());
  const auto L = std::size_t(trials.front().size());
  std::vector<double> errors;
  for (const Eigen::VectorXd& e : trials) errors.insert(errors.end(), e.data(), e.data() + e.size());
  std::vector<double> batch(trials.size() * runs);
  RunMeanKernel::Workspace workspace;
  kernel.means(errors, trials.size(), batch, workspace);
  for (std::size_t t = 0; t < trials.size(); ++t) {
    std::vector<double> alone(runs);
    kernel.means(std::span<const double>(errors.data() + t * L, L), alone);
    for (std::size_t r = 0; r < runs; ++r)
      ASSERT_EQ(batch[t * runs + r], alone[r]) << label << ", trial " << t << ", run " << r;
  }
}

TEST(RunMeanKernelBatch, BundledTrialsInLanesAreTheOneTrialMeansBitForBit) {
  // 43 trials (five packs and a partial one) of the bundled tolerances drawn uniformly within ±3 bounds, of
  // four rules mixed: with both drives' ripple, without the main drive's (its coefficients zero), with a
  // mismatch ΔΩ that needs more slow nodes, and one trial whose wobble is beyond the small-angle series (the
  // one-trial path's own loops); some with a rate error Δω whose turns of the weights' harmonics are beyond
  // the small-angle series (turned one by one, as the one-trial path turns them). Each trial's means equal
  // its means alone, bit for bit.
  const Config cfg = bundled_example();
  const Experiment ex = cfg.experiment();
  const CalibrationModel model = calibration_model(cfg);
  const RunMeanKernel kernel(ex.geometry, ex.layout, ex.site, ex.plan.runs, ex.instrument, model.reduction());
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unit(-3.0, 3.0);
  std::vector<Eigen::VectorXd> trials;
  for (int t = 0; t < 43; ++t) {
    Eigen::VectorXd e = cfg.centrifuge.errors;
    for (const Tolerance& tol : cfg.tolerances)
      if (!is_chain_parameter(tol.parameter)) e[tol.parameter] += unit(rng) * tol.bound;
    if (t % 5 == 1)
      for (int k = 0; k < 2; ++k) e[ex.layout.harmonic_index(ch::ripple1, 0, false) + 1 + k] = 0.0;
    if (t % 7 == 3) e[ch::dOmega] = 2e-5;  // Q = 6
    if (t % 6 == 2) e[ch::domega] = 3e-6;  // mΔωT/2 beyond the small-angle series for m ≥ 2
    if (t == 17) e[ex.layout.harmonic_index(ch::dthx3, 0, false)] = 2e-3;
    trials.push_back(e);
  }
  expect_batch_is_one_by_one(kernel, trials, ex.plan.runs.size(), "bundled");
  // A batch of one, and the same trials in reverse order (other neighbours in every pack).
  expect_batch_is_one_by_one(kernel, {trials[4]}, ex.plan.runs.size(), "one trial");
  std::reverse(trials.begin(), trials.end());
  expect_batch_is_one_by_one(kernel, trials, ex.plan.runs.size(), "reversed");
}

class GeneralCentrifugeBatch : public ::testing::TestWithParam<std::tuple<int, bool>> {};

TEST_P(GeneralCentrifugeBatch, TrialsInLanesAreTheOneTrialMeansBitForBit) {
  // Every part of the chain away from the paper's case (as run_means_test.cpp's GeneralCentrifuge): lever
  // arms, a tilted horizontal axis, harmonic orders 0 to 3, Earth rotation, all four mountings in groups of
  // runs of different durations, a fixed-platform run, an instrument with cross terms, a rate term and an
  // IA-rate gain, and a platform phase-locked to the main axis (it follows the main drive's ripple) or on its
  // own loop.
  const auto [order, phase_locked] = GetParam();
  // Runs of two durations: two groups of runs that share their nodes, besides the fixed-platform run.
  Experiment ex = general_centrifuge(order, {200.0, 200.0, 200.0, 237.0, 237.0, 237.0});
  if (phase_locked) ex.geometry.platform_control = PlatformControl::phase_locked;
  ReductionOptions options;
  options.quadrature.fast_nodes = 2 * (3 + order) + 4;
  const RunMeanKernel kernel(ex.geometry, ex.layout, ex.site, ex.plan.runs, ex.instrument, options);
  std::vector<Eigen::VectorXd> trials;
  for (int t = 0; t < 19; ++t) {
    Eigen::VectorXd e = random_errors(ex.layout, 1e-5, unsigned(31 + t));
    e[ch::dOmega] = (t % 3 - 1) * 2e-7;
    trials.push_back(e);
  }
  expect_batch_is_one_by_one(kernel, trials, ex.plan.runs.size(), "order " + std::to_string(order));
}
INSTANTIATE_TEST_SUITE_P(RunMeanKernelBatch, GeneralCentrifugeBatch,
                         ::testing::Combine(::testing::Values(0, 1, 2, 3), ::testing::Bool()));

TEST(RunMeanKernelBatch, RejectsSizesThatDoNotMatch) {
  const Experiment ex = bundled_example().experiment();
  const RunMeanKernel kernel(ex.geometry, ex.layout, ex.site, ex.plan.runs, ex.instrument);
  const auto L = std::size_t(ex.layout.size()), R = ex.plan.runs.size();
  RunMeanKernel::Workspace workspace;
  std::vector<double> errors(3 * L, 0.0), means(3 * R);
  EXPECT_THROW(kernel.means(errors, 2, means, workspace), std::invalid_argument);
  std::vector<double> short_means(3 * R - 1);
  EXPECT_THROW(kernel.means(errors, 3, short_means, workspace), std::invalid_argument);
  kernel.means(errors, 3, means, workspace);  // the right sizes: three error-free trials, equal means
  for (std::size_t r = 0; r < R; ++r) EXPECT_EQ(means[r], means[2 * R + r]);
}

}  // namespace
}  // namespace ccal::test
