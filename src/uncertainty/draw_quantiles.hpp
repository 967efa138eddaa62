#pragma once
// The inverse distribution functions of the Monte Carlo's draws (montecarlo.hpp), private to the library:
// written here with + − × ÷ and √ alone (IEEE-754 operations, correctly rounded on every processor, never fused:
// -ffp-contract=off), so that a draw has the same bits whatever instruction set runs it and whatever mathematical
// library is installed (the library's sin and log choose their code by the processor). Each is within 4 ulp of
// the exact value over the whole grid of uniforms the engine draws, u = (k + ½)·2⁻⁵² (its tails included), as
// tests/uncertainty/draw_quantiles_test.cpp checks against long-double references at 10⁶ points.
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "../core/cloned_loops.hpp"  // lanes::Doubles, for which sin_pi is instantiated too

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
// |x| ≤ π/2 the next term is below 2·10⁻¹⁸). T: double, or a GCC vector of doubles (the same operations in
// each lane, so the same bits).
template <class T>
inline T sin_pi(T t) {
  const T x = 3.141592653589793 * t, x2 = x * x;
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
  T s = T{} + c[9];
  for (int k = 8; k >= 0; --k) s = s * x2 + c[k];
  return x + x * (x2 * s);
}

// The arcsine's and the triangular's F⁻¹ (bound 1) of n uniforms u on the engine's grid, in SIMD lanes (the
// loops compiled for each instruction set, core/per_isa.hpp): sin(π(u − ½)), and √(2u) − 1 below ½, 1 − √(2(1 − u))
// from ½ on, each value's bits those of the scalar expression.
void arcsine_quantiles(const double* u, double* x, std::size_t n);
void triangular_quantiles(const double* u, double* x, std::size_t n);

// Φ⁻¹(u), the standard normal's quantile, for 0 < u < 1 (a normal double, as every u of the grid is): the rational
// approximations of M. J. Wichura, "Algorithm AS 241: The percentage points of the normal distribution", Applied
// Statistics 37(3), 1988 (PPND16, relative error about 10⁻¹⁶), evaluated by the compensated Horner scheme (each
// step's roundings taken exactly: exact products (Dekker's, or one fused multiply-subtract where the processor
// has it, the same exact value), Knuth's exact sums, and carried by a second sum) and divided in double-double
// arithmetic, with log_positive in its tails (draw_quantiles.cpp). normal_quantiles computes n of them in SIMD
// lanes, the loop compiled for each instruction set (core/per_isa.hpp); every value goes through the same lane
// code, so that a value's bits depend neither on the processor nor on its neighbours in the batch.
// normal_quantile is the same for one value.
void normal_quantiles(const double* u, double* x, std::size_t n);
double normal_quantile(double u);

}  // namespace ccal::draws
