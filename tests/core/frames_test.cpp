// cos and sin of an error angle (core/frames.hpp, small_angle_cos_sin) against long double cosl, sinl (a
// 64-bit mantissa: 2048 times finer than a double's ulp), over the whole small-angle range and as SIMD lanes.
#include "ccal/core/frames.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "portable_uniform.hpp"

namespace ccal::test {
namespace {

// |x − reference| in units of x's ulp (the spacing of doubles at |reference|).
double ulps(double x, long double reference) {
  const double r = double(reference);
  const double ulp = std::nextafter(std::abs(r), std::numeric_limits<double>::infinity()) - std::abs(r);
  return double(std::abs((long double)x - reference) / ulp);
}

TEST(SmallAngleCosSin, WithinOneUlpOverTheWholeRange) {
  // The Taylor polynomials to q⁹ and q⁸ leave out terms below 2e-28 of s and 1.4e-33 of c at |q| < 1e-3, and
  // the nested form's inner roundings (the reciprocals 1/6, 1/20, … included) enter s and c through terms
  // below 2e-7 of them. What is left are the final roundings: c = 1 − y is rounded once (0.5 ulp); s = q·(1 −
  // y) twice, once for 1 − y and once for the product (1 ulp). Each tolerance adds 1 % for the inner
  // roundings; one term of the series left out (q⁴/24 is 4e-14 of c, q⁴/120 8e-15 of s) or a wrong
  // coefficient fails it by orders of magnitude.
  PortableUniform u{11};
  double worst_c = 0, worst_s = 0;
  auto check = [&](double q) {
    double c, s;
    small_angle_cos_sin(q, c, s);
    worst_c = std::max(worst_c, ulps(c, std::cos((long double)q)));
    worst_s = std::max(worst_s, ulps(s, std::sin((long double)q)));
  };
  for (int k = 0; k < 1'000'000; ++k) check((2 * u() - 1) * kSmallAngle);
  for (double q = kSmallAngle; q > 1e-300; q *= 0.37) {  // down the decades, both signs, to the denormals
    check(std::nextafter(q, 0.0));
    check(-std::nextafter(q, 0.0));
  }
  check(0.0);
  EXPECT_LE(worst_c, 0.51);
  EXPECT_LE(worst_s, 1.01);
}

TEST(SmallAngleCosSin, SimdLanesGiveTheScalarBits) {
  // The Monte Carlo's node loops call it on four doubles at once (run_means_nodes.cpp): each lane must be the
  // scalar call's value, bit for bit (no fused multiply-add, no reassociation across lanes).
  using Pack = double __attribute__((vector_size(4 * sizeof(double))));
  PortableUniform u{5};
  for (int k = 0; k < 10'000; ++k) {
    Pack q;
    for (int lane = 0; lane < 4; ++lane) q[lane] = (2 * u() - 1) * kSmallAngle;
    Pack c, s;
    small_angle_cos_sin(q, c, s);
    for (int lane = 0; lane < 4; ++lane) {
      double c1, s1;
      small_angle_cos_sin(double(q[lane]), c1, s1);
      ASSERT_EQ(c[lane], c1) << "q = " << q[lane];
      ASSERT_EQ(s[lane], s1) << "q = " << q[lane];
    }
  }
}

}  // namespace
}  // namespace ccal::test
