#include "run_means_nodes.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include "../core/cloned_loops.hpp"
#include "ccal/core/frames.hpp"
#include "ccal/reduction/detail/spectral_weights.hpp"

namespace ccal::run_nodes {

namespace {

using Eigen::Matrix3d;

// The node loops are written once for a lane type T: double (one node at a time) or Pack, eight nodes at a
// time in GCC's portable SIMD vectors (one AVX-512 register, two AVX2 ones: with the divisions gone from the
// small-angle series, eight lanes run the bundled example's kernel 14 % faster than four). Node data is
// stored as structure of arrays padded to whole packs; there are no branches in the loop bodies, and
// floating-point contraction stays off, so that both lane types and every instruction set give the same bits.
using Pack = lanes::Doubles;
static_assert(sizeof(Pack) == kPackLanes * sizeof(double));
template <class T>
inline constexpr int kLanes = std::is_same_v<T, Pack> ? kPackLanes : 1;
using lanes::load;
using lanes::store;
template <class T>
[[gnu::always_inline]] inline V3<T> operator+(const V3<T>& a, const V3<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T, class K>
[[gnu::always_inline]] inline V3<T> operator*(const K& k, const V3<T>& a) {
  return {k * a.x, k * a.y, k * a.z};
}
template <class T>
[[gnu::always_inline]] inline V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T, class U>
[[gnu::always_inline]] inline T dot(const V3<T>& a, const V3<U>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
// A constant 3-vector in every lane.
template <class T>
[[gnu::always_inline]] inline V3<T> broadcast(const V3<double>& v) {
  return {T{} + v.x, T{} + v.y, T{} + v.z};
}

// One node's (or one pack's) 3-vector from structure-of-arrays storage, and back.
template <class T>
[[gnu::always_inline]] inline V3<T> get(const V3Array& a, std::size_t i) {
  return {load<T>(&a.x[i]), load<T>(&a.y[i]), load<T>(&a.z[i])};
}
template <class T>
[[gnu::always_inline]] inline void set(V3Array& a, std::size_t i, const V3<T>& v) {
  store(&a.x[i], v.x);
  store(&a.y[i], v.y);
  store(&a.z[i], v.z);
}

inline constexpr int kRuntimeOrder = -1;

// The Fourier coefficients of the five channels of one joint (x, y, z runout; x, y wobble), consecutive in
// the error vector as c0, c1, s1, …, cN, sN each; the harmonic order N known at compile time or not.
template <int kOrder>
struct JointCoefficients {
  const double* p;
  int n;
  int order() const { return kOrder == kRuntimeOrder ? n : kOrder; }
  double operator()(int channel, int i) const { return p[channel * (2 * order() + 1) + i]; }
};

// Value and first two derivatives with respect to q of one channel, v = c0 + Σ ck cos kq + sk sin kq.
template <class T>
struct ChannelSeries {
  T value, first, second;
};
template <int kOrder, class T>
[[gnu::always_inline]] inline ChannelSeries<T> channel_series(const JointCoefficients<kOrder>& a, int channel,
                                                              const T& c, const T& s) {
  ChannelSeries<T> out{T{} + a(channel, 0), T{}, T{}};
  if constexpr (kOrder == 1) {
    const T term = a(channel, 1) * c + a(channel, 2) * s;
    out.value += term;
    out.first = a(channel, 2) * c - a(channel, 1) * s;
    out.second = -term;
  } else if constexpr (kOrder != 0) {
    T ck = c, sk = s;  // cos kq, sin kq by the angle-addition recurrence
    for (int k = 1; k <= a.order(); ++k) {
      const T term = a(channel, 2 * k - 1) * ck + a(channel, 2 * k) * sk;
      out.value += term;
      out.first += double(k) * (a(channel, 2 * k) * ck - a(channel, 2 * k - 1) * sk);
      out.second -= double(k * k) * term;
      const T next_c = ck * c - sk * s;
      sk = sk * c + ck * s;
      ck = next_c;
    }
  }
  return out;
}

// The rate ripple of a drive at its nominal angle (cos q = c, sin q = s), from c1, s1, …, cN, sN
// (kinematics.hpp, drive_ripple): the angle error δ = Σ (ck sin kq − sk cos kq)/k, the relative rate
// r = Σ ck cos kq + sk sin kq and its slope r′ = Σ k (sk cos kq − ck sin kq).
template <class T>
struct RippleSeries {
  T angle, relative, slope;
};
template <int kOrder, class T>
[[gnu::always_inline]] inline RippleSeries<T> ripple_series(const double* p, int n, const T& c, const T& s) {
  const int order = kOrder == kRuntimeOrder ? n : kOrder;
  RippleSeries<T> out{T{}, T{}, T{}};
  T ck = c, sk = s;
  for (int k = 1; k <= order; ++k) {
    const double a = p[2 * k - 2], b = p[2 * k - 1];
    out.angle += (a * sk - b * ck) / double(k);
    out.relative += a * ck + b * sk;
    out.slope += double(k) * (b * ck - a * sk);
    const T next_c = ck * c - sk * s;
    sk = sk * c + ck * s;
    ck = next_c;
  }
  return out;
}
// cos and sin of q + δ from those of q, in place.
template <class T>
[[gnu::always_inline]] inline void turn_by(T& c, T& s, const T& delta) {
  T cd, sd;
  if constexpr (std::is_same_v<T, Pack>)
    small_angle_cos_sin(delta, cd, sd);
  else
    cos_sin(delta, cd, sd);
  const T turned_c = c * cd - s * sd;
  s = s * cd + c * sd;
  c = turned_c;
}

// Motion of the frame after one joint of the chain (main axis or platform) relative to the frame before it:
// the joint's runout d(q), its wobbles Ry(θy(q))·Rx(θx(q)), then Rz(q), with q turning at q̇ (a constant,
// R = double, or per node with the drive's ripple, R = T, then also with the acceleration q̈; kinematics.hpp,
// exact_state). Pack lanes use the small-angle series for the wobbles, so they are only used when both
// wobble angles are known to stay below kSmallAngle (always_small).
template <class T>
struct JointLink {
  V3<T> e1, e2, e3;  // columns of Ry(θy)·Rx(θx)
  T c, s;            // cos q, sin q
  V3<T> d, d_rate, d_acc;
  V3<T> w, dw;  // angular velocity and acceleration of the frame after the joint
};
template <int kOrder, class T, class R = double>
[[gnu::always_inline]] inline JointLink<T> joint_link(const JointCoefficients<kOrder>& a, const T& c,
                                                      const T& s, const R& rate, const R* acc = nullptr) {
  const ChannelSeries<T> x = channel_series(a, 0, c, s), y = channel_series(a, 1, c, s),
                         z = channel_series(a, 2, c, s), tx = channel_series(a, 3, c, s),
                         ty = channel_series(a, 4, c, s);
  JointLink<T> j;
  j.c = c;
  j.s = s;
  const R rate2 = rate * rate;
  j.d = {x.value, y.value, z.value};
  j.d_rate = {rate * x.first, rate * y.first, rate * z.first};
  j.d_acc = {rate2 * x.second, rate2 * y.second, rate2 * z.second};
  if (acc) j.d_acc = j.d_acc + V3<T>{*acc * x.first, *acc * y.first, *acc * z.first};
  T cx, sx, cy, sy;
  if constexpr (std::is_same_v<T, Pack>) {
    small_angle_cos_sin(tx.value, cx, sx);
    small_angle_cos_sin(ty.value, cy, sy);
  } else {
    cos_sin(tx.value, cx, sx);
    cos_sin(ty.value, cy, sy);
  }
  const T wx_rate = rate * tx.first, wy_rate = rate * ty.first;
  T wx_acc = rate2 * tx.second, wy_acc = rate2 * ty.second;
  if (acc) {
    wx_acc += *acc * tx.first;
    wy_acc += *acc * ty.first;
  }
  j.e1 = {cy, T{}, -sy};
  j.e2 = {sy * sx, cx, cy * sx};
  j.e3 = {sy * cx, -sx, cy * cx};
  // ω = θ̇y ŷ + θ̇x e1 + q̇ e3;  ω̇ = θ̈y ŷ + θ̈x e1 + θ̇y θ̇x (ŷ × e1) + (θ̇y ŷ + θ̇x e1) × q̇ e3, ŷ × e1 = (−sy, 0,
  // −cy).
  const V3<T> w_wobble{wx_rate * cy, wy_rate, -wx_rate * sy};
  const V3<T> dw_wobble{wx_acc * cy - wy_rate * wx_rate * sy, wy_acc, -wx_acc * sy - wy_rate * wx_rate * cy};
  j.dw = dw_wobble + cross(w_wobble, rate * j.e3);
  if (acc) j.dw = j.dw + *acc * j.e3;
  j.w = w_wobble + rate * j.e3;
  return j;
}
// R = [e1 e2 e3]·Rz(q): Rᵀx and R x.
template <class T>
[[gnu::always_inline]] inline V3<T> to_local(const JointLink<T>& j, const V3<T>& x) {
  const T x1 = dot(j.e1, x), x2 = dot(j.e2, x);
  return {j.c * x1 + j.s * x2, j.c * x2 - j.s * x1, dot(j.e3, x)};
}
template <class T, class U>
[[gnu::always_inline]] inline V3<T> from_local(const JointLink<T>& j, const V3<U>& x) {
  return (j.c * x.x - j.s * x.y) * j.e1 + (j.s * x.x + j.c * x.y) * j.e2 + x.z * j.e3;
}
// Position, velocity and acceleration of the point at `offset` (coordinates after the joint) in the joint's
// parent frame: r = d + R·offset differentiated with the link's ω, ω̇.
template <class T>
struct PointMotion {
  V3<T> r, v, a;
};
template <class T, class U>
[[gnu::always_inline]] inline PointMotion<T> point_motion(const JointLink<T>& j, const V3<U>& offset) {
  const V3<T> q = from_local(j, offset);
  const V3<T> wq = cross(j.w, q);
  return {j.d + q, j.d_rate + wq, j.d_acc + cross(j.dw, q) + cross(j.w, wq)};
}
// The columns of a matrix.
struct Columns {
  V3<double> c0, c1, c2;
  explicit Columns(const Matrix3d& m)
      : c0{m(0, 0), m(1, 0), m(2, 0)}, c1{m(0, 1), m(1, 1), m(2, 1)}, c2{m(0, 2), m(1, 2), m(2, 2)} {}
  template <class T>
  [[gnu::always_inline]] V3<T> transpose_times(const V3<T>& x) const {
    return {dot(x, c0), dot(x, c1), dot(x, c2)};
  }
};

// The main axis's link at fast node j: at the tabulated nominal angle, or with the drive's ripple
// (kinematics.hpp, RunMotion::add_ripple: θ1 = θ1ⁿ + δ1, θ̇1 = q̇ + q̇ r1, θ̈1 = q̇² r1′), whose δ1, δ̇1, δ̈1 are
// kept for a phase-locked platform.
template <int kOrder, bool kRipple, class T>
[[gnu::always_inline]] inline JointLink<T> main_link(const MainAxisInputs& in,
                                                     const JointCoefficients<kOrder>& coefficients, int j,
                                                     MainAxisNodes& out) {
  T c = load<T>(in.cos_theta + j), s = load<T>(in.sin_theta + j);
  const T nominal_rate = load<T>(in.rate + j);
  if constexpr (!kRipple) {
    return joint_link<kOrder, T, T>(coefficients, c, s, nominal_rate);
  } else {
    const RippleSeries<T> r = ripple_series<kOrder>(in.ripple, in.order, c, s);
    const T rate_ripple = nominal_rate * r.relative, acc = (nominal_rate * nominal_rate) * r.slope;
    const auto J = std::size_t(j);
    store(&out.ripple_angle[J], r.angle);
    store(&out.ripple_rate[J], rate_ripple);
    store(&out.ripple_acc[J], acc);
    turn_by(c, s, r.angle);
    const T rate = nominal_rate + rate_ripple;
    return joint_link<kOrder, T, T>(coefficients, c, s, rate, &acc);
  }
}

template <int kOrder, bool kRipple, class T>
[[gnu::always_inline]] inline void main_axis_loop(const MainAxisInputs& in, MainAxisNodes& out) {
  const JointCoefficients<kOrder> coefficients{in.coefficients, in.order};
  const Columns B(in.RB);
  const V3<T> coriolis_1t = broadcast<T>(in.coriolis_1t), gravity_1t = broadcast<T>(in.gravity_1t),
              earth_1t = broadcast<T>(in.earth_1t);
  for (int j = 0; j < in.nodes; j += kLanes<T>) {
    const JointLink<T> main = main_link<kOrder, kRipple, T>(in, coefficients, j, out);
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
template <int kOrder, bool kRipple, class T>
[[gnu::always_inline]] inline JointLink<T> platform_link(const PlatformInputs& in,
                                                         const JointCoefficients<kOrder>& coefficients,
                                                         const MainAxisNodes& main, int j,
                                                         const T& cg_nominal, const T& sg_nominal) {
  // By reference: a 64-byte vector passed by value draws GCC's ABI note in baseline code.
  T cg = cg_nominal, sg = sg_nominal;
  const T nominal_rate = load<T>(in.rate + j);
  if constexpr (!kRipple) {
    return joint_link<kOrder, T, T>(coefficients, cg, sg, nominal_rate);
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
    turn_by(cg, sg, delta);
    return joint_link<kOrder, T, T>(coefficients, cg, sg, rate, &acc);
  }
}

template <int kOrder, bool kRipple, class T>
[[gnu::always_inline]] inline void platform_loop(const PlatformInputs& in, const MainAxisNodes& main,
                                                 InstrumentInputs& out) {
  const JointCoefficients<kOrder> coefficients{in.coefficients, in.order};
  const Columns P(in.P);
  for (int j = 0; j < in.nodes; j += kLanes<T>) {
    const auto J = std::size_t(j);
    const T cos_gamma = load<T>(in.cos_gamma + j), sin_gamma = load<T>(in.sin_gamma + j);
    const T cos_offset = load<T>(in.cos_offset + j), sin_offset = load<T>(in.sin_offset + j);
    const T cg = cos_gamma * cos_offset - sin_gamma * sin_offset;
    const T sg = sin_gamma * cos_offset + cos_gamma * sin_offset;
    const JointLink<T> platform = platform_link<kOrder, kRipple, T>(in, coefficients, main, j, cg, sg);
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

bool always_small(const double* coefficients, int order) {
  double bound = 0;
  for (int i = 0; i < 2 * order + 1; ++i) bound += std::abs(coefficients[i]);
  return bound < kSmallAngle;
}

// The loops for the harmonic order at hand, eight nodes at a time when the wobbles are small (always, for
// real centrifuges), compiled for each instruction set the machine may have (AVX-512, AVX2, baseline) and
// chosen when the library is loaded (CCAL_CLONED, core/cloned_loops.hpp).
namespace {
// The loops for a harmonic order known at compile time (0, 1, 2) or not, with or without a drive's ripple,
// eight nodes at a time or one; inlined into the entry points below.
template <bool kRipple, class T>
[[gnu::always_inline]] inline void main_axis_dispatch(const MainAxisInputs& in, MainAxisNodes& out) {
  switch (in.order) {
    case 0:
      return main_axis_loop<0, kRipple, T>(in, out);
    case 1:
      return main_axis_loop<1, kRipple, T>(in, out);
    case 2:
      return main_axis_loop<2, kRipple, T>(in, out);
    default:
      return main_axis_loop<kRuntimeOrder, kRipple, T>(in, out);
  }
}
template <bool kRipple, class T>
[[gnu::always_inline]] inline void platform_dispatch(const PlatformInputs& in, const MainAxisNodes& main,
                                                     InstrumentInputs& out) {
  switch (in.order) {
    case 0:
      return platform_loop<0, kRipple, T>(in, main, out);
    case 1:
      return platform_loop<1, kRipple, T>(in, main, out);
    case 2:
      return platform_loop<2, kRipple, T>(in, main, out);
    default:
      return platform_loop<kRuntimeOrder, kRipple, T>(in, main, out);
  }
}
// One node at a time (wobbles beyond the small-angle series, never a real centrifuge's), in baseline code:
// out of the clones, whose vectoriser would fuse its scalar rotations (core/cloned_loops.hpp).
[[gnu::noinline]] void main_axis_one_by_one(const MainAxisInputs& in, MainAxisNodes& out) {
  return in.ripple ? main_axis_dispatch<true, double>(in, out) : main_axis_dispatch<false, double>(in, out);
}
[[gnu::noinline]] void platform_one_by_one(const PlatformInputs& in, const MainAxisNodes& main,
                                           InstrumentInputs& out) {
  return in.ripple || in.follows_main ? platform_dispatch<true, double>(in, main, out)
                                      : platform_dispatch<false, double>(in, main, out);
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
  T sum = re0 - T{};  // x − (+0) is x, −0 included
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

namespace {
// |x| lane by lane: the sign bit cleared, as std::abs does it.
[[gnu::always_inline]] inline double magnitude(double x) { return std::abs(x); }
[[gnu::always_inline]] inline Pack magnitude(const Pack& x) {
  using Bits = std::int64_t __attribute__((vector_size(sizeof(Pack))));
  return Pack(Bits(x) & std::numeric_limits<std::int64_t>::max());
}
// y(a_i, a_p, a_o, ω_IA): Σ K_n a_iⁿ by Horner, then the |a_i|a_i and rate terms, then the cross terms.
template <class T>
[[gnu::always_inline]] inline T output_at(const OutputPolynomial& k, const T& a_i, const T& a_p, const T& a_o,
                                          const T& w_ia) {
  T out = k.power[std::size_t(k.degree)] - T{};  // x − (+0) is x, −0 included
  for (int n = k.degree - 1; n >= 0; --n) out = out * a_i + k.power[std::size_t(n)];
  out += k.abs_square * magnitude(a_i) * a_i + k.rate * w_ia;
  if (k.cross)
    out += k.p * a_p + k.o * a_o + k.ip * a_i * a_p + k.io * a_i * a_o + k.pp * a_p * a_p + k.oo * a_o * a_o +
           k.po * a_p * a_o;
  return out;
}
}  // namespace

CCAL_CLONED void weighted_outputs_lanes(const OutputPolynomial& output, const double* weights,
                                        const InstrumentInputs& in, int nodes, double* products) {
  for (int n = 0; n < nodes; n += kPackLanes)
    store(products + n, load<Pack>(weights + n) *
                            output_at(output, load<Pack>(in.a_i.data() + n), load<Pack>(in.a_p.data() + n),
                                      load<Pack>(in.a_o.data() + n), load<Pack>(in.w_ia.data() + n)));
}

CCAL_CLONED void main_axis_nodes(const MainAxisInputs& in, bool small, MainAxisNodes& out) {
  if (!small) return main_axis_one_by_one(in, out);
  return in.ripple ? main_axis_dispatch<true, Pack>(in, out) : main_axis_dispatch<false, Pack>(in, out);
}
CCAL_CLONED void platform_nodes(const PlatformInputs& in, bool small, const MainAxisNodes& main,
                                InstrumentInputs& out) {
  if (!small) return platform_one_by_one(in, main, out);
  return in.ripple || in.follows_main ? platform_dispatch<true, Pack>(in, main, out)
                                      : platform_dispatch<false, Pack>(in, main, out);
}

}  // namespace ccal::run_nodes
