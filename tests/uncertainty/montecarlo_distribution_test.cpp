// The kept Monte Carlo distribution: the samples are the trials' outputs in trial order, the histogram
// counts them, the interval ends' sampling error is the closed form for a normal output, and the diagnosis
// of a failed validation follows its definition.
#include <gtest/gtest.h>

#include <boost/math/distributions/normal.hpp>
#include <cmath>

#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "monte_carlo_support.hpp"

namespace ccal::test {
namespace {

Tolerance normal_source(double sigma) {
  Tolerance t;
  t.id = "x";
  t.bound = sigma;
  t.distribution = Distribution::normal;
  return t;
}

using ccal::test::identity;

TEST(MonteCarloDistribution, SamplesHistogramAndEndErrorOfANormalOutput) {
  const double sigma = 2.0, M = 200000;
  PropagationOptions o;
  o.trials = std::uint64_t(M);
  o.seed = 11;
  o.keep_samples = true;
  o.histogram_bins = 40;
  const MonteCarloDetail r = run_monte_carlo({normal_source(sigma)}, 1, {"y"}, identity, o);
  ASSERT_EQ(r.samples.rows(), Eigen::Index(M));
  ASSERT_EQ(r.samples.cols(), 1);
  // The kept values give the reported mean and standard deviation (computed here in long double).
  long double s = 0, q = 0;
  for (Eigen::Index i = 0; i < r.samples.rows(); ++i) s += r.samples(i, 0);
  const long double mean = s / M;
  for (Eigen::Index i = 0; i < r.samples.rows(); ++i)
    q += (r.samples(i, 0) - mean) * (r.samples(i, 0) - mean);
  const OutputSummary& y = r.outputs[0];
  EXPECT_NEAR(double(mean), y.mean, 1e-13 * sigma);  // rounding of two summation orders
  EXPECT_NEAR(std::sqrt(double(q / (M - 1))), y.std_dev, 1e-13 * sigma);
  // Histogram: 40 bins from the smallest to the largest value, every trial counted once; the central bins of
  // a normal sample hold about M·w·φ(x)/σ (binomial: within 5 standard deviations).
  ASSERT_EQ(y.histogram.counts.size(), 40u);
  EXPECT_EQ(y.histogram.lowest, r.samples.minCoeff());
  EXPECT_EQ(y.histogram.highest, r.samples.maxCoeff());
  std::uint64_t total = 0;
  for (auto c : y.histogram.counts) total += c;
  EXPECT_EQ(total, std::uint64_t(M));
  const boost::math::normal n(0.0, sigma);
  const double w = y.histogram.bin_width();
  for (std::size_t b = 0; b < 40; ++b) {
    const double x0 = y.histogram.lowest + w * double(b);
    const double p = boost::math::cdf(n, x0 + w) - boost::math::cdf(n, x0);
    EXPECT_NEAR(double(y.histogram.counts[b]), M * p, 5 * std::sqrt(M * p * (1 - p)) + 1) << b;
  }
  // Sampling error of the 2.5 % quantile of a normal output: σ √(α(1 − α)/M) / φ(z_α) = 2.671 σ/√M. The
  // order-statistic estimate from the ~2k values around the end has a relative error of about 1/√k
  // (k = √(Mα) ≈ 70 here): within 40 %.
  const double alpha = 0.025, z = 1.959963984540054;
  const double closed_form =
      sigma * std::sqrt(alpha * (1 - alpha) / M) / boost::math::pdf(boost::math::normal(), z);
  EXPECT_NEAR(y.interval_end_std_error, closed_form, 0.4 * closed_form);
}

TEST(MonteCarloDistribution, NoSamplesUnlessAsked) {
  PropagationOptions o;
  o.trials = 100;
  const MonteCarloDetail r = run_monte_carlo({normal_source(1)}, 1, {"y"}, identity, o);
  EXPECT_EQ(r.samples.size(), 0);
  o.histogram_bins = 0;
  EXPECT_THROW(run_monte_carlo({normal_source(1)}, 1, {"y"}, identity, o), InputError);
}

TEST(MonteCarloDistribution, SamplesAreTheSameForAnyThreadCount) {
  PropagationOptions o;
  o.trials = 5000;
  o.keep_samples = true;
  o.threads = 1;
  const MonteCarloDetail one = run_monte_carlo({normal_source(1)}, 1, {"y"}, identity, o);
  o.threads = 2;
  const MonteCarloDetail two = run_monte_carlo({normal_source(1)}, 1, {"y"}, identity, o);
  EXPECT_TRUE(one.samples == two.samples);
}

TEST(MonteCarloDistribution, DiagnosisOfAFailedValidation) {
  OutputSummary s;
  s.has_lpu = true;
  s.validated = false;
  s.validation_delta = 1e-5;
  s.d_low = 2e-5;
  s.d_high = 1.2e-5;
  s.interval_end_std_error = 0.5e-5;
  // Excess 1e-5 = 2 standard errors: sampling explains it; M' = 10⁴ (3·0.5e-5/1e-5)² = 22 500.
  ValidationDiagnosis d = validation_diagnosis(s, 10000);
  EXPECT_DOUBLE_EQ(d.excess, 1e-5);
  EXPECT_DOUBLE_EQ(d.excess_in_std_errors, 2.0);
  EXPECT_TRUE(d.explained_by_sampling);
  EXPECT_EQ(d.trials_needed, 23000u);  // 22 500 rounded up to 2 significant digits
  // Excess 4 standard errors: not explained.
  s.d_low = 3e-5;
  d = validation_diagnosis(s, 10000);
  EXPECT_FALSE(d.explained_by_sampling);
  // Validated: nothing to explain.
  s.validated = true;
  s.d_low = 0.5e-5;
  s.d_high = 0.5e-5;
  d = validation_diagnosis(s, 10000);
  EXPECT_FALSE(d.explained_by_sampling);
  EXPECT_LE(d.excess, 0.0);
}

}  // namespace
}  // namespace ccal::test
