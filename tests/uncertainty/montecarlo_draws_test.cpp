// One trial's draws alone (draw_sources, montecarlo.hpp): a machine drawn from the stated knowledge, as `ccal
// simulate --draw-truth` and the coverage study draw it. They are the very draws run_monte_carlo makes in that
// trial, bit for bit, with and without correlations (its identity model keeps every trial's inputs).
#include <gtest/gtest.h>

#include <string>
#include <vector>

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
    MonteCarloOptions o;
    o.trials = 200;
    o.seed = 7;
    o.threads = 2;
    o.keep_samples = true;
    const MonteCarloResult mc =
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

}  // namespace
}  // namespace ccal
