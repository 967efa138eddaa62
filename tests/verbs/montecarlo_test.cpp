// verbs::monte_carlo in-process (JCGM 101, docs/model.md §10.2): the propagated distribution of the
// paper's set-up against the LPU of verbs::budget (mean and standard deviation within their sampling errors),
// the budget it validates against being that budget, a seed giving the same bits on any thread count, and
// the options' errors naming the option.
#include "ccal/verbs/montecarlo.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/verbs/budget.hpp"
#include "verbs_support.hpp"

namespace ccal::test {
namespace {

constexpr std::int64_t kTrials = 20000;

verbs::MonteCarloResult run(int threads) {
  verbs::MonteCarloOptions o;
  o.propagation.trials = kTrials;
  o.propagation.seed = 7;
  o.propagation.threads = threads;
  return verbs::monte_carlo(load_config(kPaperConfigPath), o);
}

TEST(MonteCarloVerb, AgreesWithTheLpuWithinTheSamplingError) {
  const verbs::MonteCarloResult r = run(2);
  const verbs::BudgetResult lpu = verbs::budget(load_config(kPaperConfigPath));
  EXPECT_EQ(r.monte_carlo.trials, std::uint64_t(kTrials));
  ASSERT_EQ(r.monte_carlo.outputs.size(), lpu.budget.coefficients.size());
  // The LPU the result validates against is the budget's, to the bit.
  EXPECT_EQ(r.budget.standard_uncertainty, lpu.budget.standard_uncertainty);
  for (std::size_t k = 0; k < r.monte_carlo.outputs.size(); ++k) {
    const OutputSummary& out = r.monte_carlo.outputs[k];
    const double u = lpu.budget.standard_uncertainty[Eigen::Index(k)];
    SCOPED_TRACE(out.name);
    EXPECT_EQ(out.name, lpu.budget.coefficients[k]);
    EXPECT_EQ(out.lpu_std, u);
    // The output is a sum of 52 independent sources, close to normal: the standard deviation's relative
    // sampling error is 1/√(2M) = 0.5 % and the mean's u/√M; 5 of each. The model is linear to ~1e-3 in
    // these tolerances (the §8 validation passes), far inside.
    EXPECT_NEAR(out.std_dev / u, 1.0, 5 / std::sqrt(2.0 * kTrials));
    EXPECT_NEAR(out.mean, out.estimate, 5 * u / std::sqrt(double(kTrials)));
    // Deviations of the coefficients from the error-free identification: the estimate is 0 to round-off of
    // the coefficient (the model at zero draws is the truth); 1e-9 u leaves room for the fit's round-off.
    EXPECT_NEAR(out.estimate, 0.0, 1e-9 * u);
    // The symmetric 95 % interval of a near-normal output spans ±1.96 u: within 5 % (its ends' sampling
    // error, interval_end_std_error, is ~1 % of u at this M).
    EXPECT_NEAR((out.high_symmetric - out.low_symmetric) / (2 * 1.959963984540054 * u), 1.0, 0.05);
  }
}

TEST(MonteCarloVerb, ASeedGivesTheSameBitsOnOneAndTwoThreads) {
  const verbs::MonteCarloResult one = run(1), two = run(2);
  for (std::size_t k = 0; k < one.monte_carlo.outputs.size(); ++k) {
    EXPECT_EQ(one.monte_carlo.outputs[k].mean, two.monte_carlo.outputs[k].mean) << k;
    EXPECT_EQ(one.monte_carlo.outputs[k].std_dev, two.monte_carlo.outputs[k].std_dev) << k;
    EXPECT_EQ(one.monte_carlo.outputs[k].low_shortest, two.monte_carlo.outputs[k].low_shortest) << k;
  }
}

TEST(MonteCarloVerb, BadOptionsNameTheOption) {
  const Config config = load_config(kPaperConfigPath);
  auto message = [&](verbs::MonteCarloOptions o) -> std::string {
    try {
      verbs::monte_carlo(config, o);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  verbs::MonteCarloOptions trials, p, digits;
  trials.propagation.trials = 1;  // below the least M of 2 (a negative count is not an unsigned value)
  p.propagation.coverage_probability = 1.5;
  digits.propagation.digits = 9;
  // The library names the field (an OptionError); each front end words it with its own name of the option.
  EXPECT_EQ(message(trials).rfind("trials: 1 is out of range; accepted: 2 to 1000000000", 0), 0u) << message(trials);
  EXPECT_EQ(message(p).rfind("coverage_probability: 1.5 ", 0), 0u) << message(p);
  EXPECT_EQ(message(digits).rfind("digits: 9 ", 0), 0u) << message(digits);
  Config empty = config;
  empty.tolerances.clear();
  verbs::MonteCarloOptions small;
  small.propagation.trials = 100;
  EXPECT_NE(message(small).find("no error"), std::string::npos);
  EXPECT_THROW(verbs::monte_carlo(empty, small), InputError);
}

}  // namespace
}  // namespace ccal::test
