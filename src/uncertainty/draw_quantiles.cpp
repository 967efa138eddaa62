// Φ⁻¹ of the Monte Carlo's draws in SIMD lanes (draw_quantiles.hpp): AS 241's rational functions by the
// compensated Horner scheme and a double-double division, so that the roundings of their evaluation stay far below the approximation's own
// 10⁻¹⁶ and the result is within 4 ulp with nothing but IEEE double operations (the extended precision of the
// x87, which did the same before, has no SIMD lanes and cost a quarter of a trial).
#include "draw_quantiles.hpp"

#include <algorithm>
#include <array>

#include "../core/cloned_loops.hpp"

namespace ccal::draws {
namespace {

// The cloned loops' packs of eight. (Two or four packs at once, to overlap the dependent chains, were faster
// for double-double Horner; with the compensated scheme their registers spill and one pack is fastest.)
constexpr std::size_t kLanes = lanes::kWidth;
using Pack = lanes::Doubles;
using Ints = std::int64_t __attribute__((vector_size(kLanes * sizeof(std::int64_t))));

// A double-double: hi + lo with |lo| ≤ ½ ulp(hi). In lanes, every operation elementwise.
struct Wide {
  Pack hi, lo;
};

[[gnu::always_inline]] inline Pack splat(double v) { return Pack{} + v; }

// Knuth's TwoSum: s + e = a + b exactly.
[[gnu::always_inline]] inline Wide two_sum(Pack a, Pack b) {
  const Pack s = a + b, v = s - a;
  return {s, (a - (s - v)) + (b - v)};
}
// For |a| ≥ |b| (Dekker's FastTwoSum).
[[gnu::always_inline]] inline Wide fast_two_sum(Pack a, Pack b) {
  const Pack s = a + b;
  return {s, b - (s - a)};
}
// Dekker's split and product (no fused multiply-add: the same bits on every target): p + e = a·b exactly for
// the magnitudes met here (far from overflow and underflow).
[[gnu::always_inline]] inline void split(Pack a, Pack& hi, Pack& lo) {
  const Pack t = 134217729.0 * a;  // 2²⁷ + 1
  hi = t - (t - a);
  lo = a - hi;
}
[[gnu::always_inline]] inline Wide two_product(Pack a, Pack b) {
  Pack ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  const Pack p = a * b;
  return {p, ((ah * bh - p) + ah * bl + al * bh) + al * bl};
}
[[gnu::always_inline]] inline Wide multiply(Wide x, Wide y) {
  Wide p = two_product(x.hi, y.hi);
  p.lo = p.lo + (x.hi * y.lo + x.lo * y.hi);
  return fast_two_sum(p.hi, p.lo);
}
[[gnu::always_inline]] inline Wide add(Wide x, Wide y) {
  Wide s = two_sum(x.hi, y.hi);
  s.lo = s.lo + (x.lo + y.lo);
  return fast_two_sum(s.hi, s.lo);
}
// x / y: the double quotient and one correction from the exact remainder.
[[gnu::always_inline]] inline Wide divide(Wide x, Wide y) {
  const Pack q1 = x.hi / y.hi;
  const Wide p = two_product(q1, y.hi);
  const Pack r = (((x.hi - p.hi) - p.lo) + x.lo) - q1 * y.lo;
  return fast_two_sum(q1, r / y.hi);
}

// A coefficient of AS 241 (given to 20 digits) as a double-double: its value to 106 bits would need more digits
// than given, so the long double literal (64 bits) is split into two doubles exactly.
struct Coefficient {
  double hi, lo;
};
constexpr Coefficient wide(long double c) { return {double(c), double(c - (long double)double(c))}; }
using Polynomial = std::array<Coefficient, 8>;  // c₀ … c₇

constexpr Polynomial kCentralNum{wide(3.3871328727963666080L), wide(1.3314166789178437745e+2L),
                                 wide(1.9715909503065514427e+3L), wide(1.3731693765509461125e+4L),
                                 wide(4.5921953931549871457e+4L), wide(6.7265770927008700853e+4L),
                                 wide(3.3430575583588128105e+4L), wide(2.5090809287301226727e+3L)};
constexpr Polynomial kCentralDen{wide(1.0L),
                                 wide(4.2313330701600911252e+1L),
                                 wide(6.8718700749205790830e+2L),
                                 wide(5.3941960214247511077e+3L),
                                 wide(2.1213794301586595867e+4L),
                                 wide(3.9307895800092710610e+4L),
                                 wide(2.8729085735721942674e+4L),
                                 wide(5.2264952788528545610e+3L)};
constexpr Polynomial kNearNum{wide(1.42343711074968357734L),      wide(4.63033784615654529590L),
                              wide(5.76949722146069140550L),      wide(3.64784832476320460504L),
                              wide(1.27045825245236838258L),      wide(2.41780725177450611770e-1L),
                              wide(2.27238449892691845833e-2L),   wide(7.74545014278341407640e-4L)};
constexpr Polynomial kNearDen{wide(1.0L),                         wide(2.05319162663775882187L),
                              wide(1.67638483018380384940L),      wide(6.89767334985100004550e-1L),
                              wide(1.48103976427480074590e-1L),   wide(1.51986665636164571966e-2L),
                              wide(5.47593808499534494600e-4L),   wide(1.05075007164441684324e-9L)};
constexpr Polynomial kFarNum{wide(6.65790464350110377720L),       wide(5.46378491116411436990L),
                             wide(1.78482653991729133580L),       wide(2.96560571828504891230e-1L),
                             wide(2.65321895265761230930e-2L),    wide(1.24266094738807843860e-3L),
                             wide(2.71155556874348757815e-5L),    wide(2.01033439929228813265e-7L)};
constexpr Polynomial kFarDen{wide(1.0L),                          wide(5.99832206555887937690e-1L),
                             wide(1.36929880922735805310e-1L),    wide(1.48753612908506148525e-2L),
                             wide(7.86869131145613259100e-4L),    wide(1.84631831751005468180e-5L),
                             wide(1.42151175831644588870e-7L),    wide(2.04426310338993978564e-15L)};

// Σ c_k r^k by the compensated Horner scheme (S. Graillat, Ph. Langlois, N. Louvet, "Algorithms for accurate,
// validated and fast polynomial evaluation", Japan J. Indust. Appl. Math. 26, 2009): Horner's rule in double
// with each step's rounding errors taken exactly (Dekker's product, Knuth's sum) and carried by a second Horner
// sum in double, which also takes the coefficients' and r's low parts to first order; the result as a
// double-double, as accurate as Horner's rule in twice the precision. A third fewer operations than
// double-double Horner, whose renormalisations it leaves out.
// The coefficients in lanes: c_k everywhere, or where is_far holds the far polynomial's.
struct Coefficients {
  const Polynomial& near;
  const Polynomial* far = nullptr;
  Ints is_far{};
  [[gnu::always_inline]] Pack hi(std::size_t k) const {
    return far ? (is_far ? splat((*far)[k].hi) : splat(near[k].hi)) : splat(near[k].hi);
  }
  [[gnu::always_inline]] Pack lo(std::size_t k) const {
    return far ? (is_far ? splat((*far)[k].lo) : splat(near[k].lo)) : splat(near[k].lo);
  }
};
[[gnu::always_inline]] inline Wide compensated_horner(const Coefficients& c, Wide r) {
  Pack rh, rl;
  split(r.hi, rh, rl);
  Pack s = c.hi(7), e = c.lo(7);
  for (int k = 6; k >= 0; --k) {
    const auto K = std::size_t(k);
    Pack sh, sl;
    split(s, sh, sl);
    const Pack p = s * r.hi;
    const Pack product_error = ((sh * rh - p) + sh * rl + sl * rh) + sl * rl;
    const Pack ck = c.hi(K), t = p + ck, v = t - p;
    const Pack sum_error = (p - (t - v)) + (ck - v);
    e = e * r.hi + (s * r.lo + ((product_error + sum_error) + c.lo(K)));
    s = t;
  }
  return fast_two_sum(s, e);
}

// The central region, |u − ½| ≤ 0.425: x = q·A(r)/B(r), r = 0.180625 − q² (q² exact as a double-double, the
// constant 0.425² to 106 bits: near |q| = 0.425 r cancels, and A's slope would lift a double r's rounding to
// 2 ulp of x). A and B by the compensated Horner scheme: their coefficients and r are positive, every sum
// adds positive terms.
[[gnu::always_inline]] inline Pack central(Pack u) {
  const Pack q = u - 0.5;  // exact on the grid
  const Wide q2 = two_product(q, q);
  constexpr Coefficient kEdge = wide(0.180625L);
  const Wide r = add(Wide{splat(kEdge.hi), splat(kEdge.lo)}, Wide{-q2.hi, -q2.lo});
  const Wide ratio = divide(compensated_horner({kCentralNum}, r), compensated_horner({kCentralDen}, r));
  const Wide x = multiply(ratio, Wide{q, Pack{}});
  return x.hi;
}

// ln x of normal doubles x > 0, as log_positive (draw_quantiles.hpp) in lanes: the same operations.
[[gnu::always_inline]] inline Pack log_lanes(Pack x) {
  Ints bits;
  std::memcpy(&bits, &x, sizeof bits);
  Ints e = ((bits >> 52) & 0x7ff) - 1023;
  bits = (bits & 0x000fffffffffffffLL) | 0x3ff0000000000000LL;
  Pack m;
  std::memcpy(&m, &bits, sizeof m);
  const Ints high = m > 1.4142135623730951;
  m = high ? m * 0.5 : m;
  e = high ? e + 1 : e;
  const Pack f = (m - 1) / (m + 1), f2 = f * f;
  Pack s = splat(1.0 / 23);
  for (int k = 21; k >= 3; k -= 2) s = s * f2 + 1.0 / k;
  const Pack series = 2 * f + 2 * f * (f2 * s);
  const Pack de = __builtin_convertvector(e, Pack);
  constexpr double kLn2High = 6.93147180369123816490e-01;
  constexpr double kLn2Low = 1.90821492927058770002e-10;
  return (de * kLn2High + series) + de * kLn2Low;
}

// The tails: r = √(−ln p), p the smaller of u and 1 − u (exact for u ≥ ½), x = ±A(w)/B(w) with w = r − 1.6
// (r ≤ 5) or r − 5, each as a double-double, A and B by the compensated Horner scheme (w changes sign: the
// sums alternate, which the scheme's exact error terms carry).
[[gnu::always_inline]] inline Pack tail(Pack u) {
  const Pack q = u - 0.5;
  const Ints lower = q < 0;
  const Pack minus_log = -log_lanes(lower ? u : 1 - u);
  Pack r;
  for (std::size_t l = 0; l < kLanes; ++l) r[l] = __builtin_sqrt(minus_log[l]);  // correctly rounded
  const Ints is_far = r > 5;
  constexpr Coefficient kNearShift = wide(1.6L);
  const Pack shift_hi = is_far ? splat(5.0) : splat(kNearShift.hi);
  const Pack shift_lo = is_far ? Pack{} : splat(kNearShift.lo);
  Wide w = two_sum(r, -shift_hi);
  w = fast_two_sum(w.hi, w.lo - shift_lo);
  const Wide x = divide(compensated_horner({kNearNum, &kFarNum, is_far}, w),
                        compensated_horner({kNearDen, &kFarDen, is_far}, w));
  return lower ? -x.hi : x.hi;
}

// n quantiles: the central values and the tail values each gathered into lanes (a pack's lanes all take one
// branch), the last pack of each padded with u = ½ and 0.1.
CCAL_CLONED CCAL_FLATTEN void quantiles_lanes(const double* u, double* x, std::size_t n, std::uint32_t* index) {
  std::size_t n_central = 0, n_tail = n;
  for (std::size_t i = 0; i < n; ++i) {
    const double q = u[i] - 0.5;
    if (q <= 0.425 && q >= -0.425)
      index[n_central++] = std::uint32_t(i);
    else
      index[--n_tail] = std::uint32_t(i);
  }
  const auto run = [&](std::size_t begin, std::size_t end, double pad, auto evaluate) {
    for (std::size_t k = begin; k < end; k += kLanes) {
      Pack v = splat(pad);
      const std::size_t m = std::min(kLanes, end - k);
      for (std::size_t l = 0; l < m; ++l) v[l] = u[index[k + l]];
      const Pack y = evaluate(v);
      for (std::size_t l = 0; l < m; ++l) x[index[k + l]] = y[l];
    }
  };
  run(0, n_central, 0.5, [](Pack v) { return central(v); });
  run(n_central, n, 0.1, [](Pack v) { return tail(v); });
}

// Eight lanes at a time (the cloned loops' packs), the last pack padded with u = ½.
using Eight = lanes::Doubles;
template <class F>
[[gnu::always_inline]] inline void in_eights(const double* u, double* x, std::size_t n, F evaluate) {
  constexpr std::size_t w = lanes::kWidth;
  std::size_t k = 0;
  for (; k + w <= n; k += w) lanes::store(x + k, evaluate(lanes::load<Eight>(u + k)));
  if (k == n) return;
  double in[w], out[w];
  for (std::size_t l = 0; l < w; ++l) in[l] = k + l < n ? u[k + l] : 0.5;
  lanes::store(out, evaluate(lanes::load<Eight>(in)));
  for (std::size_t l = 0; k + l < n; ++l) x[k + l] = out[l];
}

CCAL_CLONED CCAL_FLATTEN void arcsine_lanes(const double* u, double* x, std::size_t n) {
  in_eights(u, x, n, [](Eight v) { return sin_pi(v - 0.5); });
}

CCAL_CLONED CCAL_FLATTEN void triangular_lanes(const double* u, double* x, std::size_t n) {
  in_eights(u, x, n, [](Eight v) {
    const auto lower = v < 0.5;
    const Eight a = lower ? 2.0 * v : 2.0 * (1.0 - v);
    Eight r;
    for (std::size_t l = 0; l < lanes::kWidth; ++l) r[l] = __builtin_sqrt(a[l]);  // correctly rounded
    return lower ? r - 1.0 : 1.0 - r;
  });
}

}  // namespace

void arcsine_quantiles(const double* u, double* x, std::size_t n) { arcsine_lanes(u, x, n); }
void triangular_quantiles(const double* u, double* x, std::size_t n) { triangular_lanes(u, x, n); }

void normal_quantiles(const double* u, double* x, std::size_t n) {
  constexpr std::size_t kStack = 256;
  std::uint32_t stack[kStack];
  for (std::size_t k = 0; k < n; k += kStack) quantiles_lanes(u + k, x + k, std::min(kStack, n - k), stack);
}

double normal_quantile(double u) {
  double x;
  normal_quantiles(&u, &x, 1);
  return x;
}

}  // namespace ccal::draws
