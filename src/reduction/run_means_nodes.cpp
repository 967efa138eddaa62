#include "run_means_nodes.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include "../core/cloned_loops.hpp"
#include "ccal/core/frames.hpp"
#include "ccal/reduction/detail/spectral_weights.hpp"
#include "run_means_lanes.hpp"

namespace ccal::run_nodes {

namespace {

// The main axis's link at fast node j: at the tabulated nominal angle, or with the drive's ripple
// (kinematics.hpp, RunMotion::add_ripple: θ1 = θ1ⁿ + δ1, θ̇1 = q̇ + q̇ r1, θ̈1 = q̇² r1′), whose δ1, δ̇1, δ̈1 are
// kept for a phase-locked platform.
template <int kOrder, bool kRipple, bool kTiny, class T>
[[gnu::always_inline]] inline JointLink<T> main_link(const MainAxisInputs& in,
                                                     const JointCoefficients<kOrder>& coefficients, int j,
                                                     MainAxisNodes& out) {
  T c = load<T>(in.cos_theta + j), s = load<T>(in.sin_theta + j);
  const T nominal_rate = load<T>(in.rate + j);
  if constexpr (!kRipple) {
    return joint_link<kOrder, T, T, kTiny>(coefficients, c, s, nominal_rate);
  } else {
    const RippleSeries<T> r = ripple_series<kOrder>(in.ripple, in.order, c, s);
    const T rate_ripple = nominal_rate * r.relative, acc = (nominal_rate * nominal_rate) * r.slope;
    const auto J = std::size_t(j);
    store(&out.ripple_angle[J], r.angle);
    store(&out.ripple_rate[J], rate_ripple);
    store(&out.ripple_acc[J], acc);
    turn_by<kTiny>(c, s, r.angle);
    const T rate = nominal_rate + rate_ripple;
    return joint_link<kOrder, T, T, kTiny>(coefficients, c, s, rate, &acc);
  }
}

template <int kOrder, bool kRipple, bool kTiny, class T>
[[gnu::always_inline]] inline void main_axis_loop(const MainAxisInputs& in, MainAxisNodes& out) {
  const JointCoefficients<kOrder> coefficients{in.coefficients, in.order};
  const Columns<> B(in.RB);
  const V3<T> coriolis_1t = broadcast<T>(in.coriolis_1t), gravity_1t = broadcast<T>(in.gravity_1t),
              earth_1t = broadcast<T>(in.earth_1t);
  for (int j = 0; j < in.nodes; j += kLanes<T>) {
    const JointLink<T> main = main_link<kOrder, kRipple, kTiny, T>(in, coefficients, j, out);
    const PointMotion<T> o3t = point_motion(main, V3<T>{load<T>(in.arm_x + j), T{} + in.pB.y, T{} + in.pB.z});
    const V3<T> F0 = o3t.a + 2.0 * cross(coriolis_1t, o3t.v) + in.g * gravity_1t;
    // x in frame-3t coordinates: R_Bᵀ (R_jointᵀ x).
    const auto J = std::size_t(j);
    set(out.F0, J, B.transpose_times(to_local(main, F0)));
    set(out.W, J, B.transpose_times(to_local(main, main.w)));
    set(out.dW, J, B.transpose_times(to_local(main, main.dw)));
    set(out.coriolis, J, B.transpose_times(to_local(main, coriolis_1t)));
    set(out.W_total, J, B.transpose_times(to_local(main, main.w + earth_1t)));
  }
}

// The platform's link at node j: at its nominal angle (cos γⁿ = cg, sin γⁿ = sg), or with its own ripple
// and, when phase-locked, the main axis's angle error (RunMotion::add_ripple: γ = γⁿ + δ3 − δ1, γ̇ = γ̇ⁿ +
// γ̇ⁿ r3 − δ̇1, γ̈ = (γ̇ⁿ)² r3′ − δ̈1).
template <int kOrder, bool kRipple, bool kTiny, class T>
[[gnu::always_inline]] inline JointLink<T> platform_link(const PlatformInputs& in,
                                                         const JointCoefficients<kOrder>& coefficients,
                                                         const MainAxisNodes& main, int j,
                                                         const T& cg_nominal, const T& sg_nominal) {
  // By reference: a 64-byte vector passed by value draws GCC's ABI note in baseline code.
  T cg = cg_nominal, sg = sg_nominal;
  const T nominal_rate = load<T>(in.rate + j);
  if constexpr (!kRipple) {
    return joint_link<kOrder, T, T, kTiny>(coefficients, cg, sg, nominal_rate);
  } else {
    T delta{}, rate = nominal_rate, acc{};
    if (in.ripple) {
      const RippleSeries<T> r = ripple_series<kOrder>(in.ripple, in.order, cg, sg);
      delta = r.angle;
      rate += nominal_rate * r.relative;
      acc = (nominal_rate * nominal_rate) * r.slope;
    }
    if (in.follows_main) {
      const auto J = std::size_t(j);
      delta -= load<T>(&main.ripple_angle[J]);
      rate -= load<T>(&main.ripple_rate[J]);
      acc -= load<T>(&main.ripple_acc[J]);
    }
    turn_by<kTiny>(cg, sg, delta);
    return joint_link<kOrder, T, T, kTiny>(coefficients, cg, sg, rate, &acc);
  }
}

template <int kOrder, bool kRipple, bool kTiny, class T>
[[gnu::always_inline]] inline void platform_loop(const PlatformInputs& in, const MainAxisNodes& main,
                                                 InstrumentInputs& out) {
  const JointCoefficients<kOrder> coefficients{in.coefficients, in.order};
  const Columns<> P(in.P);
  for (int j = 0; j < in.nodes; j += kLanes<T>) {
    const auto J = std::size_t(j);
    const T cos_gamma = load<T>(in.cos_gamma + j), sin_gamma = load<T>(in.sin_gamma + j);
    const T cos_offset = load<T>(in.cos_offset + j), sin_offset = load<T>(in.sin_offset + j);
    const T cg = cos_gamma * cos_offset - sin_gamma * sin_offset;
    const T sg = sin_gamma * cos_offset + cos_gamma * sin_offset;
    const JointLink<T> platform = platform_link<kOrder, kRipple, kTiny, T>(in, coefficients, main, j, cg, sg);
    const PointMotion<T> o5 = point_motion(platform, in.pC);
    const V3<T> W = get<T>(main.W, J);
    const V3<T> Wr = cross(W, o5.r);
    const V3<T> f = get<T>(main.F0, J) + cross(get<T>(main.dW, J), o5.r) + cross(W, Wr) +
                    2.0 * cross(W, o5.v) + o5.a + 2.0 * cross(get<T>(main.coriolis, J), Wr + o5.v);
    const V3<T> w = get<T>(main.W_total, J) + platform.w;
    const V3<T> f5 = to_local(platform, f), w5 = to_local(platform, w);
    store(&out.a_i[J], in.inverse_g * dot(f5, P.c0));
    store(&out.a_p[J], in.inverse_g * dot(f5, P.c1));
    store(&out.a_o[J], in.inverse_g * dot(f5, P.c2));
    store(&out.w_ia[J], dot(w5, P.c0));
  }
}

}  // namespace

double ripple_angle_bound(const double* coefficients, int order) {
  if (!coefficients) return 0.0;
  double bound = 0;
  for (int k = 1; k <= order; ++k)
    bound += (std::abs(coefficients[2 * k - 2]) + std::abs(coefficients[2 * k - 1])) / double(k);
  return bound;
}

double channel_bound(const double* coefficients, int order) {
  double bound = 0;
  for (int i = 0; i < 2 * order + 1; ++i) bound += std::abs(coefficients[i]);
  return bound;
}

// The loops for the harmonic order at hand, eight nodes at a time when the wobbles are small (always, for
// real centrifuges), compiled for each instruction set the machine may have (AVX-512, AVX2, baseline) and
// chosen when the library is loaded (CCAL_CLONED, core/cloned_loops.hpp).
namespace {
// The loops for a harmonic order known at compile time (0, 1, 2) or not, with or without a drive's ripple,
// eight nodes at a time or one; inlined into the entry points below.
template <bool kRipple, bool kTiny, class T>
[[gnu::always_inline]] inline void main_axis_dispatch(const MainAxisInputs& in, MainAxisNodes& out) {
  switch (in.order) {
    case 0:
      return main_axis_loop<0, kRipple, kTiny, T>(in, out);
    case 1:
      return main_axis_loop<1, kRipple, kTiny, T>(in, out);
    case 2:
      return main_axis_loop<2, kRipple, kTiny, T>(in, out);
    default:
      return main_axis_loop<kRuntimeOrder, kRipple, kTiny, T>(in, out);
  }
}
template <bool kRipple, bool kTiny, class T>
[[gnu::always_inline]] inline void platform_dispatch(const PlatformInputs& in, const MainAxisNodes& main,
                                                     InstrumentInputs& out) {
  switch (in.order) {
    case 0:
      return platform_loop<0, kRipple, kTiny, T>(in, main, out);
    case 1:
      return platform_loop<1, kRipple, kTiny, T>(in, main, out);
    case 2:
      return platform_loop<2, kRipple, kTiny, T>(in, main, out);
    default:
      return platform_loop<kRuntimeOrder, kRipple, kTiny, T>(in, main, out);
  }
}
// One node at a time (wobbles beyond the small-angle series, never a real centrifuge's), in baseline code:
// out of the clones, whose vectoriser would fuse its scalar rotations (core/cloned_loops.hpp).
[[gnu::noinline]] void main_axis_one_by_one(const MainAxisInputs& in, MainAxisNodes& out) {
  return in.ripple ? main_axis_dispatch<true, false, double>(in, out)
                   : main_axis_dispatch<false, false, double>(in, out);
}
[[gnu::noinline]] void platform_one_by_one(const PlatformInputs& in, const MainAxisNodes& main,
                                           InstrumentInputs& out) {
  return in.ripple || in.follows_main ? platform_dispatch<true, false, double>(in, main, out)
                                      : platform_dispatch<false, false, double>(in, main, out);
}
}  // namespace

CCAL_CLONED CCAL_FLATTEN void harmonic_moments_lanes(const double* half_kappa, const double* cos_half_kappa,
                                                     const double* sin_half_kappa, int count,
                                                     const Eigen::MatrixXd& a, double* nu_re, double* nu_im) {
  const int Q = int(a.rows());
  for (int i = 0; i < count; i += kPackLanes) {
    const Pack k = load<Pack>(half_kappa + i), c = load<Pack>(cos_half_kappa + i),
               s = load<Pack>(sin_half_kappa + i);
    Pack mu_re[detail::kMaxSlowNodes], mu_im[detail::kMaxSlowNodes], nu_re_q[detail::kMaxSlowNodes],
        nu_im_q[detail::kMaxSlowNodes];
    detail::oscillatory_recursion(k, c, s, Q, mu_re, mu_im);
    detail::slow_moments_of(c, s, a, mu_re, mu_im, nu_re_q, nu_im_q);
    for (int q = 0; q < Q; ++q) {
      store(nu_re + q * count + i, nu_re_q[q]);
      store(nu_im + q * count + i, nu_im_q[q]);
    }
  }
}

// One lane type for the whole packs of nodes and the scalar one for the rest: the same operations, so the
// same bits, node by node.
namespace {
template <class T>
[[gnu::always_inline]] inline void quadrature_weights_of(const double* dft_cos, const double* dft_sin, int M,
                                                         int j, double re0, const double* re,
                                                         const double* im, int Q, double* w) {
  T sum = T{} + re0;  // as the batch path (run_means_batch.cpp, batch_weights_lanes)
  for (int m = 1; m <= M / 2; ++m) {
    const auto at = std::size_t((m - 1) * M + j);
    sum = sum + (load<T>(dft_cos + at) * re[m * Q] + load<T>(dft_sin + at) * im[m * Q]);
  }
  store(w + j, sum / double(M));
}
}  // namespace

CCAL_CLONED void quadrature_weights_lanes(const double* dft_cos, const double* dft_sin, int M, int Q,
                                          const double* nu_re, const double* nu_im, double* weights,
                                          int stride) {
  for (int q = 0; q < Q; ++q) {
    double* w = weights + q * stride;
    int j = 0;
    for (; j + kPackLanes <= M; j += kPackLanes)
      quadrature_weights_of<Pack>(dft_cos, dft_sin, M, j, nu_re[q], nu_re + q, nu_im + q, Q, w);
    for (; j < M; ++j)
      quadrature_weights_of<double>(dft_cos, dft_sin, M, j, nu_re[q], nu_re + q, nu_im + q, Q, w);
  }
}

CCAL_CLONED void small_turns_lanes(const double* delta, double* c, double* s, int count) {
  for (int i = 0; i < count; i += kPackLanes) {
    Pack cd, sd;
    small_angle_cos_sin(load<Pack>(delta + i), cd, sd);
    const Pack c0 = load<Pack>(c + i), s0 = load<Pack>(s + i);
    store(c + i, c0 * cd - s0 * sd);
    store(s + i, s0 * cd + c0 * sd);
  }
}


CCAL_CLONED void weighted_outputs_lanes(const OutputPolynomial& output, const double* weights,
                                        const InstrumentInputs& in, int nodes, double* products) {
  for (int n = 0; n < nodes; n += kPackLanes)
    store(products + n, load<Pack>(weights + n) *
                            output_at(output, load<Pack>(in.a_i.data() + n), load<Pack>(in.a_p.data() + n),
                                      load<Pack>(in.a_o.data() + n), load<Pack>(in.w_ia.data() + n)));
}

CCAL_CLONED void main_axis_nodes(const MainAxisInputs& in, AngleSeries series, MainAxisNodes& out) {
  if (series == AngleSeries::library) return main_axis_one_by_one(in, out);
  if (series == AngleSeries::tiny)
    return in.ripple ? main_axis_dispatch<true, true, Pack>(in, out)
                     : main_axis_dispatch<false, true, Pack>(in, out);
  return in.ripple ? main_axis_dispatch<true, false, Pack>(in, out)
                   : main_axis_dispatch<false, false, Pack>(in, out);
}
CCAL_CLONED void platform_nodes(const PlatformInputs& in, AngleSeries series, const MainAxisNodes& main,
                                InstrumentInputs& out) {
  if (series == AngleSeries::library) return platform_one_by_one(in, main, out);
  const bool ripple = in.ripple || in.follows_main;
  if (series == AngleSeries::tiny)
    return ripple ? platform_dispatch<true, true, Pack>(in, main, out)
                  : platform_dispatch<false, true, Pack>(in, main, out);
  return ripple ? platform_dispatch<true, false, Pack>(in, main, out)
                : platform_dispatch<false, false, Pack>(in, main, out);
}

}  // namespace ccal::run_nodes
