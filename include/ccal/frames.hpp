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

// R ← R · Rk(q) for k = 0, 1, 2 (x, y, z), given c = cos q, s = sin q; active right-handed rotation.
template <class S>
void post_rotate(Mat3<S>& R, int axis, const S& c, const S& s) {
  const int i = (axis + 1) % 3, j = (axis + 2) % 3;
  const Vec3<S> ci = R.col(i), cj = R.col(j);
  R.col(i) = ci * c + cj * s;
  R.col(j) = cj * c - ci * s;
}

template <class S>
Mat3<S> elementary_rotation(int axis, const S& q) {
  using std::cos;
  using std::sin;
  Mat3<S> R = Mat3<S>::Identity();
  post_rotate<S>(R, axis, cos(q), sin(q));
  return R;
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

  void rotate(int axis, const S& q) {
    using std::cos;
    using std::sin;
    post_rotate<S>(R, axis, cos(q), sin(q));
  }

  void rotate(int axis, const S& q, const S& q_rate, const S& q_acc) {
    const Vec3<S> n = R.col(axis);
    const Vec3<S> w_rel = n * q_rate;
    dw += n * q_acc + w.cross(w_rel);
    w += w_rel;
    rotate(axis, q);
  }
};

}  // namespace ccal
