// The Monte Carlo propagation of JCGM 101: sampling of every distribution and of correlation groups,
// agreement with the LPU for a linear model, its failure for a nonlinear one, the coverage intervals,
// determinism across threads, the adaptive procedure, and the calibration pipeline end to end.
//
// Every tolerance below is derived from the sampling error of the estimator at the number of trials used
// (5 standard deviations unless said otherwise). The runs are seeded, so the outcome is the same every time;
// the tolerances say that the seed was not chosen to make them pass.
#include "ccal/uncertainty/montecarlo.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <stdexcept>

#include "../src/uncertainty/calibration_cache.hpp"
#include "ccal/io/config_file.hpp"
#include "experiment_support.hpp"
#include "independent_lpu.hpp"
#include "monte_carlo_support.hpp"

namespace ccal::test {
namespace {

// The model y = x (every source is an output).
using ccal::test::identity;

PropagationOptions fixed(std::uint64_t trials, std::uint64_t seed = 1) {
  PropagationOptions o;
  o.trials = trials;
  o.seed = seed;
  return o;
}

const boost::math::normal kStdNormal;

// Standard deviation of the sample p-quantile of M values from a density f at the quantile.
double quantile_sd(double p, double density, double M) { return std::sqrt(p * (1 - p) / M) / density; }

TEST(MonteCarlo, EveryDistributionHasItsMomentsAndQuantiles) {
  // M = 10⁶ draws of each distribution. Estimators and their standard deviations:
  //   mean: σ/√M;   standard deviation: σ·√((κ − 1)/4M), κ the kurtosis (3, 1.8, 2.4, 1.5);
  //   97.5 % quantile (the upper end of the symmetric 95 % interval): √(p(1 − p)/M)/f(x_p);
  //   correlation between independent sources: 1/√M.
  const double M = 1e6;
  const std::vector<Tolerance> s = {
      source("n", 2.0, Distribution::normal), source("u", 3.0, Distribution::uniform),
      source("t", 1.5, Distribution::triangular), source("a", 0.5, Distribution::arcsine)};
  const MonteCarloDetail r = run_monte_carlo(s, 4, {}, identity, fixed(std::uint64_t(M)));
  ASSERT_EQ(r.trials, std::uint64_t(M));
  const double sigma[] = {2.0, 3.0 / std::sqrt(3.0), 1.5 / std::sqrt(6.0), 0.5 / std::numbers::sqrt2};
  const double kurtosis[] = {3.0, 1.8, 2.4, 1.5};
  const double p = 0.975;
  // x_p and f(x_p) of each distribution.
  const double zn = quantile(kStdNormal, p);
  const double xt = 1.5 * (1 - std::sqrt(2 * (1 - p)));
  const double xa = 0.5 * std::sin(std::numbers::pi * (p - 0.5));
  const double xp[] = {2.0 * zn, 3.0 * (2 * p - 1), xt, xa};
  const double fp[] = {pdf(kStdNormal, zn) / 2.0, 1 / 6.0, (1.5 - xt) / (1.5 * 1.5),
                       1 / (std::numbers::pi * std::sqrt(0.25 - xa * xa))};
  for (int k = 0; k < 4; ++k) {
    const OutputSummary& o = r.outputs[std::size_t(k)];
    SCOPED_TRACE(s[std::size_t(k)].id);
    EXPECT_EQ(o.name, fmt::format("y{}", k + 1));
    EXPECT_NEAR(o.mean, 0.0, 5 * sigma[k] / std::sqrt(M));
    EXPECT_NEAR(o.std_dev, sigma[k], 5 * sigma[k] * std::sqrt((kurtosis[k] - 1) / (4 * M)));
    EXPECT_NEAR(o.std_dev, standard_uncertainty(s[std::size_t(k)].bound, s[std::size_t(k)].distribution),
                5 * sigma[k] * std::sqrt((kurtosis[k] - 1) / (4 * M)));
    EXPECT_NEAR(o.high_symmetric, xp[k], 5 * quantile_sd(p, fp[k], M));
    EXPECT_NEAR(o.low_symmetric, -xp[k], 5 * quantile_sd(p, fp[k], M));
    for (int l = 0; l < k; ++l) EXPECT_NEAR(r.correlation(k, l), 0.0, 5 / std::sqrt(M));
    EXPECT_EQ(o.estimate, 0.0);
    EXPECT_FALSE(o.has_lpu);
  }
  // No sample ever reaches the bound of a bounded distribution (u is never 0 or 1).
  EXPECT_LT(r.outputs[1].high_shortest, 3.0);
  EXPECT_LT(r.outputs[3].high_shortest, 0.5);
}

TEST(MonteCarlo, AGroupSharesOneDrawWithRankCorrelationOne) {
  // a, b normal and c, d uniform in one group, e independent. Members of one type are exactly proportional
  // (b − 3a and c − 2d are 0 in every trial, to the bit); a normal and a uniform member sharing u have the
  // Pearson correlation E[Z(2Φ(Z) − 1)]·√3 = √(3/π) = 0.9772 (sampling error (1 − r²)/√M = 5e-5 at M = 10⁵);
  // the independent e is uncorrelated to 5/√M.
  const double M = 1e5;
  const std::vector<Tolerance> s = {
      source("a", 1.0, Distribution::normal, "g"), source("b", 3.0, Distribution::normal, "g"),
      source("c", 2.0, Distribution::uniform, "g"), source("d", 1.0, Distribution::uniform, "g"),
      source("e", 1.0, Distribution::normal)};
  const TrialFunction trial = [](std::span<const double> x, std::span<double> y) {
    y[0] = x[1] - 3 * x[0];
    y[1] = x[2] - 2 * x[3];
    y[2] = x[0];
    y[3] = x[2];
    y[4] = x[4];
  };
  const MonteCarloDetail r =
      run_monte_carlo(s, 5, {"b-3a", "c-2d", "a", "c", "e"}, trial, fixed(std::uint64_t(M)));
  EXPECT_EQ(r.outputs[0].std_dev, 0.0);
  EXPECT_EQ(r.outputs[0].high_symmetric, 0.0);
  EXPECT_EQ(r.outputs[1].std_dev, 0.0);
  EXPECT_EQ(r.outputs[1].low_symmetric, 0.0);
  EXPECT_NEAR(r.correlation(2, 3), std::sqrt(3 / std::numbers::pi),
              5 * (1 - 3 / std::numbers::pi) / std::sqrt(M));
  EXPECT_NEAR(r.correlation(2, 4), 0.0, 5 / std::sqrt(M));
  EXPECT_NEAR(r.correlation(3, 4), 0.0, 5 / std::sqrt(M));
  EXPECT_NE(r.notes.find("1 fully correlated group"), std::string::npos) << r.notes;
}

// y1 = x1 + 2 x2 − x3 + 3 x4 + 2 x5 + x6, y2 = x1 − x6, with x5 and x6 (both uniform) in one group.
const std::vector<Tolerance> kLinearSources = {
    source("x1", 3.0, Distribution::normal),       source("x2", 1.0, Distribution::uniform),
    source("x3", 1.0, Distribution::triangular),   source("x4", 0.5, Distribution::arcsine),
    source("x5", 0.6, Distribution::uniform, "g"), source("x6", 0.3, Distribution::uniform, "g")};
void linear(std::span<const double> x, std::span<double> y) {
  y[0] = x[0] + 2 * x[1] - x[2] + 3 * x[3] + 2 * x[4] + x[5];
  y[1] = x[0] - x[5];
}

TEST(MonteCarlo, LinearModelMatchesTheLpuAndValidatesIt) {
  // LPU by hand: contributions c·u = 3, 2/√3, 1/√6, 1.5/√2 and, for the group, (2·0.6 + 0.3)/√3 added
  // linearly; u²(y1) = 9 + 4/3 + 1/6 + 9/8 + 3/4 = 12.375. y2: 3 and −0.3/√3, cov(y1, y2) = 9 − 0.15 = 8.85.
  const double u1 = std::sqrt(12.375), u2 = std::sqrt(9 + 0.03), c12 = 8.85;
  const LinearPropagation lp = propagate_linear(kLinearSources, 2, linear);
  // Central differences of a linear model are exact up to round-off.
  EXPECT_NEAR(lp.std_uncertainty[0], u1, 1e-12 * u1);
  EXPECT_NEAR(lp.std_uncertainty[1], u2, 1e-12 * u2);
  EXPECT_NEAR(lp.covariance(0, 1), c12, 1e-12 * c12);
  EXPECT_NEAR(lp.sensitivities(0, 3), 3.0, 1e-12);
  EXPECT_EQ(lp.estimate, Eigen::Vector2d::Zero());

  // M = 2·10⁶. y1 is nearly normal (excess kurtosis −0.03), so the relative sampling error of u(y) is
  // 1/√(2M) = 5e-4, of the covariance √((u1²u2² + c12²)/M) = 0.01.
  const double M = 2e6;
  const MonteCarloDetail r =
      run_monte_carlo(kLinearSources, 2, {"y1", "y2"}, linear, fixed(std::uint64_t(M)), &lp.std_uncertainty);
  EXPECT_NEAR(r.outputs[0].std_dev, u1, 5 * u1 / std::sqrt(2 * M));
  EXPECT_NEAR(r.outputs[1].std_dev, u2, 5 * u2 / std::sqrt(2 * M));
  EXPECT_NEAR(r.covariance(0, 1), c12, 5 * std::sqrt((u1 * u1 * u2 * u2 + c12 * c12) / M));
  // §8 with n_dig = 2: δ = 0.05 for u1 = 3.5 and u2 = 3.0. The MC interval ends differ from y ± 1.96 u by the
  // kurtosis (Cornish–Fisher: −0.008 for y1) and by sampling (√(p(1 − p)/M)/φ(1.96)·u = 0.007 at 1σ), well
  // within δ.
  EXPECT_NEAR(r.coverage_factor, 1.959964, 1e-6);
  for (const OutputSummary& o : r.outputs) {
    SCOPED_TRACE(o.name);
    EXPECT_TRUE(o.has_lpu);
    EXPECT_DOUBLE_EQ(o.validation_delta, 0.05);
    EXPECT_LE(o.d_low, o.validation_delta);
    EXPECT_LE(o.d_high, o.validation_delta);
    EXPECT_TRUE(o.validated);
  }
}

TEST(MonteCarlo, SquareOfAZeroMeanInputInvalidatesTheLpu) {
  // y = x², x ~ N(0, 1): the first-order LPU gives u_c = 0 (the derivative vanishes at 0) and the interval
  // 0 ± 0, while y is χ²₁ with the 95 % symmetric interval [0.00098, 5.02]; even the second-order u_c = √2
  // (GUM 5.1.2 note) gives 0 ± 2.77. Both fail by far more than δ.
  const std::vector<Tolerance> s = {source("x", 1.0, Distribution::normal)};
  const TrialFunction square = [](std::span<const double> x, std::span<double> y) { y[0] = x[0] * x[0]; };
  const LinearPropagation lp = propagate_linear(s, 1, square);
  EXPECT_EQ(lp.std_uncertainty[0], 0.0);
  const MonteCarloDetail r = run_monte_carlo(s, 1, {"x^2"}, square, fixed(100000), &lp.std_uncertainty);
  const OutputSummary& o = r.outputs[0];
  EXPECT_NEAR(o.mean, 1.0, 5 * std::sqrt(2.0 / 1e5));  // χ²₁: mean 1, variance 2
  EXPECT_NEAR(o.high_symmetric, 5.024, 0.15);          // 5 sd of the quantile: √(p(1−p)/M)/f = 0.029
  EXPECT_GT(o.d_high, 4.0);
  EXPECT_FALSE(o.validated);
  const Eigen::VectorXd second_order = Eigen::VectorXd::Constant(1, std::numbers::sqrt2);
  const MonteCarloDetail r2 = run_monte_carlo(s, 1, {"x^2"}, square, fixed(100000), &second_order);
  EXPECT_FALSE(r2.outputs[0].validated);
  EXPECT_GT(r2.outputs[0].d_high, 2.0);
  EXPECT_GT(r2.outputs[0].d_low, 2.0);
}

TEST(MonteCarlo, ShortestIntervalIsNarrowerForASkewedOutput) {
  // y = exp(x), x ~ N(0, 0.5²), M = 2·10⁵. Symmetric: [e^(−0.98), e^(0.98)] exactly in distribution;
  // shortest: the least e^(σ z2) − e^(σ z1) with Φ(z2) − Φ(z1) = 0.95 (found here by scanning Φ(z1)). The
  // endpoint errors are 5 quantile standard deviations (at most 0.008 at 1σ); the theoretical widths
  // are 2.289 and 2.056: they differ by 0.23, over 6 times the combined tolerance of the two ends, 0.036.
  const double sigma = 0.5, M = 2e5, p = 0.95;
  const std::vector<Tolerance> s = {source("x", sigma, Distribution::normal)};
  const TrialFunction lognormal = [](std::span<const double> x, std::span<double> y) {
    y[0] = std::exp(x[0]);
  };
  const MonteCarloDetail r = run_monte_carlo(s, 1, {}, lognormal, fixed(std::uint64_t(M)));
  const OutputSummary& o = r.outputs[0];
  const double z = quantile(kStdNormal, 0.975);
  const auto density = [&](double y) { return pdf(kStdNormal, std::log(y) / sigma) / (sigma * y); };
  const auto tol = [&](double y, double q) { return 5 * quantile_sd(q, density(y), M); };
  EXPECT_NEAR(o.low_symmetric, std::exp(-sigma * z), tol(std::exp(-sigma * z), 0.025));
  EXPECT_NEAR(o.high_symmetric, std::exp(sigma * z), tol(std::exp(sigma * z), 0.975));
  double best = INFINITY, best_low = 0, best_high = 0, best_a = 0;
  for (int k = 1; k < 50000; ++k) {
    const double a = 0.05 * k / 50000;
    const double lo = std::exp(sigma * quantile(kStdNormal, a)),
                 hi = std::exp(sigma * quantile(kStdNormal, a + p));
    if (hi - lo < best) {
      best = hi - lo;
      best_low = lo;
      best_high = hi;
      best_a = a;
    }
  }
  const double width_tol = tol(best_low, best_a) + tol(best_high, best_a + p);
  const double shortest = o.high_shortest - o.low_shortest, symmetric = o.high_symmetric - o.low_symmetric;
  EXPECT_NEAR(shortest, best, width_tol);
  EXPECT_LT(shortest, symmetric - 3 * width_tol) << best << " " << width_tol;
  EXPECT_LT(o.low_shortest, o.low_symmetric);
  EXPECT_LT(o.high_shortest, o.high_symmetric);
}

TEST(MonteCarlo, ShortestAndSymmetricIntervalsAgreeForASymmetricOutput) {
  // y = x ~ N(0, 1), M = 10⁶: both intervals estimate ±1.96. The symmetric ends have the quantile error
  // 0.0027 (1σ). The shortest window is the minimum of a noisy width w(a) = Φ⁻¹(a + p) − Φ⁻¹(a) that is flat
  // at a = 0.025 (w'' = 2·1.96/φ(1.96)² = 1150), so its position is uncertain by √(2·5·sd_w/w'') in a, with
  // sd_w ≤ 2·0.0027: 0.0069 in a, i.e. 0.0069/φ(1.96) = 0.12 on each end. Its width can only be ≤ the
  // symmetric one (that window is a candidate) and is within 5·sd_w of it.
  const double M = 1e6;
  const std::vector<Tolerance> s = {source("x", 1.0, Distribution::normal)};
  const MonteCarloDetail r = run_monte_carlo(s, 1, {}, identity, fixed(std::uint64_t(M)));
  const OutputSummary& o = r.outputs[0];
  const double z = quantile(kStdNormal, 0.975), sd_q = quantile_sd(0.975, pdf(kStdNormal, z), M);
  EXPECT_NEAR(o.high_symmetric, z, 5 * sd_q);
  EXPECT_NEAR(o.low_symmetric, -z, 5 * sd_q);
  EXPECT_NEAR(o.low_shortest, o.low_symmetric, 0.12);
  EXPECT_NEAR(o.high_shortest, o.high_symmetric, 0.12);
  const double shortest = o.high_shortest - o.low_shortest, symmetric = o.high_symmetric - o.low_symmetric;
  EXPECT_LE(shortest, symmetric);
  EXPECT_GT(shortest, symmetric - 5 * 2 * sd_q);
}

TEST(MonteCarlo, IntervalsFollowTheOrderStatisticRule) {
  // §7.7.2: q = pM if an integer, else ⌊pM + ½⌋; symmetric r = (M − q)/2 if an integer, else ⌊(M − q + 1)/2⌋.
  EXPECT_EQ(coverage_points(10, 0.8), 8u);   // pM = 8 (0.8·10 rounds to exactly 8)
  EXPECT_EQ(coverage_points(10, 0.75), 8u);  // 7.5 → 8
  EXPECT_EQ(coverage_points(10, 0.74), 7u);  // 7.4 → 7
  EXPECT_EQ(coverage_points(10000, 0.95), 9500u);
  EXPECT_EQ(coverage_points(10, 0.999), 9u);  // at most M − 1: an interval has two ends
  const std::vector<double> y = {1, 2, 4, 8, 16, 32, 64, 128, 256, 512};
  // q = 8, r = 1: [y(1), y(9)].
  EXPECT_EQ(symmetric_coverage_interval(y, 0.8), std::make_pair(1.0, 256.0));
  // q = 7, M − q = 3, r = ⌊4/2⌋ = 2: [y(2), y(9)].
  EXPECT_EQ(symmetric_coverage_interval(y, 0.74), std::make_pair(2.0, 256.0));
  // Growing gaps: the narrowest window of q + 1 values is the lowest one.
  EXPECT_EQ(shortest_coverage_interval(y, 0.74), std::make_pair(1.0, 128.0));
  const std::vector<double> falling = {0, 100, 150, 175, 187, 193, 196, 198, 199, 200};
  EXPECT_EQ(shortest_coverage_interval(falling, 0.74), std::make_pair(150.0, 200.0));
  // Ties: the first window.
  const std::vector<double> even = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9};
  EXPECT_EQ(shortest_coverage_interval(even, 0.74), std::make_pair(0.0, 7.0));

  // §7.9.2: u = c·10ˡ with c of n_dig digits, δ = ½·10ˡ.
  EXPECT_DOUBLE_EQ(numerical_tolerance(1.15, 2), 0.05);     // 12·10⁻¹
  EXPECT_DOUBLE_EQ(numerical_tolerance(0.028, 2), 0.0005);  // 28·10⁻³
  EXPECT_DOUBLE_EQ(numerical_tolerance(0.028, 1), 0.005);   // 3·10⁻²
  EXPECT_DOUBLE_EQ(numerical_tolerance(9.96, 2), 0.5);      // 99.6·10⁻¹ rounds to 100: 10·10⁰
  EXPECT_DOUBLE_EQ(numerical_tolerance(1e-3, 1), 0.0005);
  EXPECT_DOUBLE_EQ(numerical_tolerance(1000.0, 2), 50.0);  // 10·10²
  EXPECT_EQ(numerical_tolerance(0.0, 2), 0.0);
}

// Every number of two results, to the bit.
void expect_identical(const MonteCarloDetail& a, const MonteCarloDetail& b) {
  ASSERT_EQ(a.trials, b.trials);
  ASSERT_EQ(a.outputs.size(), b.outputs.size());
  EXPECT_EQ(a.stages, b.stages);
  for (std::size_t k = 0; k < a.outputs.size(); ++k) {
    const OutputSummary &x = a.outputs[k], &y = b.outputs[k];
    EXPECT_EQ(x.mean, y.mean);
    EXPECT_EQ(x.std_dev, y.std_dev);
    EXPECT_EQ(x.low_symmetric, y.low_symmetric);
    EXPECT_EQ(x.high_symmetric, y.high_symmetric);
    EXPECT_EQ(x.low_shortest, y.low_shortest);
    EXPECT_EQ(x.high_shortest, y.high_shortest);
    EXPECT_EQ(x.d_low, y.d_low);
    EXPECT_EQ(x.d_high, y.d_high);
  }
  EXPECT_EQ(std::memcmp(a.covariance.data(), b.covariance.data(),
                        sizeof(double) * std::size_t(a.covariance.size())),
            0);
}

// A nonlinear model with a group, for the determinism tests.
const std::vector<Tolerance> kMixedSources = {
    source("a", 1.0, Distribution::normal, "g"), source("b", 2.0, Distribution::triangular),
    source("c", 0.5, Distribution::arcsine, "g"), source("d", 1.0, Distribution::uniform)};
void mixed(std::span<const double> x, std::span<double> y) {
  y[0] = x[0] * x[1] + std::sin(x[2]);
  y[1] = std::exp(0.3 * x[3]) - x[0];
  y[2] = x[1] * x[1];
}

TEST(MonteCarlo, SameSeedGivesBitIdenticalResultsForAnyThreadCount) {
  const Eigen::VectorXd lpu = propagate_linear(kMixedSources, 3, mixed).std_uncertainty;
  PropagationOptions o = fixed(20011, 42);  // a prime: the threads get unequal shares
  o.threads = 1;
  const MonteCarloDetail one = run_monte_carlo(kMixedSources, 3, {}, mixed, o, &lpu);
  EXPECT_EQ(one.threads, 1);
  for (int threads : {2, 3}) {
    SCOPED_TRACE(threads);
    o.threads = threads;
    const MonteCarloDetail r = run_monte_carlo(kMixedSources, 3, {}, mixed, o, &lpu);
    EXPECT_EQ(r.threads, threads);
    expect_identical(one, r);
  }
  o.seed = 43;
  const MonteCarloDetail other = run_monte_carlo(kMixedSources, 3, {}, mixed, o, &lpu);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_NE(other.outputs[k].mean, one.outputs[k].mean);
    EXPECT_NE(other.outputs[k].high_symmetric, one.outputs[k].high_symmetric);
  }
}

TEST(MonteCarlo, AdaptiveRunEqualsAFixedRunOfTheSameLength) {
  // Trials are numbered over all stages, so h stages of M are the fixed run of h·M trials, for any threads.
  PropagationOptions o = fixed(2, 7);  // adaptive: stages of max(2, J, 10⁴) trials
  o.digits = 1;
  o.threads = 1;
  const MonteCarloDetail adaptive = run_monte_carlo(kMixedSources, 3, {}, mixed, o);
  ASSERT_TRUE(adaptive.converged);
  o.threads = 2;
  expect_identical(adaptive, run_monte_carlo(kMixedSources, 3, {}, mixed, o));
  PropagationOptions f = fixed(adaptive.trials, 7);
  const MonteCarloDetail fixed_run = run_monte_carlo(kMixedSources, 3, {}, mixed, f);
  EXPECT_EQ(fixed_run.stages, 1);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(adaptive.outputs[k].mean, fixed_run.outputs[k].mean);
    EXPECT_EQ(adaptive.outputs[k].low_shortest, fixed_run.outputs[k].low_shortest);
  }
}

TEST(MonteCarlo, AdaptiveProcedureStopsWhenTheStageAveragesAreStable) {
  // y1 = x1 + x2, x1 ~ N(0, 3.4²), x2 uniform ±2, and y2 = x1·x2: u(y1) = 3.6 = 36·10⁻¹ with n_dig = 2, so
  // δ = 0.05; a stage of 10⁴ trials has a 97.5 % quantile with sd 0.027·3.6 = 0.097, so that twice the sd of
  // the average over h stages is ≤ δ after about (2·0.097/0.05)² = 15 stages. y2 (u = 3.9, δ = 0.05) has
  // heavier tails and needs more (48 with this seed); all of it takes 0.1 s.
  const std::vector<Tolerance> s = {source("x1", 3.4, Distribution::normal),
                                    source("x2", 2.0, Distribution::uniform)};
  const TrialFunction f = [](std::span<const double> x, std::span<double> y) {
    y[0] = x[0] + x[1];
    y[1] = x[0] * x[1];
  };
  PropagationOptions o;
  o.trials = 2;  // the stage size is then max(2, J = 2000, 10⁴)
  o.digits = 2;
  const MonteCarloDetail r = run_monte_carlo(s, 2, {}, f, o);
  EXPECT_TRUE(r.adaptive);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.stage_trials, 10000u);
  EXPECT_GT(r.stages, 5);
  EXPECT_EQ(r.trials, std::uint64_t(r.stages) * r.stage_trials);
  EXPECT_DOUBLE_EQ(r.outputs[0].delta, 0.05);
  for (const OutputSummary& y : r.outputs) {
    SCOPED_TRACE(y.name);
    EXPECT_GT(y.delta, 0.0);
    for (double spread : {y.s_mean, y.s_std_dev, y.s_low, y.s_high}) {
      EXPECT_GT(spread, 0.0);
      EXPECT_LE(2 * spread, y.delta);
    }
  }
  // One stage fewer would not have been enough for at least one output (else it would have stopped there).
  PropagationOptions shorter = o;
  shorter.max_trials = r.trials - r.stage_trials;
  const MonteCarloDetail cut = run_monte_carlo(s, 2, {}, f, shorter);
  EXPECT_FALSE(cut.converged);
  EXPECT_EQ(cut.trials, shorter.max_trials);
  EXPECT_NE(cut.notes.find("NOT converged"), std::string::npos) << cut.notes;
  bool some_unstable = false;
  for (const OutputSummary& y : cut.outputs)
    for (double spread : {y.s_mean, y.s_std_dev, y.s_low, y.s_high}) some_unstable |= 2 * spread > y.delta;
  EXPECT_TRUE(some_unstable);

  // The stage size: at least the requested trials, J = ⌈100/(1 − p)⌉ and 10⁴.
  o.trials = 12345;
  o.max_trials = 2 * 12345;
  EXPECT_EQ(run_monte_carlo(s, 2, {}, f, o).stage_trials, 12345u);
  o.trials = 2;
  o.coverage_probability = 0.999;
  o.max_trials = 200000;
  EXPECT_EQ(run_monte_carlo(s, 2, {}, f, o).stage_trials, 100000u);
}

TEST(MonteCarlo, RefusesBadInputAndPassesOnTrialErrors) {
  const std::vector<Tolerance> s = {source("x", 1.0, Distribution::normal)};
  EXPECT_THROW(run_monte_carlo(s, 1, {"a", "b"}, identity, fixed(100)), InputError);
  EXPECT_THROW(run_monte_carlo(s, 1, {}, identity, fixed(1)), InputError);
  PropagationOptions o = fixed(100);
  o.coverage_probability = 1.0;
  EXPECT_THROW(run_monte_carlo(s, 1, {}, identity, o), InputError);
  EXPECT_THROW(run_monte_carlo({source("x", -1.0, Distribution::normal)}, 1, {}, identity, fixed(100)),
               InputError);
  // A non-finite output names the output; an exception of the model comes through unchanged.
  const TrialFunction log = [](std::span<const double> x, std::span<double> y) { y[0] = std::log(x[0]); };
  try {
    run_monte_carlo({source("x", 1.0, Distribution::uniform)}, 1, {"log"}, log, fixed(1000));
    ADD_FAILURE() << "no error";
  } catch (const InputError&) {
    // log(0) at the estimate: refused before any trial.
  }
  const TrialFunction shifted = [](std::span<const double> x, std::span<double> y) {
    y[0] = std::log(1 + x[0]);
  };
  try {
    run_monte_carlo({source("x", 2.0, Distribution::uniform)}, 1, {"log1p"}, shifted, fixed(1000));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'log1p'"), std::string::npos) << e.what();
  }
  const TrialFunction throws = [](std::span<const double> x, std::span<double> y) {
    if (x[0] > 0.9) throw std::domain_error("too far");
    y[0] = x[0];
  };
  EXPECT_THROW(run_monte_carlo({source("x", 1.0, Distribution::uniform)}, 1, {}, throws, fixed(1000)),
               std::domain_error);
}

TEST(MonteCarlo, CalibrationPipelineMatchesTheLpuOfItsSensitivities) {
  // The paper's experiment with the Earth on, three sources: IA azimuth (normal 1e-5 rad), static radius
  // (uniform ±25 µm) and main-axis levelling (normal 1e-5 rad). Trial: simulate, identify K0, K2, K3,
  // subtract the error-free terms. Checked against an LPU computed without the trial (below).
  const Experiment ex = paper_experiment(true);
  std::vector<Tolerance> s = {source("dthz5", 1e-5, Distribution::normal),
                              source("dR_s", 25e-6, Distribution::uniform),
                              source("dthx1t", 1e-5, Distribution::normal)};
  s[0].parameter = ch::dthz5;
  s[1].parameter = ch::dR_s;
  s[2].parameter = ch::dthx1t;
  const CalibrationModel model =
      calibration_model(ex, paper_spec(), s, Eigen::VectorXd::Zero(ex.layout.size()), ModelMode::exact);
  EXPECT_EQ(model.output_names(), (std::vector<std::string>{"K0", "K2", "K3"}));
  EXPECT_NEAR(model.reference()[2] / kDeg, 0.003, 1e-12);
  const TrialFunction trial = calibration_trial(model);
  const LinearPropagation lp = propagate_linear(s, model.n_outputs(), trial);
  // The levelling dominates K3 (−1.45e-3 °/s/g³ per 1e-5 rad, reduction/observe_test.cpp).
  EXPECT_NEAR(lp.sensitivities(2, 2) * 1e-5 / kDeg, -1.45e-3, 0.02e-3);
  // The reference LPU does not use the trial: central differences of the re-identified pipeline
  // (independent_lpu.hpp), σ = bound (normal) and bound/√3 (uniform) written out. The propagate_linear of the
  // trial must agree with it to the central differences' accuracy (1e-6 relative), and the Monte Carlo
  // standard deviations within sampling: M = 2·10⁴, relative standard error ≤ 1/√(2M) = 0.5 % for outputs
  // no more peaked than a normal (these are sums of a normal-dominated and a uniform part), 5 of them 2.5 %;
  // the nonlinearity at 1e-5 is O(1e-5).
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const Eigen::MatrixXd cov =
      lpu_covariance(finite_difference_sensitivities(ex, paper_spec(), zero, zero, s), s);
  const double M = 2e4;
  const MonteCarloDetail r = run_monte_carlo(s, model.n_outputs(), model.output_names(), trial,
                                             fixed(std::uint64_t(M)), &lp.std_uncertainty);
  const OutputSummary& k3 = r.outputs[2];
  EXPECT_EQ(k3.name, "K3");
  for (int k = 0; k < 3; ++k) {
    const double u = std::sqrt(cov(k, k));
    EXPECT_NEAR(lp.std_uncertainty[k], u, 1e-6 * u) << k;
    EXPECT_NEAR(r.outputs[std::size_t(k)].std_dev, u, 5 * u / std::sqrt(2 * M)) << k;
  }
  EXPECT_NEAR(k3.mean, 0.0, 5 * std::sqrt(cov(2, 2) / M));
  EXPECT_LT(std::abs(k3.estimate), 1e-12 * kDeg);  // the error-free run reproduces the reference

  // The bundled example builds its model from the configuration: its tolerances, then the rate noise of both
  // drives as one source per run each (rate_noise.hpp).
  const Config cfg = bundled_example();
  const CalibrationModel bundled = calibration_model(cfg);
  EXPECT_EQ(bundled.parameters().size(), cfg.tolerances.size() + 2 * cfg.plan.runs.size());
}

TEST(MonteCarlo, CalibrationTrialIsTheFullPipelineAtItsDraw) {
  // A trial (run-mean kernel with the trial rule, cached H⁺ and known part) at ±3σ corner draws of the
  // bundled tolerances against the full pipeline: observe the truth (configured errors + draw) with the
  // converged default rule, identify, subtract the same identification at zero truth. The two rules differ
  // by < 1e-12 of each run's swing K1·A (tests/reduction/run_average_test.cpp), which H⁺ maps to at most
  // Σ_j |H⁺_kj| · 1e-12 · K1·A_j per coefficient: that bound is the tolerance.
  const Config cfg = bundled_example();
  const Experiment ex = cfg.experiment();
  const CalibrationModel model = calibration_model(cfg);
  ASSERT_TRUE(model.trial_cache().run_means);  // exact mode goes through the kernel
  const TrialFunction trial = calibration_trial(model);
  const IdentificationSpec& spec = cfg.identification;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const Eigen::VectorXd known = spec.compensate ? cfg.centrifuge.errors : zero;
  const Eigen::VectorXd reference =
      identify_coefficients<double>(observe<double>(ex, zero, known, spec), spec);
  const double K1 = ex.instrument.coefficient("K1").value();
  std::mt19937 rng(3);
  for (int draw = 0; draw < 3; ++draw) {
    const Eigen::VectorXd truth = corner_draw(cfg, 3.0, rng);
    // A draw for every source of the model: the tolerances' (the chain's at 0), then the runs' rate noise (0).
    std::vector<double> draws(model.parameters().size(), 0.0);
    for (std::size_t j = 0; j < cfg.tolerances.size(); ++j) {
      const int p = cfg.tolerances[j].parameter;
      if (!is_chain_parameter(p)) draws[j] = truth[p] - cfg.centrifuge.errors[p];
    }
    std::vector<double> out(std::size_t(model.n_outputs()));
    trial(draws, out);
    const Eigen::VectorXd want =
        identify_coefficients<double>(observe<double>(ex, truth, known, spec), spec) - reference;
    for (Eigen::Index k = 0; k < want.size(); ++k) {
      double bound = 0;
      for (Eigen::Index j = 0; j < model.trial_cache().design_pinv.cols(); ++j)
        bound += std::abs(model.trial_cache().design_pinv(k, j)) * 1e-12 * K1 * ex.plan.runs[std::size_t(j)].g_level;
      EXPECT_NEAR(out[std::size_t(k)], want[k], bound)
          << spec.free_terms[std::size_t(k)] << ", draw " << draw;
      EXPECT_GT(std::abs(want[k]), 1e3 * bound);  // a real deviation, far above the tolerance
    }
  }
}

}  // namespace
}  // namespace ccal::test
