// One trial's draws alone (draw_sources, montecarlo.hpp): a machine drawn from the stated knowledge, as `ccal
// simulate --draw-truth` and the coverage study draw it. They are the very draws run_monte_carlo makes in that
// trial, bit for bit, with and without correlations (its identity model keeps every trial's inputs). A run that
// takes an earlier run's values (PropagationOptions::earlier_samples) evaluates only its new trials and gives the
// bits of a run that evaluates them all.
#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "monte_carlo_support.hpp"

namespace ccal {
namespace {

using ccal::test::source;

const std::vector<Tolerance> kInputs = {
    source("n", 2.0, Distribution::normal), source("u", 3.0, Distribution::uniform),
    source("t", 1.5, Distribution::triangular), source("a", 0.5, Distribution::arcsine),
    source("g1", 1.0, Distribution::uniform, "g"), source("g2", 0.4, Distribution::normal, "g")};

TEST(MonteCarloDraws, OneTrialsDrawsAreTheMonteCarlosOwn) {
  for (const std::vector<Correlation>& correlations :
       {std::vector<Correlation>{}, std::vector<Correlation>{{"n", "u", 0.6}, {"t", "a", 0.3}}}) {
    PropagationOptions o;
    o.trials = 200;
    o.seed = 7;
    o.threads = 2;
    o.keep_samples = true;
    const MonteCarloDetail mc =
        run_monte_carlo(kInputs, correlations, int(kInputs.size()), {}, ccal::test::identity, o);
    for (std::uint64_t i : {0u, 1u, 57u, 199u}) {
      const std::vector<double> draws = draw_sources(kInputs, correlations, 7, i);
      ASSERT_EQ(draws.size(), kInputs.size());
      for (std::size_t s = 0; s < draws.size(); ++s)
        EXPECT_EQ(draws[s], mc.samples(Eigen::Index(i), Eigen::Index(s))) << "trial " << i << ", " << kInputs[s].id;
    }
    // A group is one draw: its members move together, each by its own bound and distribution.
    const std::vector<double> d = draw_sources(kInputs, correlations, 3);
    EXPECT_GT(d[4] * d[5], 0.0);
  }
  // Another seed, another machine.
  EXPECT_NE(draw_sources(kInputs, {}, 1), draw_sources(kInputs, {}, 2));
}

TEST(MonteCarloDraws, ARunExtendingAnEarlierOneGivesTheBitsOfAWholeRunAndEvaluatesOnlyItsNewTrials) {
  const std::vector<Correlation> correlations = {{"n", "u", 0.6}};
  PropagationOptions o;
  o.seed = 11;
  o.threads = 2;
  o.keep_samples = true;
  o.trials = 300;
  const MonteCarloDetail earlier =
      run_monte_carlo(kInputs, correlations, int(kInputs.size()), {}, ccal::test::identity, o);
  o.trials = 1000;
  const MonteCarloDetail whole =
      run_monte_carlo(kInputs, correlations, int(kInputs.size()), {}, ccal::test::identity, o);
  // The earlier values count the trials a model is called for; one is the engine's own call at zero.
  std::atomic<int> calls = 0;
  const TrialFunction counted = [&calls](std::span<const double> x, std::span<double> y) {
    ++calls;
    ccal::test::identity(x, y);
  };
  o.earlier_samples = &earlier.samples;
  const MonteCarloDetail extended = run_monte_carlo(kInputs, correlations, int(kInputs.size()), {}, counted, o);
  EXPECT_EQ(calls.load(), 1 + 700);
  EXPECT_EQ(extended.trials, 1000u);
  EXPECT_TRUE(extended.samples == whole.samples);
  EXPECT_TRUE(extended.covariance == whole.covariance);
  for (std::size_t s = 0; s < kInputs.size(); ++s) {
    EXPECT_EQ(extended.outputs[s].low_symmetric, whole.outputs[s].low_symmetric) << kInputs[s].id;
    EXPECT_EQ(extended.outputs[s].high_shortest, whole.outputs[s].high_shortest) << kInputs[s].id;
    EXPECT_EQ(extended.outputs[s].mean, whole.outputs[s].mean) << kInputs[s].id;
  }
  // Values that cannot be the first trials of this run are refused: more of them than trials, other outputs.
  o.trials = 200;
  EXPECT_THROW(run_monte_carlo(kInputs, correlations, int(kInputs.size()), {}, counted, o), InputError);
  o.trials = 1000;
  EXPECT_THROW(run_monte_carlo(kInputs, correlations, 2, {}, [](std::span<const double>, std::span<double> y) {
    y[0] = y[1] = 0;
  }, o), InputError);
}

// Trials are drawn in batches (their normal quantiles in SIMD lanes): a trial's draws are its own whatever
// batch, thread or position in its batch it falls in. 1001 trials: the last batch is short, and with 2 threads
// the batches of one thread are not the other's; both with independent and with copula-correlated sources.
TEST(MonteCarloDraws, EveryTrialHasItsOwnBitsForAnyThreadCountAndBatch) {
  for (const std::vector<Correlation>& correlations :
       {std::vector<Correlation>{}, std::vector<Correlation>{{"n", "u", 0.6}, {"t", "a", 0.3}}}) {
    PropagationOptions o;
    o.trials = 1001;
    o.seed = 5;
    o.keep_samples = true;
    o.threads = 1;
    const MonteCarloDetail one =
        run_monte_carlo(kInputs, correlations, int(kInputs.size()), {}, ccal::test::identity, o);
    o.threads = 2;
    const MonteCarloDetail two =
        run_monte_carlo(kInputs, correlations, int(kInputs.size()), {}, ccal::test::identity, o);
    EXPECT_TRUE(one.samples == two.samples);
    for (std::uint64_t i : {31u, 32u, 33u, 1000u}) {  // the ends of batches, the short last one
      const std::vector<double> draws = draw_sources(kInputs, correlations, 5, i);
      for (std::size_t s = 0; s < draws.size(); ++s)
        EXPECT_EQ(draws[s], one.samples(Eigen::Index(i), Eigen::Index(s))) << "trial " << i << ", " << kInputs[s].id;
    }
  }
}

}  // namespace
}  // namespace ccal
