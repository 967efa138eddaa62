#pragma once
// The inverse distribution functions of the Monte Carlo's draws (montecarlo.hpp), private to the library:
// written here with + − × ÷ and √ alone (IEEE-754 operations, correctly rounded on every processor, never fused:
// -ffp-contract=off), so that a draw has the same bits whatever instruction set runs it and whatever mathematical
// library is installed (the library's sin and log choose their code by the processor). Each is within 4 ulp of
// the exact value over the whole grid of uniforms the engine draws, u = (k + ½)·2⁻⁵² (its tails included), as
// tests/uncertainty/draw_quantiles_test.cpp checks against long-double references at 10⁶ points.
#include <cstdint>
#include <cstring>

namespace ccal::draws {

// ln x for a finite x > 0 (a normal double): x = 2ᵉ m with m in [√½, √2), ln m = 2 atanh f with f = (m − 1)/(m + 1),
// |f| ≤ 0.1716, by its series to f²³ (the next term is below 10⁻¹⁸ of the sum), and e ln 2 in two parts whose
// first has 32 bits, so that e times it is exact.
inline double log_positive(double x) {
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  int e = int((bits >> 52) & 0x7ff) - 1023;
  bits = (bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL;  // m in [1, 2)
  double m;
  std::memcpy(&m, &bits, sizeof m);
  if (m > 1.4142135623730951) {
    m *= 0.5;
    ++e;
  }
  const double f = (m - 1) / (m + 1), f2 = f * f;
  // 2 atanh f = 2f (1 + f²/3 + f⁴/5 + …)
  double s = 1.0 / 23;
  for (int k = 21; k >= 3; k -= 2) s = s * f2 + 1.0 / k;
  const double series = 2 * f + 2 * f * (f2 * s);
  constexpr double kLn2High = 6.93147180369123816490e-01;  // ln 2 to 32 bits (0x3fe62e42fee00000)
  constexpr double kLn2Low = 1.90821492927058770002e-10;   // ln 2 − kLn2High
  return (double(e) * kLn2High + series) + double(e) * kLn2Low;
}

// sin(π t) for |t| ≤ ½ (the arcsine's F⁻¹ at u = t + ½): x = π t and the Taylor series of sin x to x²¹ (on
// |x| ≤ π/2 the next term is below 2·10⁻¹⁸).
inline double sin_pi(double t) {
  const double x = 3.141592653589793 * t, x2 = x * x;
  // 1/(2k + 1)! for k = 1 … 10, with alternating signs
  constexpr double c[] = {-1.0 / 6,
                          1.0 / 120,
                          -1.0 / 5040,
                          1.0 / 362880,
                          -1.0 / 39916800,
                          1.0 / 6227020800,
                          -1.0 / 1307674368000,
                          1.0 / 355687428096000,
                          -1.0 / 121645100408832000,
                          1.0 / 51090942171709440000.0};
  double s = c[9];
  for (int k = 8; k >= 0; --k) s = s * x2 + c[k];
  return x + x * (x2 * s);
}

// Φ⁻¹(u), the standard normal's quantile, for 0 < u < 1 (a normal double, as every u of the grid is): the rational
// approximations of M. J. Wichura, "Algorithm AS 241: The percentage points of the normal distribution", Applied
// Statistics 37(3), 1988 (PPND16, relative error about 10⁻¹⁶), with log_positive in its tails.
inline double normal_quantile(double u) {
  const double q = u - 0.5;  // exact on the grid
  // The rational functions in the x87's extended precision (IEEE operations on 64-bit significands, the same on
  // every x86-64 processor; in double their roundings reach 6 ulp), their coefficients as AS 241 gives them.
  using Wide = long double;
  if (q <= 0.425 && q >= -0.425) {
    constexpr Wide kCentral[2][8] = {
        {3.3871328727963666080L, 1.3314166789178437745e+2L, 1.9715909503065514427e+3L, 1.3731693765509461125e+4L,
         4.5921953931549871457e+4L, 6.7265770927008700853e+4L, 3.3430575583588128105e+4L,
         2.5090809287301226727e+3L},
        {1.0L, 4.2313330701600911252e+1L, 6.8718700749205790830e+2L, 5.3941960214247511077e+3L,
         2.1213794301586595867e+4L, 3.9307895800092710610e+4L, 2.8729085735721942674e+4L,
         5.2264952788528545610e+3L}};
    const Wide r = 0.180625L - Wide(q) * Wide(q);
    Wide num = kCentral[0][7], den = kCentral[1][7];
    for (int k = 6; k >= 0; --k) {
      num = num * r + kCentral[0][k];
      den = den * r + kCentral[1][k];
    }
    return double(Wide(q) * num / den);
  }
  // The tail: r = √(−ln p) of the smaller of u and 1 − u (1 − u is exact for u ≥ ½).
  const double r = __builtin_sqrt(-log_positive(q < 0 ? u : 1 - u));
  constexpr Wide kNear[2][8] = {
      {1.42343711074968357734L, 4.63033784615654529590L, 5.76949722146069140550L, 3.64784832476320460504L,
       1.27045825245236838258L, 2.41780725177450611770e-1L, 2.27238449892691845833e-2L,
       7.74545014278341407640e-4L},
      {1.0L, 2.05319162663775882187L, 1.67638483018380384940L, 6.89767334985100004550e-1L,
       1.48103976427480074590e-1L, 1.51986665636164571966e-2L, 5.47593808499534494600e-4L,
       1.05075007164441684324e-9L}};
  constexpr Wide kFar[2][8] = {
      {6.65790464350110377720L, 5.46378491116411436990L, 1.78482653991729133580L, 2.96560571828504891230e-1L,
       2.65321895265761230930e-2L, 1.24266094738807843860e-3L, 2.71155556874348757815e-5L,
       2.01033439929228813265e-7L},
      {1.0L, 5.99832206555887937690e-1L, 1.36929880922735805310e-1L, 1.48753612908506148525e-2L,
       7.86869131145613259100e-4L, 1.84631831751005468180e-5L, 1.42151175831644588870e-7L,
       2.04426310338993978564e-15L}};
  const bool near = r <= 5;
  const Wide(&c)[2][8] = near ? kNear : kFar;
  const Wide w = Wide(r) - (near ? 1.6L : 5.0L);
  Wide num = c[0][7], den = c[1][7];
  for (int k = 6; k >= 0; --k) {
    num = num * w + c[0][k];
    den = den * w + c[1][k];
  }
  const double x = double(num / den);
  return q < 0 ? -x : x;
}

}  // namespace ccal::draws
