#pragma once
// Rigid-body motion of a frame relative to the Earth-fixed frame 0, propagated link by link through
// elementary joints (a translation along the current axes, a rotation about one current axis). Templated on
// the scalar so that Eigen's AutoDiff differentiates it. Joint accelerations are zero throughout ccal
// (constant rates), but the recursion keeps them for generality.
//
// For a child frame reached from the current one by a translation d (local coordinates, with local time
// derivatives ḋ, d̈), with r = R d, the current frame having angular velocity ω and acceleration ω̇:
//     p' = p + r
//     v' = v + ω × r + R ḋ
//     a' = a + ω̇ × r + ω × (ω × r) + 2 ω × (R ḋ) + R d̈
// and for a rotation by angle q about local axis k (rates q̇, q̈), with n = R e_k:
//     R' = R Rk(q),  ω' = ω + q̇ n,  ω̇' = ω̇ + q̈ n + ω × (q̇ n).

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products
#include <cmath>

namespace ccal {

template <class S>
using Vec3 = Eigen::Matrix<S, 3, 1>;
template <class S>
using Mat3 = Eigen::Matrix<S, 3, 3>;
template <class S>
using VecX = Eigen::Matrix<S, Eigen::Dynamic, 1>;

// cos q and sin q. Error angles are tiny, and for |q| < kSmallAngle = 1e-3 their Taylor polynomials to q⁹
// (resp. q⁸) are exact in double precision (the first omitted term is below 1e-30 relative), several times
// faster than the library calls; larger angles use std::cos/std::sin.
inline constexpr double kSmallAngle = 1e-3;
// The nested form multiplies by the reciprocals 1/6, 1/20, … rather than dividing: a division costs the SIMD
// node loops of the Monte Carlo (run_means_nodes.cpp) about half their time. The rounding of 1/n (half an
// ulp) reaches s and c only through terms below 2e-7 of them, so it moves them by at most ~1e-23 relative
// before their own rounding (docs/model.md §12). Always inlined: an out-of-line copy is baseline code, which
// the node loops' AVX-512 clones would call with their vectors passed through memory.
template <class S>
[[gnu::always_inline]] inline void small_angle_cos_sin(const S& q, S& c, S& s) {
  // Written with double literals so that S may also be a SIMD vector of doubles.
  constexpr double k6 = 1.0 / 6.0, k20 = 1.0 / 20.0, k42 = 1.0 / 42.0, k72 = 1.0 / 72.0;
  constexpr double k12 = 1.0 / 12.0, k30 = 1.0 / 30.0, k56 = 1.0 / 56.0;
  const S q2 = q * q;
  s = q * (1.0 - q2 * k6 * (1.0 - q2 * k20 * (1.0 - q2 * k42 * (1.0 - q2 * k72))));
  c = 1.0 - q2 * 0.5 * (1.0 - q2 * k12 * (1.0 - q2 * k30 * (1.0 - q2 * k56)));
}
template <class S>
void cos_sin(const S& q, S& c, S& s) {
  using std::abs;
  using std::cos;
  using std::sin;
  if (abs(q) < kSmallAngle) {
    small_angle_cos_sin(q, c, s);
  } else {
    c = cos(q);
    s = sin(q);
  }
}

// R ← R · Rk(q) for k = 0, 1, 2 (x, y, z), given c = cos q, s = sin q; active right-handed rotation.
template <class S>
void post_rotate(Mat3<S>& R, int axis, const S& c, const S& s) {
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  const Vec3<S> ci = R.col(i), cj = R.col(j);
  R.col(i) = ci * c + cj * s;
  R.col(j) = cj * c - ci * s;
}

template <class S>
struct FrameMotion {
  Mat3<S> R = Mat3<S>::Identity();  // columns: the frame's axes in frame 0
  Vec3<S> p = Vec3<S>::Zero();      // origin [m]
  Vec3<S> v = Vec3<S>::Zero();      // origin velocity relative to frame 0 [m/s]
  Vec3<S> a = Vec3<S>::Zero();      // origin acceleration relative to frame 0 [m/s²]
  Vec3<S> w = Vec3<S>::Zero();      // angular velocity relative to frame 0 [rad/s]
  Vec3<S> dw = Vec3<S>::Zero();     // angular acceleration relative to frame 0 [rad/s²]

  void translate(const Vec3<S>& d) {
    const Vec3<S> r = R * d;
    const Vec3<S> wr = w.cross(r);
    a += dw.cross(r) + w.cross(wr);
    v += wr;
    p += r;
  }

  void translate(const Vec3<S>& d, const Vec3<S>& d_rate, const Vec3<S>& d_acc) {
    const Vec3<S> r = R * d, rd = R * d_rate;
    const Vec3<S> wr = w.cross(r);
    a += dw.cross(r) + w.cross(wr) + S(2) * w.cross(rd) + R * d_acc;
    v += wr + rd;
    p += r;
  }

  // A rigid, time-invariant offset of the child frame: translation ps, then rotation Rs (both local).
  void transform(const Mat3<S>& Rs, const Vec3<S>& ps) {
    translate(ps);
    R = R * Rs;
  }

  void rotate(int axis, const S& q) {
    S c, s;
    cos_sin(q, c, s);
    post_rotate<S>(R, axis, c, s);
  }

  void rotate(int axis, const S& q, const S& q_rate, const S& q_acc) {
    S c, s;
    cos_sin(q, c, s);
    rotate_cs(axis, c, s, q_rate, q_acc);
  }

  // The same with cos q and sin q already known.
  void rotate_cs(int axis, const S& c, const S& s, const S& q_rate, const S& q_acc) {
    const Vec3<S> n = R.col(axis);
    const Vec3<S> w_rel = n * q_rate;
    dw += n * q_acc + w.cross(w_rel);
    w += w_rel;
    post_rotate<S>(R, axis, c, s);
  }
};

}  // namespace ccal
