// The Monte Carlo's samplers checked as distributions, not bits: each source's draws (normal, uniform,
// triangular, arcsine, and a normal and an arcsine correlated by the Gaussian copula) against the exact
// distribution function (one-sample Kolmogorov–Smirnov) and against the earlier samplers (the normal's
// AS 241 in the x87's extended precision, the others by the C library's long double functions) drawn from
// a generator of their own (two-sample Kolmogorov–Smirnov), and their first four moments against the exact
// ones. At 2·10⁵ draws (under a second); CCAL_SAMPLER_DRAWS=10000000 runs the same at 10⁷ and prints each
// figure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "ccal/uncertainty/montecarlo.hpp"
#include "monte_carlo_support.hpp"
#include "portable_uniform.hpp"

namespace ccal {
namespace {

using ccal::test::source;

// The normal quantile as the engine computed it before the draws went into lanes: AS 241 in long double.
long double earlier_normal(long double u) {
  const long double q = u - 0.5L;
  const long double a[] = {3.3871328727963666080L,     1.3314166789178437745e+2L, 1.9715909503065514427e+3L,
                           1.3731693765509461125e+4L, 4.5921953931549871457e+4L, 6.7265770927008700853e+4L,
                           3.3430575583588128105e+4L, 2.5090809287301226727e+3L};
  const long double b[] = {1.0L,                      4.2313330701600911252e+1L, 6.8718700749205790830e+2L,
                           5.3941960214247511077e+3L, 2.1213794301586595867e+4L, 3.9307895800092710610e+4L,
                           2.8729085735721942674e+4L, 5.2264952788528545610e+3L};
  const long double c[] = {1.42343711074968357734L,     4.63033784615654529590L,     5.76949722146069140550L,
                           3.64784832476320460504L,     1.27045825245236838258L,     2.41780725177450611770e-1L,
                           2.27238449892691845833e-2L,  7.74545014278341407640e-4L};
  const long double d[] = {1.0L,                        2.05319162663775882187L,     1.67638483018380384940L,
                           6.89767334985100004550e-1L,  1.48103976427480074590e-1L,  1.51986665636164571966e-2L,
                           5.47593808499534494600e-4L,  1.05075007164441684324e-9L};
  const long double e[] = {6.65790464350110377720L,     5.46378491116411436990L,     1.78482653991729133580L,
                           2.96560571828504891230e-1L,  2.65321895265761230930e-2L,  1.24266094738807843860e-3L,
                           2.71155556874348757815e-5L,  2.01033439929228813265e-7L};
  const long double f[] = {1.0L,                        5.99832206555887937690e-1L,  1.36929880922735805310e-1L,
                           1.48753612908506148525e-2L,  7.86869131145613259100e-4L,  1.84631831751005468180e-5L,
                           1.42151175831644588870e-7L,  2.04426310338993978564e-15L};
  const auto ratio = [](const long double* n, const long double* m, long double t) {
    long double x = n[7], y = m[7];
    for (int k = 6; k >= 0; --k) x = x * t + n[k], y = y * t + m[k];
    return x / y;
  };
  if (std::abs(q) <= 0.425L) return q * ratio(a, b, 0.180625L - q * q);
  const long double r = std::sqrt(-std::log(q < 0 ? u : 1 - u));
  const long double x = r <= 5 ? ratio(c, d, r - 1.6L) : ratio(e, f, r - 5.0L);
  return q < 0 ? -x : x;
}

// F⁻¹ of each distribution of bound 1, earlier, and its distribution function.
double earlier_quantile(Distribution dist, long double u) {
  switch (dist) {
    case Distribution::normal:
      return double(earlier_normal(u));
    case Distribution::uniform:
      return double(2 * u - 1);
    case Distribution::triangular:
      return double(u < 0.5L ? std::sqrt(2 * u) - 1 : 1 - std::sqrt(2 * (1 - u)));
    case Distribution::arcsine:
      return double(std::sin(std::numbers::pi_v<long double> * (u - 0.5L)));
  }
  return 0;
}
double cdf(Distribution dist, double x) {
  switch (dist) {
    case Distribution::normal:
      return 0.5 * std::erfc(-x / std::numbers::sqrt2);
    case Distribution::uniform:
      return std::clamp((x + 1) / 2, 0.0, 1.0);
    case Distribution::triangular:
      return x < 0 ? 0.5 * (x + 1) * (x + 1) : 1 - 0.5 * (1 - x) * (1 - x);
    case Distribution::arcsine:
      return 0.5 + std::asin(std::clamp(x, -1.0, 1.0)) / std::numbers::pi;
  }
  return 0;
}
// The standard deviation and the kurtosis of each (bound 1; all are symmetric: skewness 0).
double sigma_of(Distribution d) {
  const double s[] = {1.0, 1 / std::sqrt(3.0), 1 / std::sqrt(6.0), 1 / std::numbers::sqrt2};
  return s[int(d)];
}
double kurtosis_of(Distribution d) {
  const double k[] = {3.0, 1.8, 2.4, 1.5};
  return k[int(d)];
}

// D of one sorted sample against F, and of two sorted samples of the same size.
double ks_one(const std::vector<double>& x, Distribution d) {
  double D = 0;
  const double n = double(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double F = cdf(d, x[i]);
    D = std::max({D, F - double(i) / n, double(i + 1) / n - F});
  }
  return D;
}
double ks_two(const std::vector<double>& a, const std::vector<double>& b) {
  double D = 0;
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const double v = std::min(a[i], b[j]);
    while (i < a.size() && a[i] == v) ++i;
    while (j < b.size() && b[j] == v) ++j;
    D = std::max(D, std::abs(double(i) / double(a.size()) - double(j) / double(b.size())));
  }
  return D;
}

struct Moments {
  double mean = 0, sd = 0, skewness = 0, kurtosis = 0;
};
Moments moments_of(const std::vector<double>& x) {
  const double n = double(x.size());
  long double m = 0;
  for (double v : x) m += v;
  m /= n;
  long double m2 = 0, m3 = 0, m4 = 0;
  for (double v : x) {
    const long double d = v - m, d2 = d * d;
    m2 += d2, m3 += d2 * d, m4 += d2 * d2;
  }
  m2 /= n, m3 /= n, m4 /= n;
  return {double(m), double(std::sqrt(m2)), double(m3 / std::pow(m2, 1.5L)), double(m4 / (m2 * m2))};
}

TEST(MonteCarloSamplers, EachDistributionIsItsOwnAndTheEarlierSamplersAtFourMoments) {
  const char* asked = std::getenv("CCAL_SAMPLER_DRAWS");
  const std::uint64_t n = asked ? std::strtoull(asked, nullptr, 10) : 200000;
  const bool print = asked != nullptr;
  // The independent sources' draws (each by its F⁻¹), and a pair correlated by the copula: a run with any
  // [[correlations]] draws every source through the copula, so the pair has a run of its own.
  const std::vector<Tolerance> independent = {
      source("n", 1.0, Distribution::normal), source("u", 1.0, Distribution::uniform),
      source("t", 1.0, Distribution::triangular), source("a", 1.0, Distribution::arcsine)};
  const std::vector<Tolerance> pair = {source("cn", 1.0, Distribution::normal),
                                       source("ca", 1.0, Distribution::arcsine)};
  const double r = 0.5;  // the copula pair's configured Pearson correlation
  PropagationOptions o;
  o.trials = n;
  o.seed = 2024;
  o.keep_samples = true;
  o.threads = 2;
  const MonteCarloDetail alone = run_monte_carlo(independent, {}, 4, {}, ccal::test::identity, o);
  o.seed = 2025;  // another seed: the pair's first score would otherwise be the independent normal's draw
  const MonteCarloDetail copula = run_monte_carlo(pair, {{"cn", "ca", r}}, 2, {}, ccal::test::identity, o);
  std::vector<Tolerance> sources = independent;
  sources.insert(sources.end(), pair.begin(), pair.end());
  const auto sample = [&](std::size_t s) {
    const Eigen::MatrixXd& m = s < 4 ? alone.samples : copula.samples;
    const auto col = m.col(Eigen::Index(s < 4 ? s : s - 4));
    return std::vector<double>(col.begin(), col.end());
  };
  // Critical values at α = 10⁻³ (the asymptotic Kolmogorov distribution: 1.949): D√n, and D√(n/2) for two.
  const double critical = 1.949;
  test::PortableUniform random{99};
  for (std::size_t s = 0; s < sources.size(); ++s) {
    const Distribution d = sources[s].distribution;
    std::vector<double> now = sample(s);
    std::sort(now.begin(), now.end());
    std::vector<double> before(n);
    for (double& v : before) v = earlier_quantile(d, (std::floor(random() * 0x1p52) + 0.5L) * 0x1p-52L);
    std::sort(before.begin(), before.end());
    const double one = ks_one(now, d) * std::sqrt(double(n)), two = ks_two(now, before) * std::sqrt(n / 2.0);
    const Moments m = moments_of(now), e = moments_of(before);
    // Each moment within 5 of its standard errors at n: σ/√n for the mean, σ√((κ − 1)/(4n)) for σ, √(6/n) for
    // the skewness, √(24/n) for the kurtosis (the normal's; the others' are smaller).
    const double sigma = sigma_of(d), kappa = kurtosis_of(d), rn = std::sqrt(double(n));
    EXPECT_LT(one, critical) << sources[s].id;
    EXPECT_LT(two, critical) << sources[s].id;
    EXPECT_NEAR(m.mean, 0, 5 * sigma / rn) << sources[s].id;
    EXPECT_NEAR(m.sd, sigma, 5 * sigma * std::sqrt((kappa - 1) / 4) / rn) << sources[s].id;
    EXPECT_NEAR(m.skewness, 0, 5 * std::sqrt(6.0) / rn) << sources[s].id;
    EXPECT_NEAR(m.kurtosis, kappa, 5 * std::sqrt(24.0) / rn) << sources[s].id;
    if (print)
      std::printf("%-3s %-10s n=%llu  KS vs F: D√n=%.3f  vs earlier: D√(n/2)=%.3f  mean %+.2e (%+.2e)  sd %.6f (%.6f, "
                  "exact %.6f)  skew %+.4f (%+.4f)  kurt %.4f (%.4f, exact %.1f)\n",
                  sources[s].id.c_str(), std::string(distribution_name(d)).c_str(), (unsigned long long)n, one, two,
                  m.mean, e.mean, m.sd, e.sd, sigma, m.skewness, e.skewness, m.kurtosis, e.kurtosis, kappa);
  }
  // The copula pair's Pearson r within 5 standard errors, (1 − r²)/√n.
  const double got = copula.correlation(0, 1);
  EXPECT_NEAR(got, r, 5 * (1 - r * r) / std::sqrt(double(n)));
  if (print) std::printf("copula pair cn, ca: Pearson r = %.5f (configured %.2f)\n", got, r);
}

}  // namespace
}  // namespace ccal
