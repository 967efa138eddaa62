// The Monte Carlo with partly correlated sources (JCGM 101 §6.4.8, docs/model.md §10.2): the sample's input
// correlation is the configured one and every input keeps its distribution; a linear model's u and interval
// agree with the correlated LPU; r = 1 draws as a group does; the results do not depend on the threads.
//
// Tolerances are 5 standard deviations of the estimator at the number of trials used. The sample Pearson r of
// M pairs has a standard deviation of (1 − r²)/√M for normal inputs; bounded inputs have lighter tails and
// no larger one, but 1.5× that is allowed for them.
#include <gtest/gtest.h>

#include <cmath>

#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/gaussian_copula.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "monte_carlo_support.hpp"

namespace ccal {
namespace {

using ccal::test::source;

using ccal::test::identity;

PropagationOptions kept(std::uint64_t trials, int threads = 0) {
  PropagationOptions o;
  o.trials = trials;
  o.threads = threads;
  o.keep_samples = true;
  return o;
}

double pearson(const Eigen::MatrixXd& x, Eigen::Index a, Eigen::Index b) {
  const Eigen::VectorXd da = x.col(a).array() - x.col(a).mean(), db = x.col(b).array() - x.col(b).mean();
  return da.dot(db) / std::sqrt(da.squaredNorm() * db.squaredNorm());
}

const std::vector<Tolerance> kSources = {
    source("n", 2.0, Distribution::normal),        source("u", 3.0, Distribution::uniform),
    source("t", 1.5, Distribution::triangular),    source("a", 0.5, Distribution::arcsine),
    source("g1", 1.0, Distribution::uniform, "g"), source("g2", 0.4, Distribution::normal, "g")};
// Every pairing of distributions, one negative; the last names a grouped source: it applies to the group.
const std::vector<Correlation> kCorrelatedPairs = {
    {"n", "u", 0.6}, {"u", "t", -0.4}, {"t", "a", 0.3}, {"n", "g1", 0.5}};

TEST(MonteCarloCorrelations, TheSampleHasTheConfiguredCorrelationsAndMarginals) {
  const double M = 1e6;
  const MonteCarloDetail r =
      run_monte_carlo(kSources, kCorrelatedPairs, 6, {}, identity, kept(std::uint64_t(M)));
  // The configured pairs. n–g2 (normal–normal) takes g1's score correlation: c_NN(ρ) = ρ with ρ from the
  // normal–uniform pair, and g1–g2 are one draw: the largest normal–uniform correlation (as for any group).
  const double rho_ng = copula_score_correlation(Distribution::normal, Distribution::uniform, 0.5);
  struct Expected {
    Eigen::Index a, b;
    double r;
  };
  const Expected expected[] = {
      {0, 1, 0.6}, {1, 2, -0.4},   {2, 3, 0.3},
      {0, 4, 0.5}, {0, 5, rho_ng}, {4, 5, largest_pearson(Distribution::uniform, Distribution::normal)},
      {0, 2, 0.0}, {0, 3, 0.0},    {1, 3, 0.0},
      {1, 4, 0.0}, {3, 5, 0.0}};
  for (const Expected& e : expected) {
    SCOPED_TRACE(::testing::Message()
                 << kSources[std::size_t(e.a)].id << "–" << kSources[std::size_t(e.b)].id);
    EXPECT_NEAR(pearson(r.samples, e.a, e.b), e.r, 5 * 1.5 * (1 - e.r * e.r) / std::sqrt(M) + 1e-12);
  }
  // Every input keeps its distribution: σ (relative error √((κ − 1)/4M), κ ≤ 3), the bound of the bounded
  // ones and the 97.5 % quantile of the uniform (a quantile of a density 1/(2·3): √(p(1 − p)/M)·6).
  for (std::size_t j = 0; j < kSources.size(); ++j) {
    const double sigma = standard_uncertainty(kSources[j].bound, kSources[j].distribution);
    EXPECT_NEAR(r.outputs[j].std_dev, sigma, 5 * sigma * std::sqrt(2 / (4 * M))) << kSources[j].id;
    if (kSources[j].distribution != Distribution::normal) {
      EXPECT_LE(r.samples.col(Eigen::Index(j)).cwiseAbs().maxCoeff(), kSources[j].bound) << kSources[j].id;
    }
  }
  EXPECT_NEAR(r.outputs[1].high_symmetric, 0.95 * 3.0, 5 * std::sqrt(0.975 * 0.025 / M) * 6);
  EXPECT_NE(r.notes.find("Gaussian copula"), std::string::npos) << r.notes;
}

// y1 = x1 + 2 x2 − x3 + 3 x4 + x5 + x6, y2 = x1 − x4.
void linear(std::span<const double> x, std::span<double> y) {
  y[0] = x[0] + 2 * x[1] - x[2] + 3 * x[3] + x[4] + x[5];
  y[1] = x[0] - x[3];
}

TEST(MonteCarloCorrelations, ALinearModelAgreesWithTheCorrelatedLpu) {
  // By hand, c^T V c: effects E = c_j u_j of y1: 2, 2·3/√3, −1.5/√6, 3·0.5/√2, and the group (1 + 0.4 with
  // u 1/√3 and 0.4); the pairs' r as configured, n–g2 at the group's r.
  const double e[] = {2,  6 / std::sqrt(3.0), -1.5 / std::sqrt(6.0), 1.5 / std::sqrt(2.0), 1 / std::sqrt(3.0),
                      0.4};
  Eigen::MatrixXd R = Eigen::MatrixXd::Identity(6, 6);
  const auto set = [&](int a, int b, double r) { R(a, b) = R(b, a) = r; };
  set(0, 1, 0.6);
  set(1, 2, -0.4);
  set(2, 3, 0.3);
  set(0, 4, 0.5);
  set(0, 5, 0.5);
  set(4, 5, 1.0);
  const Eigen::Map<const Eigen::VectorXd> effects(e, 6);
  const double u1 = std::sqrt(effects.dot(R * effects));
  const LinearPropagation lp = propagate_linear(kSources, kCorrelatedPairs, 2, linear);
  EXPECT_NEAR(lp.std_uncertainty[0], u1, 1e-12 * u1);  // central differences of a linear model: exact
  // The MC: u(y1) within 5/√(2M) relatively (y1 is near normal); its interval is not compared with the LPU's
  // (the inputs are far from normal and so, slightly, is y1) except through u.
  const double M = 1e6;
  const MonteCarloDetail r =
      run_monte_carlo(kSources, kCorrelatedPairs, 2, {}, linear, kept(std::uint64_t(M)), &lp.std_uncertainty);
  EXPECT_NEAR(r.outputs[0].std_dev, u1, 5 * u1 / std::sqrt(2 * M));
  EXPECT_NEAR(r.covariance(0, 1), lp.covariance(0, 1),
              5 * std::sqrt((u1 * u1 * lp.covariance(1, 1) + lp.covariance(0, 1) * lp.covariance(0, 1)) / M));
}

TEST(MonteCarloCorrelations, NormalInputsGiveTheLpuIntervalWhichValidates) {
  // All normal, a linear model: y is normal with the LPU's u, so the MC's 95 % interval is y ± 1.96 u to
  // within its sampling error, and the §8 validation holds (δ of a two-digit u).
  const std::vector<Tolerance> s = {source("p", 1.0, Distribution::normal),
                                    source("q", 2.0, Distribution::normal),
                                    source("r", 0.5, Distribution::normal)};
  const std::vector<Correlation> pairs = {{"p", "q", -0.7}, {"q", "r", 0.4}};
  const auto model = [](std::span<const double> x, std::span<double> y) { y[0] = x[0] + x[1] + 2 * x[2]; };
  const LinearPropagation lp = propagate_linear(s, pairs, 1, model);
  // u² = 1 + 4 + 1 + 2(−0.7·1·2) + 2(0.4·2·1) = 6 − 2.8 + 1.6 = 4.8.
  EXPECT_NEAR(lp.std_uncertainty[0], std::sqrt(4.8), 1e-12);
  const MonteCarloDetail r = run_monte_carlo(s, pairs, 1, {}, model, kept(1000000), &lp.std_uncertainty);
  const OutputSummary& o = r.outputs[0];
  EXPECT_NEAR(o.high_symmetric, 1.959964 * std::sqrt(4.8), 5 * o.interval_end_std_error);
  EXPECT_NEAR(o.low_symmetric, -1.959964 * std::sqrt(4.8), 5 * o.interval_end_std_error);
  EXPECT_TRUE(o.validated) << o.d_low << " " << o.d_high << " " << o.validation_delta;
}

TEST(MonteCarloCorrelations, FullCorrelationDrawsAsAGroupDoes) {
  // r = 1 between two lone uniforms: one draw for both (up to the factor's round-off), as a group.
  const std::vector<Tolerance> s = {source("x", 1.0, Distribution::uniform),
                                    source("y", 3.0, Distribution::uniform),
                                    source("z", 1.0, Distribution::normal)};
  const MonteCarloDetail r =
      run_monte_carlo(s, {{"x", "y", 1.0}, {"y", "z", 0.2}, {"x", "z", 0.2}}, 3, {}, identity, kept(10000));
  EXPECT_LT((3 * r.samples.col(0) - r.samples.col(1)).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(MonteCarloCorrelations, TheThreadsDoNotChangeTheDraws) {
  const MonteCarloDetail one = run_monte_carlo(kSources, kCorrelatedPairs, 6, {}, identity, kept(20000, 1));
  const MonteCarloDetail two = run_monte_carlo(kSources, kCorrelatedPairs, 6, {}, identity, kept(20000, 2));
  EXPECT_EQ(one.samples, two.samples);
  // and a copula that cannot be drawn is refused before any trial
  EXPECT_THROW(run_monte_carlo(kSources, {{"n", "u", 0.99}}, 6, {}, identity, kept(100)), InputError);
}

}  // namespace
}  // namespace ccal
