// The Gaussian copula's pieces (uncertainty/gaussian_copula.hpp): each input's value of a normal score
// against its quantile function, the Pearson correlation c_DE(ρ) of two inputs against closed forms and
// against an independent two-dimensional quadrature, its inverse, its largest value, and the copula of a
// configuration (slots, groups, refusals).
#include "ccal/uncertainty/gaussian_copula.hpp"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ccal/core/errors.hpp"

namespace {

using namespace ccal;

constexpr Distribution kAll[] = {Distribution::normal, Distribution::uniform, Distribution::triangular,
                                 Distribution::arcsine};

double phi_cdf(double y) { return 0.5 * std::erfc(-y / std::numbers::sqrt2); }

// F⁻¹(u) of each distribution with bound 1, written from its definition (docs/model.md §10.2).
double quantile(Distribution d, double u) {
  switch (d) {
    case Distribution::normal:
      return normal_erf_quantile(2 * u - 1);
    case Distribution::uniform:
      return 2 * u - 1;
    case Distribution::triangular:
      return u < 0.5 ? std::sqrt(2 * u) - 1 : 1 - std::sqrt(2 * (1 - u));
    case Distribution::arcsine:
      return -std::cos(std::numbers::pi * u);
  }
  return 0;
}

TEST(GaussianCopula, AScoreGivesTheQuantileOfItsProbability) {
  // G_D(y) = F_D⁻¹(Φ(y)); for |y| ≤ 3 the probability keeps 15 digits, so both sides agree to ~1e-15 (the
  // triangular's √ doubles a relative error near its ends: 1e-14).
  for (const Distribution d : kAll)
    for (double y = -3; y <= 3; y += 0.125) {
      EXPECT_NEAR(standard_value_of_score(d, y), quantile(d, phi_cdf(y)), 1e-14) << int(d) << " " << y;
      EXPECT_EQ(standard_value_of_score(d, -y), -standard_value_of_score(d, y));  // exactly odd
    }
  // Far out the tail probability is used: still inside the bound, and at it only beyond 8σ.
  EXPECT_LT(standard_value_of_score(Distribution::triangular, 8), 1.0);
  EXPECT_NEAR(standard_value_of_score(Distribution::triangular, 8), 1 - std::sqrt(2 * phi_cdf(-8)), 1e-16);
}

TEST(GaussianCopula, PearsonCorrelationAgainstClosedForms) {
  // Mehler's series against forms derived by hand (docs/model.md §10.2): the quadrature of the Hermite
  // coefficients and the sum are accurate to round-off, so 1e-13.
  for (double rho = -1; rho <= 1; rho += 0.0625) {
    EXPECT_EQ(copula_pearson(Distribution::normal, Distribution::normal, rho), rho);
    EXPECT_NEAR(copula_pearson(Distribution::uniform, Distribution::uniform, rho),
                6 / std::numbers::pi * std::asin(rho / 2), 1e-13);
    EXPECT_NEAR(copula_pearson(Distribution::normal, Distribution::uniform, rho),
                std::sqrt(3 / std::numbers::pi) * rho, 1e-13);
  }
  // The largest correlations: ∫(2u − 1) F⁻¹(u) du / (σσ) by hand: uniform–triangular 7√2/10, uniform–arcsine
  // 4√6/π², normal–uniform √(3/π); one distribution with itself: 1.
  EXPECT_NEAR(largest_pearson(Distribution::uniform, Distribution::triangular), 0.7 * std::numbers::sqrt2,
              1e-13);
  EXPECT_NEAR(largest_pearson(Distribution::arcsine, Distribution::uniform),
              4 * std::sqrt(6.0) / (std::numbers::pi * std::numbers::pi), 1e-13);
  EXPECT_NEAR(largest_pearson(Distribution::normal, Distribution::uniform), 0.9772050238058398, 1e-15);
  for (const Distribution d : kAll) EXPECT_EQ(largest_pearson(d, d), 1.0);
}

// E[G_D(y₁) G_E(y₂)]/(σ_D σ_E) for corr(y₁, y₂) = ρ by a product Gauss–Legendre rule over the two independent
// normals (z₁, z₂), y₂ = ρ z₁ + √(1 − ρ²) z₂: an independent oracle. The triangular's kink in the second
// derivative lies along a line the panels do not follow, so it is good to ~1e-9 there; the others to 1e-13.
double oracle_pearson(Distribution d, Distribution e, double rho) {
  using Rule = boost::math::quadrature::gauss<double, 20>;
  const double s = std::sqrt(1 - rho * rho), width = 0.5;
  std::vector<double> z, w;
  for (double left = -10; left < 10 - 1e-9; left += width)
    for (std::size_t i = 0; i < Rule::abscissa().size(); ++i)
      for (const double sign : {-1.0, 1.0}) {
        const double x = left + 0.5 * width * (1 + sign * Rule::abscissa()[i]);
        z.push_back(x);
        w.push_back(0.5 * width * Rule::weights()[i] * std::exp(-0.5 * x * x) /
                    std::sqrt(2 * std::numbers::pi));
      }
  double sum = 0;
  for (std::size_t i = 0; i < z.size(); ++i) {
    const double gd = standard_value_of_score(d, z[i]);
    double inner = 0;
    for (std::size_t j = 0; j < z.size(); ++j)
      inner += w[j] * standard_value_of_score(e, rho * z[i] + s * z[j]);
    sum += w[i] * gd * inner;
  }
  return sum * divisor(d) * divisor(e);
}

TEST(GaussianCopula, PearsonCorrelationAgainstAnIndependentQuadrature) {
  for (const Distribution d : kAll)
    for (const Distribution e : kAll)
      for (const double rho : {-0.7, 0.3, 0.95}) {
        const bool kinked = d == Distribution::triangular || e == Distribution::triangular;
        EXPECT_NEAR(copula_pearson(d, e, rho), oracle_pearson(d, e, rho), kinked ? 2e-8 : 1e-12)
            << distribution_name(d) << "–" << distribution_name(e) << " ρ = " << rho;
      }
}

TEST(GaussianCopula, TheScoreCorrelationGivesBackTheConfiguredOne) {
  for (const Distribution d : kAll)
    for (const Distribution e : kAll) {
      const double largest = largest_pearson(d, e);
      for (const double r : {-0.9, -0.3, 0.0, 0.1, 0.5, 0.97}) {
        const double target = r * largest;
        const double rho = copula_score_correlation(d, e, target);
        EXPECT_NEAR(copula_pearson(d, e, rho), target, 1e-14) << int(d) << int(e) << " r = " << target;
        EXPECT_GE(std::abs(rho), std::abs(target) - 1e-15);  // the scores correlate at least as strongly
      }
      EXPECT_EQ(copula_score_correlation(d, e, 1.0), 1.0);  // the comonotone draw, as a group's
      EXPECT_EQ(copula_score_correlation(d, e, -1.0), -1.0);
      if (largest < 1) {
        EXPECT_THROW(copula_score_correlation(d, e, 0.5 * (1 + largest)), std::domain_error);
      }
    }
  EXPECT_EQ(copula_score_correlation(Distribution::uniform, Distribution::uniform, 0.5),
            2 * std::sin(std::numbers::pi / 12));
  EXPECT_THROW(copula_score_correlation(Distribution::normal, Distribution::normal, 1.5), std::domain_error);
}

Tolerance source(const std::string& id, Distribution d, const std::string& group = "") {
  Tolerance t;
  t.id = id;
  t.bound = 1;
  t.distribution = d;
  t.group = group;
  return t;
}

TEST(GaussianCopula, SlotsGroupsAndFactor) {
  const std::vector<Tolerance> s = {
      source("a", Distribution::uniform), source("b", Distribution::normal, "g"),
      source("c", Distribution::uniform, "g"), source("d", Distribution::uniform)};
  const GaussianCopula c = gaussian_copula(s, {{"a", "c", 0.5}, {"a", "d", -0.25}});
  EXPECT_EQ(c.slots, 3);
  EXPECT_EQ(c.slot, (std::vector<int>{0, 1, 1, 2}));
  // The pair names c (uniform): its score correlation is the uniform–uniform one, for the whole group.
  EXPECT_EQ(c.score_correlation(0, 1), 2 * std::sin(std::numbers::pi * 0.5 / 6));
  EXPECT_EQ(c.score_correlation(0, 2), 2 * std::sin(std::numbers::pi * -0.25 / 6));
  EXPECT_EQ(c.score_correlation(1, 2), 0.0);
  // The factor is lower triangular, and its rows in the slots' order reproduce R_z.
  EXPECT_TRUE(c.factor.isLowerTriangular());
  Eigen::MatrixXd L(c.slots, c.slots);
  for (int slot = 0; slot < c.slots; ++slot) L.row(slot) = c.factor.row(c.row_of_slot[std::size_t(slot)]);
  EXPECT_LT((L * L.transpose() - c.score_correlation).cwiseAbs().maxCoeff(), 1e-15);
  // r = 1 (semi-definite R_z) factors too: the two slots get one score.
  const GaussianCopula one = gaussian_copula(s, {{"a", "d", 1.0}});
  EXPECT_EQ(one.factor.row(one.row_of_slot[0]), one.factor.row(one.row_of_slot[2]));
}

TEST(GaussianCopula, RefusesWhatNoDrawWithTheseMarginalsHas) {
  // Normal–uniform beyond √(3/π): refused with the largest and what would do.
  const std::vector<Tolerance> s = {source("a", Distribution::normal), source("b", Distribution::uniform)};
  try {
    gaussian_copula(s, {{"a", "b", 0.99}});
    FAIL() << "not refused";
  } catch (const InputError& e) {
    EXPECT_STREQ(
        e.what(),
        "[[correlations]] between = [\"a\", \"b\"], r = 0.99: no joint distribution of a normal 'a' and a "
        "uniform 'b' has a correlation beyond ±0.9772 (the Monte Carlo keeps each input's distribution); "
        "accepted: |r| ≤ 0.9772, or r = 1 (fully correlated: one draw, as a group)");
  }
  EXPECT_NO_THROW(gaussian_copula(s, {{"a", "b", 1.0}}));
  // Three uniforms whose Pearson matrix is a correlation matrix (singular: 2·0.9² = 1 + 0.62) while the
  // scores' is not, as 2 sin(πr/6) > r stretches the two strong pairs more than the weak one.
  const std::vector<Tolerance> u = {source("x", Distribution::uniform), source("y", Distribution::uniform),
                                    source("z", Distribution::uniform)};
  try {
    gaussian_copula(u, {{"x", "y", 0.9}, {"x", "z", 0.9}, {"y", "z", 0.62 + 1e-9}});
    FAIL() << "not refused";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("[[correlations]]: the normal scores"), std::string::npos) << m;
    EXPECT_NE(m.find("along x, y, z"), std::string::npos) << m;
    EXPECT_NE(m.find("accepted: weaker correlations"), std::string::npos) << m;
  }
  EXPECT_THROW(gaussian_copula(u, {{"x", "nope", 0.5}}), std::invalid_argument);
}

}  // namespace
