// Φ⁻¹ of the Monte Carlo's draws in SIMD lanes (draw_quantiles.hpp): AS 241's rational functions by the
// compensated Horner scheme and a double-double division, so that the roundings of their evaluation stay far
// below the approximation's own 10⁻¹⁶ and the result is within 4 ulp with nothing but IEEE double operations
// and exact products (the extended precision of the x87, which did the same before, has no SIMD lanes and cost
// a quarter of a trial). The loops are in draw_quantiles_lanes.inc, compiled once per instruction set.
#include "draw_quantiles.hpp"

#include <algorithm>
#include <array>

#include "../core/cloned_loops.hpp"
#include "../core/per_isa.hpp"

namespace ccal::draws {
namespace {

#define CCAL_ISA_BODY "../uncertainty/draw_quantiles_lanes.inc"
#include "../core/per_isa_bodies.inc"

}  // namespace

void arcsine_quantiles(const double* u, double* x, std::size_t n) { CCAL_ON_THIS_ISA(arcsine_lanes(u, x, n)); }
void triangular_quantiles(const double* u, double* x, std::size_t n) {
  CCAL_ON_THIS_ISA(triangular_lanes(u, x, n));
}

void normal_quantiles(const double* u, double* x, std::size_t n) {
  constexpr std::size_t kStack = 256;
  std::uint32_t stack[kStack];
  for (std::size_t k = 0; k < n; k += kStack)
    CCAL_ON_THIS_ISA(quantiles_lanes(u + k, x + k, std::min(kStack, n - k), stack));
}

double normal_quantile(double u) {
  double x;
  normal_quantiles(&u, &x, 1);
  return x;
}

}  // namespace ccal::draws
