#pragma once
// The kinematics of the run-mean kernel's node loops (run_means.hpp), written once for a lane type T: double
// (one node at a time) or Pack, eight lanes at a time in GCC's portable SIMD vectors (one AVX-512 register,
// two AVX2 ones). The lanes are eight nodes of one trial (run_means_nodes.cpp) or one node of eight trials
// (run_means_batch.cpp); the per-error data (joint coefficients, ripple, matrices) is then the same in every
// lane (C = double) or a trial's own in each (C = Pack). Each lane takes the same operations in either case,
// so a node's value has the same bits whatever its neighbours. There are no branches in the loop bodies, and
// floating-point contraction stays off, so that both lane types and every instruction set give the same bits.
// Internal to the library, included only by the kernel's sources.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "../core/cloned_loops.hpp"
#include "ccal/core/frames.hpp"
#include "run_means_nodes.hpp"

namespace ccal::run_nodes {

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

// Value i of per-error data: p[i] (C = double: the same in every lane), or lanes i·kPackLanes … of data
// stored a pack per value (C = Pack: one trial per lane, run_means_batch.cpp).
template <class C>
[[gnu::always_inline]] inline C value_at(const double* p, int i) {
  if constexpr (std::is_same_v<C, double>)
    return p[i];
  else
    return load<C>(p + std::size_t(i) * kPackLanes);
}

// The Fourier coefficients of the five channels of one joint (x, y, z runout; x, y wobble), consecutive in
// the error vector as c0, c1, s1, …, cN, sN each; the harmonic order N known at compile time or not.
template <int kOrder, class C = double>
struct JointCoefficients {
  const double* p;
  int n;
  int order() const { return kOrder == kRuntimeOrder ? n : kOrder; }
  [[gnu::always_inline]] C operator()(int channel, int i) const {
    return value_at<C>(p, channel * (2 * order() + 1) + i);
  }
};

// Value and first two derivatives with respect to q of one channel, v = c0 + Σ ck cos kq + sk sin kq.
template <class T>
struct ChannelSeries {
  T value, first, second;
};
template <int kOrder, class C, class T>
[[gnu::always_inline]] inline ChannelSeries<T> channel_series(const JointCoefficients<kOrder, C>& a,
                                                              int channel, const T& c, const T& s) {
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
template <int kOrder, class T, class C = double>
[[gnu::always_inline]] inline RippleSeries<T> ripple_series(const double* p, int n, const T& c, const T& s) {
  const int order = kOrder == kRuntimeOrder ? n : kOrder;
  RippleSeries<T> out{T{}, T{}, T{}};
  T ck = c, sk = s;
  for (int k = 1; k <= order; ++k) {
    const C a = value_at<C>(p, 2 * k - 2), b = value_at<C>(p, 2 * k - 1);
    out.angle += (a * sk - b * ck) / double(k);
    out.relative += a * ck + b * sk;
    out.slope += double(k) * (b * ck - a * sk);
    const T next_c = ck * c - sk * s;
    sk = sk * c + ck * s;
    ck = next_c;
  }
  return out;
}
// Below this bound on every wobble and ripple angle of a trial (the series' first omitted terms, q⁵/120 of
// sin q and q⁴/24 of cos q, then below 5e-18, under 0.05 ulp of either) the Pack loops take cos q ≈ 1 − q²/2
// and sin q ≈ q − q³/6 (tiny_angle_cos_sin): 4 multiplications for small_angle_cos_sin's 15, at nine angles a
// fast node of the bundled example. Its wobbles are 2e-5 rad at most, its ripple angles 2e-5.
inline constexpr double kTinyAngle = 1e-4;
template <class S>
[[gnu::always_inline]] inline void tiny_angle_cos_sin(const S& q, S& c, S& s) {
  const S q2 = q * q;
  s = q * (1.0 - q2 * (1.0 / 6.0));
  c = 1.0 - q2 * 0.5;
}
// cos and sin of a wobble or ripple angle: the library's or frames.hpp's series one node at a time (T =
// double), the series to q⁹ in Pack lanes (below kSmallAngle), or to q³ (kTiny: below kTinyAngle).
template <bool kTiny, class T>
[[gnu::always_inline]] inline void angle_cos_sin(const T& q, T& c, T& s) {
  if constexpr (!std::is_same_v<T, Pack>)
    cos_sin(q, c, s);
  else if constexpr (kTiny)
    tiny_angle_cos_sin(q, c, s);
  else
    small_angle_cos_sin(q, c, s);
}
// cos and sin of q + δ from those of q, in place.
template <bool kTiny = false, class T>
[[gnu::always_inline]] inline void turn_by(T& c, T& s, const T& delta) {
  T cd, sd;
  angle_cos_sin<kTiny>(delta, cd, sd);
  const T turned_c = c * cd - s * sd;
  s = s * cd + c * sd;
  c = turned_c;
}

// Motion of the frame after one joint of the chain (main axis or platform) relative to the frame before it:
// the joint's runout d(q), its wobbles Ry(θy(q))·Rx(θx(q)), then Rz(q), with q turning at q̇ (a constant,
// R = double, or per node with the drive's ripple, R = T, then also with the acceleration q̈; kinematics.hpp,
// exact_state). Pack lanes use the small-angle series for the wobbles, so they are only used when both
// wobble angles are known to stay below kSmallAngle (always_small), with kTiny below kTinyAngle.
template <class T>
struct JointLink {
  V3<T> e1, e2, e3;  // columns of Ry(θy)·Rx(θx)
  T c, s;            // cos q, sin q
  V3<T> d, d_rate, d_acc;
  V3<T> w, dw;  // angular velocity and acceleration of the frame after the joint
};
// What of a joint's link depends on its angle alone, not on its rate: the five channels' series, the wobbles'
// rotation [e1 e2 e3] and cos q, sin q. Runs that share their nodes' angles share it (run_means_batch.cpp).
template <class T>
struct JointShape {
  ChannelSeries<T> x, y, z, tx, ty;
  T cx, sx, cy, sy;
  V3<T> e1, e2, e3;
  T c, s;
};
template <int kOrder, class T, bool kTiny = false, class C = double>
[[gnu::always_inline]] inline JointShape<T> joint_shape(const JointCoefficients<kOrder, C>& a, const T& c,
                                                        const T& s) {
  JointShape<T> j{channel_series(a, 0, c, s), channel_series(a, 1, c, s), channel_series(a, 2, c, s),
                  channel_series(a, 3, c, s), channel_series(a, 4, c, s), T{}, T{}, T{}, T{}, {}, {}, {}, c, s};
  angle_cos_sin<kTiny>(j.tx.value, j.cx, j.sx);
  angle_cos_sin<kTiny>(j.ty.value, j.cy, j.sy);
  j.e1 = {j.cy, T{}, -j.sy};
  j.e2 = {j.sy * j.sx, j.cx, j.cy * j.sx};
  j.e3 = {j.sy * j.cx, -j.sx, j.cy * j.cx};
  return j;
}
// The link from its shape at the rate q̇ (and acceleration q̈).
template <class T, class R = double>
[[gnu::always_inline]] inline JointLink<T> joint_motion(const JointShape<T>& shape, const R& rate,
                                                        const R* acc = nullptr) {
  const ChannelSeries<T>&x = shape.x, &y = shape.y, &z = shape.z, &tx = shape.tx, &ty = shape.ty;
  const T &cy = shape.cy, &sy = shape.sy;
  JointLink<T> j;
  j.c = shape.c;
  j.s = shape.s;
  const R rate2 = rate * rate;
  j.d = {x.value, y.value, z.value};
  j.d_rate = {rate * x.first, rate * y.first, rate * z.first};
  j.d_acc = {rate2 * x.second, rate2 * y.second, rate2 * z.second};
  if (acc) j.d_acc = j.d_acc + V3<T>{*acc * x.first, *acc * y.first, *acc * z.first};
  const T wx_rate = rate * tx.first, wy_rate = rate * ty.first;
  T wx_acc = rate2 * tx.second, wy_acc = rate2 * ty.second;
  if (acc) {
    wx_acc += *acc * tx.first;
    wy_acc += *acc * ty.first;
  }
  j.e1 = shape.e1;
  j.e2 = shape.e2;
  j.e3 = shape.e3;
  // ω = θ̇y ŷ + θ̇x e1 + q̇ e3;  ω̇ = θ̈y ŷ + θ̈x e1 + θ̇y θ̇x (ŷ × e1) + (θ̇y ŷ + θ̇x e1) × q̇ e3, ŷ × e1 = (−sy, 0,
  // −cy).
  const V3<T> w_wobble{wx_rate * cy, wy_rate, -wx_rate * sy};
  const V3<T> dw_wobble{wx_acc * cy - wy_rate * wx_rate * sy, wy_acc, -wx_acc * sy - wy_rate * wx_rate * cy};
  j.dw = dw_wobble + cross(w_wobble, rate * j.e3);
  if (acc) j.dw = j.dw + *acc * j.e3;
  j.w = w_wobble + rate * j.e3;
  return j;
}
template <int kOrder, class T, class R = double, bool kTiny = false, class C = double>
[[gnu::always_inline]] inline JointLink<T> joint_link(const JointCoefficients<kOrder, C>& a, const T& c,
                                                      const T& s, const R& rate, const R* acc = nullptr) {
  return joint_motion(joint_shape<kOrder, T, kTiny>(a, c, s), rate, acc);
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
// The columns of a matrix: the same in every lane (C = double, from an Eigen matrix), or a trial's in each
// (C = Pack, from 9 packs in column-major order).
template <class C = double>
struct Columns {
  V3<C> c0, c1, c2;
  explicit Columns(const Eigen::Matrix3d& m)
      : c0{m(0, 0), m(1, 0), m(2, 0)}, c1{m(0, 1), m(1, 1), m(2, 1)}, c2{m(0, 2), m(1, 2), m(2, 2)} {}
  explicit Columns(const double* packs)
      : c0{value_at<C>(packs, 0), value_at<C>(packs, 1), value_at<C>(packs, 2)},
        c1{value_at<C>(packs, 3), value_at<C>(packs, 4), value_at<C>(packs, 5)},
        c2{value_at<C>(packs, 6), value_at<C>(packs, 7), value_at<C>(packs, 8)} {}
  template <class T>
  [[gnu::always_inline]] V3<T> transpose_times(const V3<T>& x) const {
    return {dot(x, c0), dot(x, c1), dot(x, c2)};
  }
};

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
  T out = T{} + k.power[std::size_t(k.degree)];  // (+0) + x: one broadcast (run_means_batch.cpp, splat)
  for (int n = k.degree - 1; n >= 0; --n) out = out * a_i + k.power[std::size_t(n)];
  out += k.abs_square * magnitude(a_i) * a_i + k.rate * w_ia;
  if (k.cross)
    out += k.p * a_p + k.o * a_o + k.ip * a_i * a_p + k.io * a_i * a_o + k.pp * a_p * a_p + k.oo * a_o * a_o +
           k.po * a_p * a_o;
  return out;
}

}  // namespace ccal::run_nodes
