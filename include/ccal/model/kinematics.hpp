#pragma once
// Exact kinematics of the instrument on the centrifuge (docs/model.md §4): the full chain
//   0 →(levelling) 1t →(runout, wobble, Rz θ1) 1 →(R0+ΔR, Δy2t, Δθy2t) 2t →(Rx β) 2 →(Δy3t, Δθx3t, Δθy3t) 3t
//     →(runout, wobble, Rz γ) 3 →(L, Δθx4, Δθy4) 4 →(l, Δx5, Δy5, Δθx5, Δθy5, Δθz5) 5
// composed with exact rotations (an error triple is Rz(θz)·Ry(θy)·Rx(θx)), every dynamic error differentiated
// analytically through its joint angle, and
//   specific force  f = a + 2 ω_ie × v + g z0          (a, v relative to the Earth-fixed frame 0)
//   angular rate    ω = ω_ie + ω_05                     (inertial)
// both resolved on IA = x5, PA = y5, OA = z5. Everything is templated on the scalar type, so
// Eigen::AutoDiffScalar gives exact derivatives with respect to any error parameter or joint variable.

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "ccal/core/frames.hpp"
#include "ccal/core/scalar.hpp"
#include "ccal/model/centrifuge.hpp"
#include "ccal/model/error_sources.hpp"
#include "ccal/model/site.hpp"

namespace ccal {

// Joint angles, rates and accelerations at one instant. The accelerations are those of the drives' rate
// ripple (docs/model.md §3.1); β does not move during a run.
template <class S>
struct JointState {
  S theta1{0};       // main-axis angle from x0 (East) [rad]
  S theta1_rate{0};  // θ̇1 = (Ω + Δω)(1 + r1) [rad/s]
  S beta{0};         // horizontal-axis angle [rad]
  S beta_rate{0};
  S gamma{0};       // platform angle: IA from the outward radial x1, about z3 [rad]
  S gamma_rate{0};  // γ̇ [rad/s]
  S theta1_acc{0};  // θ̈1 [rad/s²]
  S gamma_acc{0};   // γ̈ [rad/s²]
  // The ripple's part of θ̇1: the arm stretch follows the mean rate θ̇1 − this (model.md §3.1).
  S theta1_ripple_rate{0};
};

template <class S>
struct InstrumentState {
  Vec3<S> position;        // o5 in frame 0 [m]
  Vec3<S> velocity;        // relative to frame 0 [m/s]
  Vec3<S> acceleration;    // relative to frame 0 [m/s²]
  Mat3<S> orientation;     // columns IA, PA, OA resolved in frame 0
  Vec3<S> specific_force;  // along IA, PA, OA [g] (divided by the site's g)
  Vec3<S> angular_rate;    // inertial, about IA, PA, OA [rad/s]
};

struct ChainOptions {
  // The paper's "frozen-γ" differentiation (model.md §2.1): the platform rate is left out of the position
  // derivatives (as if the platform were fixed at the current γ); it still enters the angular rate.
  bool frozen_platform = false;
};

// Value of a dynamic channel and its first two time derivatives at joint angle q turning at q̇ with q̈:
//   v = Σ ck cos kq + sk sin kq,  v̇ = q̇ dv/dq,  v̈ = q̇² d²v/dq² + q̈ dv/dq.
template <class S>
struct ChannelValue {
  S value{0}, rate{0}, acc{0};
};

template <class S, class Errors>
ChannelValue<S> dynamic_channel(const ErrorLayout& layout, const Errors& e, int channel, const S& q,
                                const S& q_rate, const S& q_acc = S(0)) {
  using std::cos;
  using std::sin;
  ChannelValue<S> out;
  out.value = S(e[layout.harmonic_index(channel, 0, false)]);
  const int order = layout.harmonic_order();
  if (order == 0) return out;
  const S c1 = cos(q), s1 = sin(q);
  S ck = c1, sk = s1, d1{0}, d2{0};
  for (int k = 1; k <= order; ++k) {
    const S a = S(e[layout.harmonic_index(channel, k, false)]);
    const S b = S(e[layout.harmonic_index(channel, k, true)]);
    const S term = a * ck + b * sk;
    out.value += term;
    d1 += double(k) * (b * ck - a * sk);
    d2 -= double(k * k) * term;
    const S next_c = ck * c1 - sk * s1;  // cos (k+1)q, sin (k+1)q by the angle-addition recurrence
    sk = sk * c1 + ck * s1;
    ck = next_c;
  }
  out.rate = q_rate * d1;
  out.acc = q_rate * q_rate * d2 + q_acc * d1;
  return out;
}

// A dynamic error (model.md §3) of three channels from first_channel (x, y, z): its harmonic series in the
// joint's angle q, with its rates, moves the frame.
template <class S, class Errors>
void translate_by_dynamic_error(FrameMotion<S>& m, const ErrorLayout& layout, const Errors& e,
                                int first_channel, const S& q, const S& q_rate, const S& q_acc) {
  Vec3<S> d, dd, ddd;
  for (int i = 0; i < 3; ++i) {
    const auto c = dynamic_channel<S>(layout, e, first_channel + i, q, q_rate, q_acc);
    d[i] = c.value;
    dd[i] = c.rate;
    ddd[i] = c.acc;
  }
  m.translate(d, dd, ddd);
}

// The instrument's state at the end of the chain: its motion, and what it senses, the specific force
// (f = a + 2 Ω_E × v + g, in the g of the g-levels) and the inertial rate (the frame's and the Earth's), on
// its axes.
template <class S>
InstrumentState<S> sensed_state(const FrameMotion<S>& m, const Site& site) {
  const Vec3<S> earth = site.sensed_rate_enu().template cast<S>();
  Vec3<S> f = m.a + S(2) * Vec3<S>(site.coriolis_rate_enu().template cast<S>()).cross(m.v);
  f[2] += S(site.g);
  InstrumentState<S> out;
  out.position = m.p;
  out.velocity = m.v;
  out.acceleration = m.a;
  out.orientation = m.R;
  out.specific_force = m.R.transpose() * f / S(site.g_unit());
  out.angular_rate = m.R.transpose() * (m.w + earth);
  return out;
}

// Exact state of the instrument for error vector `e` (indexed by `layout`, SI values).
template <class S, class Errors>
InstrumentState<S> exact_state(const Geometry& geo, const ErrorLayout& layout, const Errors& e,
                               const Site& site, const JointState<S>& j, const ChainOptions& options = {}) {
  constexpr int X = 0, Y = 1, Z = 2;
  auto E = [&](int i) { return S(e[i]); };
  FrameMotion<S> m;
  // A dynamic error (model.md §3): its harmonic series in the joint's angle q, with its rates, moves the frame.
  auto translate_dynamic = [&](int first_channel, const S& q, const S& q_rate, const S& q_acc) {
    translate_by_dynamic_error(m, layout, e, first_channel, q, q_rate, q_acc);
  };
  auto rotate_dynamic = [&](int channel, int axis, const S& q, const S& q_rate, const S& q_acc) {
    const auto c = dynamic_channel<S>(layout, e, channel, q, q_rate, q_acc);
    m.rotate(axis, c.value, c.rate, c.acc);
  };
  // 0 → 1t: levelling of the main-axis sleeve.
  m.rotate(Y, E(ch::dthy1t));
  m.rotate(X, E(ch::dthx1t));
  // 1t → 1: runouts, wobbles, then the main axis itself.
  translate_dynamic(ch::dx1, j.theta1, j.theta1_rate, j.theta1_acc);
  rotate_dynamic(ch::dthy1, Y, j.theta1, j.theta1_rate, j.theta1_acc);
  rotate_dynamic(ch::dthx1, X, j.theta1, j.theta1_rate, j.theta1_acc);
  m.rotate(Z, j.theta1, j.theta1_rate, j.theta1_acc);
  // 1 → 2t: arm of radius R0 + ΔR_s + c·θ̇1² (at the mean rate), intersection, perpendicularity.
  const S mean_rate = j.theta1_rate - j.theta1_ripple_rate;
  m.translate(Vec3<S>(S(geo.R0) + E(ch::dR_s) + E(ch::arm_stretch) * mean_rate * mean_rate, E(ch::dy2t), S(0)));
  m.rotate(Y, E(ch::dthy2t));
  // 2t → 2: horizontal-axis float, runouts, wobbles, then Rx(β).
  translate_dynamic(ch::dx2, j.beta, j.beta_rate, S(0));
  rotate_dynamic(ch::dthz2, Z, j.beta, j.beta_rate, S(0));
  rotate_dynamic(ch::dthy2, Y, j.beta, j.beta_rate, S(0));
  m.rotate(X, j.beta, j.beta_rate, S(0));
  // 2 → 3t: azimuth sleeve.
  m.translate(Vec3<S>(S(0), E(ch::dy3t), S(0)));
  m.rotate(Y, E(ch::dthy3t));
  m.rotate(X, E(ch::dthx3t));
  // 3t → 3: platform runouts, float, wobbles, then Rz(γ). Frozen-γ drops γ̇ from the position derivatives.
  const S gamma_rate_in_position = options.frozen_platform ? S(0) : j.gamma_rate;
  const S gamma_acc_in_position = options.frozen_platform ? S(0) : j.gamma_acc;
  translate_dynamic(ch::dx3, j.gamma, gamma_rate_in_position, gamma_acc_in_position);
  rotate_dynamic(ch::dthy3, Y, j.gamma, gamma_rate_in_position, gamma_acc_in_position);
  rotate_dynamic(ch::dthx3, X, j.gamma, gamma_rate_in_position, gamma_acc_in_position);
  const Vec3<S> azimuth_axis = m.R.col(Z);
  m.rotate(Z, j.gamma, gamma_rate_in_position, gamma_acc_in_position);
  // 3 → 4: working base plane.
  m.translate(Vec3<S>(S(0), S(0), S(geo.L)));
  m.rotate(Y, E(ch::dthy4));
  m.rotate(X, E(ch::dthx4));
  // 4 → 5: the instrument at its place on the base plane (x5, y5, l), turned by its azimuth (model.md §4.2).
  m.translate(Vec3<S>(S(geo.x5) + E(ch::dx5), S(geo.y5) + E(ch::dy5), S(geo.l)));
  m.rotate(Z, S(geo.azimuth5) + E(ch::dthz5));
  m.rotate(Y, E(ch::dthy5));
  m.rotate(X, E(ch::dthx5));

  if (options.frozen_platform) m.w += azimuth_axis * j.gamma_rate;

  return sensed_state(m, site);
}

// Specific force [g] and inertial angular rate [rad/s] on IA, PA, OA: the two quantities an instrument
// senses.
template <class S>
struct SensedInput {
  Vec3<S> specific_force;
  Vec3<S> angular_rate;
};

// The time-invariant blocks of the chain (docs/model.md §4.1): A, the levelling (only gravity and Earth rate
// in its frame-1t coordinates are needed), B = frame 1 → 3t (arm, horizontal axis at fixed β, azimuth sleeve)
// and C = frame 3 → 5 (base plane, instrument).
template <class S>
struct ChainBlocks {
  Vec3<S> gravity_1t, coriolis_1t, earth_1t;  // z0, Coriolis ω_ie and sensed ω_ie in frame-1t coordinates
  Mat3<S> RB, RC;
  Vec3<S> pB, pC;
};

template <class S, class Errors>
ChainBlocks<S> chain_blocks(const Geometry& geo, const ErrorLayout& layout, const Errors& e, const Site& site,
                            const S& theta1_rate, const S& beta) {
  constexpr int X = 0, Y = 1, Z = 2;
  auto E = [&](int i) { return S(e[i]); };
  ChainBlocks<S> out;
  FrameMotion<S> a;
  a.rotate(Y, E(ch::dthy1t));
  a.rotate(X, E(ch::dthx1t));
  out.gravity_1t = a.R.transpose().col(Z);
  out.coriolis_1t = a.R.transpose() * site.coriolis_rate_enu().template cast<S>();
  out.earth_1t = a.R.transpose() * site.sensed_rate_enu().template cast<S>();

  const S zero{0};
  FrameMotion<S> b;
  b.translate(Vec3<S>(S(geo.R0) + E(ch::dR_s) + E(ch::arm_stretch) * theta1_rate * theta1_rate, E(ch::dy2t), zero));
  b.rotate(Y, E(ch::dthy2t));
  b.translate(Vec3<S>(dynamic_channel<S>(layout, e, ch::dx2, beta, zero).value,
                      dynamic_channel<S>(layout, e, ch::dy2, beta, zero).value,
                      dynamic_channel<S>(layout, e, ch::dz2, beta, zero).value));
  b.rotate(Z, dynamic_channel<S>(layout, e, ch::dthz2, beta, zero).value);
  b.rotate(Y, dynamic_channel<S>(layout, e, ch::dthy2, beta, zero).value);
  b.rotate(X, beta);
  b.translate(Vec3<S>(zero, E(ch::dy3t), zero));
  b.rotate(Y, E(ch::dthy3t));
  b.rotate(X, E(ch::dthx3t));
  out.RB = b.R;
  out.pB = b.p;

  FrameMotion<S> c;
  c.translate(Vec3<S>(zero, zero, S(geo.L)));
  c.rotate(Y, E(ch::dthy4));
  c.rotate(X, E(ch::dthx4));
  c.translate(Vec3<S>(S(geo.x5) + E(ch::dx5), S(geo.y5) + E(ch::dy5), S(geo.l)));
  c.rotate(Z, S(geo.azimuth5) + E(ch::dthz5));
  c.rotate(Y, E(ch::dthy5));
  c.rotate(X, E(ch::dthx5));
  out.RC = c.R;
  out.pC = c.p;
  return out;
}

// The chain with only static errors (and a fixed horizontal axis), factored as in model.md §4.1:
//   p = A · Rz(θ1) · (B_R · Rz(γ) · c + B_p),  frame 5 = A · Rz(θ1) · B_R · Rz(γ) · C_R,
// so that one evaluation costs two sine/cosine pairs and a few 3×3 products. Everything that does not change
// in time is precomputed. In frame-1 coordinates, with K = [z×] (so Rz(−θ)Rz′(θ) = K, Rz(−θ)Rz″(θ) = K²),
//   u = B_R Rz(γ) c + B_p,  u′ = B_R Rz′(γ) c,  u″ = B_R Rz″(γ) c
//   a₁ = θ̇1² K² u + θ̈1 K u + 2 θ̇1 γ̇ K u′ + γ̇² u″ + γ̈ u′,   v₁ = θ̇1 K u + γ̇ u′
// (θ̈1, γ̈: the drives' rate ripple). Dynamic errors of the main and azimuth axes are ignored here: use
// exact_state for them.
template <class S>
class StaticChain {
 public:
  template <class Errors>
  StaticChain(const Geometry& geo, const ErrorLayout& layout, const Errors& e, const Site& site,
              const S& theta1_rate, const S& beta, const ChainOptions& options = {})
      : g_(site.g),
        unit_(site.g_unit()),
        frozen_(options.frozen_platform),
        b_(chain_blocks<S>(geo, layout, e, site, theta1_rate, beta)) {}

  SensedInput<S> operator()(const S& theta1, const S& gamma, const S& theta1_rate, const S& gamma_rate,
                            const S& theta1_acc = S(0), const S& gamma_acc = S(0)) const {
    using std::cos;
    using std::sin;
    const S ct = cos(theta1), st = sin(theta1), cg = cos(gamma), sg = sin(gamma);
    const Vec3<S> rz_c(cg * b_.pC[0] - sg * b_.pC[1], sg * b_.pC[0] + cg * b_.pC[1], b_.pC[2]);
    const Vec3<S> rz1_c(-rz_c[1], rz_c[0], S(0));  // Rz′(γ) c = K Rz(γ) c
    const Vec3<S> u = b_.RB * rz_c + b_.pB;
    const Vec3<S> u1 = b_.RB * rz1_c;
    const Vec3<S> u2 = -(b_.RB.template leftCols<2>() * rz_c.template head<2>());  // Rz″(γ)c = −(x, y, 0)
    const S gr = frozen_ ? S(0) : gamma_rate;
    const S ga = frozen_ ? S(0) : gamma_acc;
    const S w2 = theta1_rate * theta1_rate;
    const Vec3<S> acc(
        -w2 * u[0] - theta1_acc * u[1] - S(2) * theta1_rate * gr * u1[1] + gr * gr * u2[0] + ga * u1[0],
        -w2 * u[1] + theta1_acc * u[0] + S(2) * theta1_rate * gr * u1[0] + gr * gr * u2[1] + ga * u1[1],
        gr * gr * u2[2] + ga * u1[2]);
    const Vec3<S> vel(-theta1_rate * u[1] + gr * u1[0], theta1_rate * u[0] + gr * u1[1], gr * u1[2]);
    // Gravity direction and Earth rate in frame-1 coordinates: Rz(−θ1) applied to their 1t coordinates.
    const Vec3<S> up(ct * b_.gravity_1t[0] + st * b_.gravity_1t[1],
                     ct * b_.gravity_1t[1] - st * b_.gravity_1t[0], b_.gravity_1t[2]);
    const Vec3<S> earth(ct * b_.earth_1t[0] + st * b_.earth_1t[1], ct * b_.earth_1t[1] - st * b_.earth_1t[0],
                        b_.earth_1t[2]);
    const Vec3<S> coriolis(ct * b_.coriolis_1t[0] + st * b_.coriolis_1t[1],
                           ct * b_.coriolis_1t[1] - st * b_.coriolis_1t[0], b_.coriolis_1t[2]);
    const Vec3<S> f1 = acc + S(2) * coriolis.cross(vel) + S(g_) * up;
    const Vec3<S> w1 = Vec3<S>(S(0), S(0), theta1_rate) + gamma_rate * b_.RB.col(2) + earth;
    // Frame 5 in frame 1 is M = R_B Rz(γ) R_C, so x₅ = M^T x₁ = R_C^T Rz(−γ) R_B^T x₁.
    auto to_frame5 = [&](const Vec3<S>& x1) {
      const Vec3<S> x3t = b_.RB.transpose() * x1;
      const Vec3<S> x3(cg * x3t[0] + sg * x3t[1], cg * x3t[1] - sg * x3t[0], x3t[2]);
      return Vec3<S>(b_.RC.transpose() * x3);
    };
    return {to_frame5(f1) / S(unit_), to_frame5(w1)};
  }

 private:
  double g_;     // gravity [m/s²]
  double unit_;  // the g of the g-levels [m/s²]
  bool frozen_;
  ChainBlocks<S> b_;
};

// The chain with every error, for repeated evaluation (run means, Monte Carlo): the time-invariant blocks
// A (levelling), B (arm, horizontal axis at fixed β, azimuth sleeve) and C (base plane, instrument) are
// composed once, so that an evaluation propagates the motion through ten elementary joints (the dynamic
// errors of the main and azimuth axes and the two joint rotations) instead of thirty, and evaluates the
// Fourier series of each joint once; a channel with no error at all costs nothing. Same result as exact_state
// to round-off (tests/model/kinematics_test.cpp).
template <class S>
class DynamicChain {
 public:
  template <class Errors>
  DynamicChain(const Geometry& geo, const ErrorLayout& layout, const Errors& e, const Site& site,
               const S& theta1_rate, const S& beta, const ChainOptions& options = {})
      : layout_(layout),
        g_(site.g),
        unit_(site.g_unit()),
        frozen_(options.frozen_platform),
        b_(chain_blocks<S>(geo, layout, e, site, theta1_rate, beta)) {
    // Fourier coefficients of the ten dynamic channels, [channel][c0, c1, s1, …].
    const int order = layout.harmonic_order();
    for (int k = 0; k < 10; ++k) {
      const int ch = kChannelsOrder[k];
      coefficients_[k].resize(2 * order + 1);
      zero_[k] = true;
      for (int i = 0; i < 2 * order + 1; ++i) {
        coefficients_[k][i] = S(e[layout.harmonic_index(ch, 0, false) + i]);
        zero_[k] = zero_[k] && is_exactly_zero(coefficients_[k][i]);
      }
    }
  }

  SensedInput<S> operator()(const JointState<S>& j) const { return platform(main_axis(j), j); }

  // The two halves of an evaluation: the motion of frame 3t (everything up to the azimuth joint, a function
  // of θ1 alone), then the rest for a platform state. Run means reuse one main-axis half for all the
  // slow-time nodes that share a fast phase.
  FrameMotion<S> main_axis(const JointState<S>& j) const {
    constexpr int X = 0, Y = 1, Z = 2;
    ChannelValue<S> main[5];
    S c1, s1;
    cos_sin(j.theta1, c1, s1);
    series(c1, s1, j.theta1_rate, j.theta1_acc, 0, main);
    FrameMotion<S> m;  // in frame-1t coordinates, which do not move: the main-axis runout is the motion
    m.p = Vec3<S>(main[0].value, main[1].value, main[2].value);
    m.v = Vec3<S>(main[0].rate, main[1].rate, main[2].rate);
    m.a = Vec3<S>(main[0].acc, main[1].acc, main[2].acc);
    if (!zero_[4]) m.rotate(Y, main[4].value, main[4].rate, main[4].acc);
    if (!zero_[3]) m.rotate(X, main[3].value, main[3].rate, main[3].acc);
    m.rotate_cs(Z, c1, s1, j.theta1_rate, j.theta1_acc);
    m.transform(b_.RB, b_.pB);
    return m;
  }

  SensedInput<S> platform(FrameMotion<S> m, const JointState<S>& j) const {
    constexpr int X = 0, Y = 1, Z = 2;
    const S gamma_rate = frozen_ ? S(0) : j.gamma_rate;
    const S gamma_acc = frozen_ ? S(0) : j.gamma_acc;
    ChannelValue<S> platform[5];
    S cg, sg;
    cos_sin(j.gamma, cg, sg);
    series(cg, sg, gamma_rate, gamma_acc, 5, platform);
    if (!(zero_[5] && zero_[6] && zero_[7]))
      m.translate(Vec3<S>(platform[0].value, platform[1].value, platform[2].value),
                  Vec3<S>(platform[0].rate, platform[1].rate, platform[2].rate),
                  Vec3<S>(platform[0].acc, platform[1].acc, platform[2].acc));
    if (!zero_[9]) m.rotate(Y, platform[4].value, platform[4].rate, platform[4].acc);
    if (!zero_[8]) m.rotate(X, platform[3].value, platform[3].rate, platform[3].acc);
    const Vec3<S> azimuth_axis = m.R.col(Z);
    m.rotate_cs(Z, cg, sg, gamma_rate, gamma_acc);
    m.transform(b_.RC, b_.pC);
    if (frozen_) m.w += azimuth_axis * j.gamma_rate;
    const Vec3<S> f = m.a + S(2) * b_.coriolis_1t.cross(m.v) + S(g_) * b_.gravity_1t;
    return {m.R.transpose() * f / S(unit_), m.R.transpose() * (m.w + b_.earth_1t)};
  }

 private:
  // Main-axis channels dx1, dy1, dz1, dthx1, dthy1, then the azimuth-axis ones.
  static constexpr int kChannelsOrder[10] = {ccal::ch::dx1, ccal::ch::dy1, ccal::ch::dz1, ccal::ch::dthx1, ccal::ch::dthy1,
                                             ccal::ch::dx3, ccal::ch::dy3, ccal::ch::dz3, ccal::ch::dthx3, ccal::ch::dthy3};

  // Values and time derivatives of five channels of one joint (cos q = c, sin q = s, turning at q̇ with q̈)
  // from one evaluation of its harmonics.
  void series(const S& c, const S& s, const S& q_rate, const S& q_acc, int first,
              ChannelValue<S>* out) const {
    const int order = layout_.harmonic_order();
    S ck[65], sk[65];
    ck[0] = S(1);
    sk[0] = S(0);
    if (order > 0) {
      ck[1] = c;
      sk[1] = s;
      for (int k = 2; k <= order; ++k) {
        ck[k] = ck[k - 1] * ck[1] - sk[k - 1] * sk[1];
        sk[k] = sk[k - 1] * ck[1] + ck[k - 1] * sk[1];
      }
    }
    for (int c = 0; c < 5; ++c) {
      if (zero_[first + c]) {
        out[c] = {S(0), S(0), S(0)};
        continue;
      }
      const std::vector<S>& a = coefficients_[first + c];
      S v = a[0], d1{0}, d2{0};
      for (int k = 1; k <= order; ++k) {
        const S term = a[2 * k - 1] * ck[k] + a[2 * k] * sk[k];
        v += term;
        d1 += double(k) * (a[2 * k] * ck[k] - a[2 * k - 1] * sk[k]);
        d2 -= double(k * k) * term;
      }
      out[c] = {v, q_rate * d1, q_rate * q_rate * d2 + q_acc * d1};
    }
  }

  ErrorLayout layout_;
  double g_;     // gravity [m/s²]
  double unit_;  // the g of the g-levels [m/s²]
  bool frozen_;
  ChainBlocks<S> b_;
  std::vector<S> coefficients_[10];
  // A channel whose coefficients are all exactly zero (with no derivative): its values are zero, and its
  // rotation or translation, the identity, is skipped (the same values: R·1 + 0, p + 0).
  bool zero_[10] = {};
};

// A drive's rate ripple at its nominal angle q turning at the nominal rate q̇ (docs/model.md §3.1): the
// relative rate r(q) = Σ_{k=1..N} (ck cos kq + sk sin kq) integrates to the angle error
// δ(q) = Σ (ck sin kq − sk cos kq)/k (zero mean over a revolution), so that δ̇ = q̇ r and δ̈ = q̇² r′.
// `coefficients` holds c1, s1, …, cN, sN.
template <class S>
struct RippleValue {
  S angle{0}, rate{0}, acc{0};  // δ, δ̇, δ̈
};

template <class S>
RippleValue<S> drive_ripple(const std::vector<S>& coefficients, const S& q, const S& q_rate) {
  using std::cos;
  using std::sin;
  RippleValue<S> out;
  const int order = int(coefficients.size() / 2);
  if (order == 0) return out;
  const S c1 = cos(q), s1 = sin(q);
  S ck = c1, sk = s1, relative{0}, slope{0};
  for (int k = 1; k <= order; ++k) {
    const S& a = coefficients[std::size_t(2 * k - 2)];
    const S& b = coefficients[std::size_t(2 * k - 1)];
    out.angle += (a * sk - b * ck) / double(k);
    relative += a * ck + b * sk;
    slope += double(k) * (b * ck - a * sk);
    const S next_c = ck * c1 - sk * s1;
    sk = sk * c1 + ck * s1;
    ck = next_c;
  }
  out.rate = q_rate * relative;
  out.acc = q_rate * q_rate * slope;
  return out;
}

// Joint motion of one run. Nominally θ1(t) = θ1(0) + (Ω + Δω) t, γ(t) = φ0 + γ̇ t with γ̇ = −(Ω + Δω + ΔΩ)
// on a counter-rotating platform and 0 on a fixed one, β constant. The drives' rate ripple (if any) is added
// at the nominal angles (add_ripple): the main axis turns by δ1(θ1ⁿ); a turning platform by δ3(γⁿ), and when
// phase-locked it follows the main axis's angle error too, γ = γⁿ − δ1(θ1ⁿ) + δ3(γⁿ) (model.md §2.3).
template <class S>
struct RunMotion {
  S theta1_0{0};
  S theta1_rate{0};
  S beta{0};
  S gamma_0{0};
  S gamma_rate{0};
  std::vector<S> main_ripple, platform_ripple;  // c1, s1, …, cN, sN of each drive (empty: none)
  bool platform_follows_main = false;           // phase-locked counter-rotating platform

  bool has_ripple() const { return !main_ripple.empty() || !platform_ripple.empty(); }

  // A state on the nominal motion, moved by the ripple.
  void add_ripple(JointState<S>& j) const {
    if (!has_ripple()) return;
    const RippleValue<S> main = drive_ripple(main_ripple, j.theta1, theta1_rate);
    const RippleValue<S> platform = drive_ripple(platform_ripple, j.gamma, gamma_rate);
    j.theta1 += main.angle;
    j.theta1_rate += main.rate;
    j.theta1_acc += main.acc;
    j.theta1_ripple_rate += main.rate;
    j.gamma += platform.angle;
    j.gamma_rate += platform.rate;
    j.gamma_acc += platform.acc;
    if (platform_follows_main) {
      j.gamma -= main.angle;
      j.gamma_rate -= main.rate;
      j.gamma_acc -= main.acc;
    }
  }

  JointState<S> at(const S& t) const {
    JointState<S> j{theta1_0 + theta1_rate * t, theta1_rate, beta, S(0),
                    gamma_0 + gamma_rate * t,   gamma_rate};
    add_ripple(j);
    return j;
  }
};

// The run's motion with the drive rate errors Δω, ΔΩ of `e` (no ripple).
template <class S, class Errors>
RunMotion<S> run_motion(double nominal_rate, double theta1_0, double phi0, PlatformMode mode, double beta,
                        const Errors& e) {
  RunMotion<S> r;
  r.theta1_0 = S(theta1_0);
  r.theta1_rate = S(nominal_rate) + S(e[ch::domega]);
  r.beta = S(beta);
  r.gamma_0 = S(phi0);
  r.gamma_rate = mode == PlatformMode::counter_rotating ? S(-(r.theta1_rate + S(e[ch::dOmega]))) : S(0);
  return r;
}

// The same with the drives' rate ripple of `e` (channels ripple1, ripple3 of `layout`) and the platform's
// control (geo.platform_control). A fixed platform does not turn, so it has neither ripple nor following.
template <class S, class Errors>
RunMotion<S> run_motion(double nominal_rate, double theta1_0, double phi0, PlatformMode mode,
                        const Geometry& geo, const ErrorLayout& layout, const Errors& e) {
  RunMotion<S> r = run_motion<S>(nominal_rate, theta1_0, phi0, mode, geo.beta, e);
  const int order = layout.harmonic_order();
  auto coefficients = [&](int channel) {
    std::vector<S> c(std::size_t(2 * order));
    bool any = false;
    for (int k = 1; k <= order; ++k)
      for (bool sine : {false, true}) {
        const S v = S(e[layout.harmonic_index(channel, k, sine)]);
        c[std::size_t(2 * k - 2 + (sine ? 1 : 0))] = v;
        any = any || !is_exactly_zero(v);
      }
    return any ? c : std::vector<S>{};
  };
  const bool counter = mode == PlatformMode::counter_rotating;
  r.main_ripple = coefficients(ch::ripple1);
  if (counter) {
    r.platform_ripple = coefficients(ch::ripple3);
    r.platform_follows_main = geo.platform_control == PlatformControl::phase_locked;
  }
  return r;
}

}  // namespace ccal
