// The inverse distribution functions of the Monte Carlo's draws (src/uncertainty/draw_quantiles.hpp) against
// long-double references, each over 10⁶ points of its domain with its tails: within 4 ulp of the exact value (the
// promise the header makes; their errors are a few roundings of a series or rational function, about 1–2 ulp),
// and exactly odd where the engine relies on it.
#include <gtest/gtest.h>

#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <vector>

#include "../../src/uncertainty/draw_quantiles.hpp"
#include "portable_uniform.hpp"

namespace ccal {
namespace {

// |x − exact| in units of the last place of the exact value rounded to double.
double ulps(double x, long double exact) {
  const double e = double(exact);
  const double ulp = std::nextafter(std::abs(e), INFINITY) - std::abs(e);
  return double(std::abs((long double)x - exact) / ulp);
}

// The engine's grid of uniforms: u = (k + ½)·2⁻⁵², k < 2⁵².
double grid(std::uint64_t k) { return (double(k) + 0.5) * 0x1p-52; }

constexpr double kMaxUlps = 4;

TEST(DrawQuantiles, NormalQuantileIsWithinFourUlpOverTheGridAndItsTails) {
  test::PortableUniform random{52};
  const boost::math::normal_distribution<long double> normal;
  double worst = 0, worst_u = 0;
  const auto check = [&](double u) {
    const double e = ulps(draws::normal_quantile(u), boost::math::quantile(normal, (long double)u));
    if (e > worst) worst = e, worst_u = u;
    ASSERT_EQ(draws::normal_quantile(1 - u), -draws::normal_quantile(u)) << u;  // exactly odd on the grid
  };
  for (int i = 0; i < 500000; ++i) check(grid(std::uint64_t(random() * 0x1p52)));
  // The tails, u from 2⁻⁵³ (the grid's first point, Φ⁻¹ = −8.2) up to ½, log-uniformly: the tail branches.
  for (int i = 0; i < 400000; ++i) check(grid(std::uint64_t(std::exp2(52 * random()))));
  for (std::uint64_t k = 0; k < 100000; ++k) check(grid(k));  // the grid's first points themselves
  EXPECT_LE(worst, kMaxUlps) << "at u = " << worst_u;
  RecordProperty("normal_worst_ulps", std::to_string(worst));
}

// normal_quantiles computes a batch in SIMD lanes, its central and tail values gathered into lanes of their
// own: each value's bits are normal_quantile's of it alone, whatever batch, order and neighbours it has.
TEST(DrawQuantiles, NormalQuantilesInLanesAreEachValuesOwn) {
  test::PortableUniform random{55};
  std::vector<double> u;
  for (int i = 0; i < 3000; ++i)
    u.push_back(i % 3 == 0 ? grid(std::uint64_t(std::exp2(52 * random()))) : grid(std::uint64_t(random() * 0x1p52)));
  u.push_back(grid(0));
  u.push_back(1 - grid(0));
  std::vector<double> x(u.size());
  draws::normal_quantiles(u.data(), x.data(), u.size());
  for (std::size_t i = 0; i < u.size(); ++i) ASSERT_EQ(x[i], draws::normal_quantile(u[i])) << u[i];
  // Another batch: reversed, offset by one, of odd length.
  std::vector<double> v(u.rbegin(), u.rend() - 1), y(v.size());
  draws::normal_quantiles(v.data(), y.data(), v.size());
  for (std::size_t i = 0; i < v.size(); ++i) ASSERT_EQ(y[i], x[u.size() - 1 - i]) << v[i];
  EXPECT_EQ(draws::normal_quantile(0.5), 0.0);
  EXPECT_EQ(x[u.size() - 2], -x[u.size() - 1]);
}

// The arcsine's and the triangular's F⁻¹ in lanes: each value the scalar expression's bits, for any length
// (whole packs of eight and a padded rest), the ends of the grid included.
TEST(DrawQuantiles, ArcsineAndTriangularInLanesAreTheScalarExpressions) {
  test::PortableUniform random{56};
  for (std::size_t n : {1u, 7u, 8u, 13u, 1000u}) {
    std::vector<double> u(n), a(n), t(n);
    for (double& v : u) v = grid(std::uint64_t(random() * 0x1p52));
    u[0] = grid(0);
    u[n - 1] = 1 - grid(0);
    draws::arcsine_quantiles(u.data(), a.data(), n);
    draws::triangular_quantiles(u.data(), t.data(), n);
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(a[i], draws::sin_pi(u[i] - 0.5)) << u[i];
      ASSERT_EQ(t[i], u[i] < 0.5 ? std::sqrt(2.0 * u[i]) - 1.0 : 1.0 - std::sqrt(2.0 * (1.0 - u[i]))) << u[i];
    }
  }
}

TEST(DrawQuantiles, SinPiIsWithinFourUlpOnHalfATurn) {
  test::PortableUniform random{53};
  double worst = 0, worst_t = 0;
  const auto check = [&](double t) {
    const double e = ulps(draws::sin_pi(t), sinl(std::numbers::pi_v<long double> * (long double)t));
    if (e > worst) worst = e, worst_t = t;
    ASSERT_EQ(draws::sin_pi(-t), -draws::sin_pi(t)) << t;
  };
  for (int i = 0; i < 600000; ++i) check(grid(std::uint64_t(random() * 0x1p52)) - 0.5);
  for (int i = 0; i < 200000; ++i) check(0x1p-53 * std::exp2(52 * random()));   // near 0 (u near ½)
  for (int i = 0; i < 200000; ++i) check(0.5 - 0x1p-53 * std::exp2(52 * random()));  // near the ends
  EXPECT_LE(worst, kMaxUlps) << "at t = " << worst_t;
  EXPECT_EQ(draws::sin_pi(0.5), 1.0);
}

TEST(DrawQuantiles, LogIsWithinFourUlpOverTheNormalDoubles) {
  test::PortableUniform random{54};
  double worst = 0, worst_x = 0;
  const auto check = [&](double x) {
    const double e = ulps(draws::log_positive(x), logl((long double)x));
    if (e > worst) worst = e, worst_x = x;
  };
  for (int i = 0; i < 600000; ++i) check(std::ldexp(1 + random(), int(2044 * random()) - 1021));
  for (int i = 0; i < 400000; ++i) check(1 + (random() - 0.5) * 0x1p-10);  // near 1, where ln x → 0
  EXPECT_LE(worst, kMaxUlps) << "at x = " << worst_x;
  EXPECT_EQ(draws::log_positive(1.0), 0.0);
}

}  // namespace
}  // namespace ccal
