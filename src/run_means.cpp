#include "ccal/run_means.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <type_traits>

#include "ccal/frames.hpp"
#include "ccal/kinematics.hpp"
#include "ccal/quadrature.hpp"

namespace ccal {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// The instrument's output as a polynomial in a_i plus the other terms (instrument.hpp), for one pass per
// node.
struct OutputPolynomial {
  std::array<double, kMaxPower + 1> power{};  // K_n of a_iⁿ
  int degree = 0;
  double abs_square = 0, p = 0, o = 0, ip = 0, io = 0, pp = 0, oo = 0, po = 0;
  double rate = 0;  // s_ω + K_w
  bool cross = false;

  explicit OutputPolynomial(const InstrumentModel& model) : rate(model.rate_gain) {
    const std::vector<TermSpec> terms = model.terms();
    for (std::size_t k = 0; k < terms.size(); ++k) {
      const double K = model.coefficients[Eigen::Index(k)];
      switch (terms[k].kind) {
        case TermKind::power:
          power[std::size_t(terms[k].power)] += K;
          degree = std::max(degree, terms[k].power);
          break;
        case TermKind::abs_square:
          abs_square += K;
          break;
        case TermKind::p:
          p += K;
          break;
        case TermKind::o:
          o += K;
          break;
        case TermKind::ip:
          ip += K;
          break;
        case TermKind::io:
          io += K;
          break;
        case TermKind::pp:
          pp += K;
          break;
        case TermKind::oo:
          oo += K;
          break;
        case TermKind::po:
          po += K;
          break;
        case TermKind::rate:
          rate += K;
          break;
      }
    }
    cross = p != 0 || o != 0 || ip != 0 || io != 0 || pp != 0 || oo != 0 || po != 0;
  }
  double operator()(double a_i, double a_p, double a_o, double w_ia) const {
    double out = power[std::size_t(degree)];
    for (int n = degree - 1; n >= 0; --n) out = out * a_i + power[std::size_t(n)];
    out += abs_square * std::abs(a_i) * a_i + rate * w_ia;
    if (cross)
      out += p * a_p + o * a_o + ip * a_i * a_p + io * a_i * a_o + pp * a_p * a_p + oo * a_o * a_o +
             po * a_p * a_o;
    return out;
  }
};

// The node loops are written once for a lane type T: double (one node at a time) or Pack, four nodes at a
// time in GCC's portable SIMD vectors. Node data is stored as structure of arrays padded to whole packs;
// there are no branches in the loop bodies, and floating-point contraction stays off, so that both lane
// types and every instruction set give the same bits.
// Pack values pass between functions of this file only, all inlined into the cloned loops, so the ABI note
// GCC gives for 32-byte vectors in baseline code is moot here.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
using Pack = double __attribute__((vector_size(4 * sizeof(double))));
inline constexpr int kPackLanes = 4;
template <class T>
inline constexpr int kLanes = std::is_same_v<T, Pack> ? kPackLanes : 1;
template <class T>
[[gnu::always_inline]] inline T load(const double* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class T>
[[gnu::always_inline]] inline void store(double* p, const T& v) {
  std::memcpy(p, &v, sizeof v);
}
int padded(int n) { return (n + kPackLanes - 1) / kPackLanes * kPackLanes; }

template <class T>
struct V3 {
  T x, y, z;
};
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
V3<double> to_v3(const Vector3d& v) { return {v[0], v[1], v[2]}; }

// Structure-of-arrays storage of 3-vectors, one per node.
struct V3Array {
  std::vector<double> x, y, z;
  void resize(std::size_t n) {
    x.resize(n);
    y.resize(n);
    z.resize(n);
  }
  template <class T>
  [[gnu::always_inline]] V3<T> get(std::size_t i) const {
    return {load<T>(&x[i]), load<T>(&y[i]), load<T>(&z[i])};
  }
  template <class T>
  [[gnu::always_inline]] void set(std::size_t i, const V3<T>& v) {
    store(&x[i], v.x);
    store(&y[i], v.y);
    store(&z[i], v.z);
  }
};

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

// Motion of the frame after one joint of the chain (main axis or platform) relative to the frame before it:
// the joint's runout d(q), its wobbles Ry(θy(q))·Rx(θx(q)), then Rz(q), with q turning at q̇ (kinematics.hpp,
// exact_state). Pack lanes use the small-angle series for the wobbles, so they are only used when both
// wobble angles are known to stay below kSmallAngle (always_small).
template <class T>
struct JointLink {
  V3<T> e1, e2, e3;  // columns of Ry(θy)·Rx(θx)
  T c, s;            // cos q, sin q
  V3<T> d, d_rate, d_acc;
  V3<T> w, dw;  // angular velocity and acceleration of the frame after the joint
};
template <int kOrder, class T>
[[gnu::always_inline]] inline JointLink<T> joint_link(const JointCoefficients<kOrder>& a, const T& c,
                                                      const T& s, double rate) {
  const ChannelSeries<T> x = channel_series(a, 0, c, s), y = channel_series(a, 1, c, s),
                         z = channel_series(a, 2, c, s), tx = channel_series(a, 3, c, s),
                         ty = channel_series(a, 4, c, s);
  JointLink<T> j;
  j.c = c;
  j.s = s;
  const double rate2 = rate * rate;
  j.d = {x.value, y.value, z.value};
  j.d_rate = {rate * x.first, rate * y.first, rate * z.first};
  j.d_acc = {rate2 * x.second, rate2 * y.second, rate2 * z.second};
  T cx, sx, cy, sy;
  if constexpr (std::is_same_v<T, Pack>) {
    small_angle_cos_sin(tx.value, cx, sx);
    small_angle_cos_sin(ty.value, cy, sy);
  } else {
    cos_sin(tx.value, cx, sx);
    cos_sin(ty.value, cy, sy);
  }
  const T wx_rate = rate * tx.first, wx_acc = rate2 * tx.second;
  const T wy_rate = rate * ty.first, wy_acc = rate2 * ty.second;
  j.e1 = {cy, T{}, -sy};
  j.e2 = {sy * sx, cx, cy * sx};
  j.e3 = {sy * cx, -sx, cy * cx};
  // ω = θ̇y ŷ + θ̇x e1 + q̇ e3;  ω̇ = θ̈y ŷ + θ̈x e1 + θ̇y θ̇x (ŷ × e1) + (θ̇y ŷ + θ̇x e1) × q̇ e3, ŷ × e1 = (−sy, 0,
  // −cy).
  const V3<T> w_wobble{wx_rate * cy, wy_rate, -wx_rate * sy};
  const V3<T> dw_wobble{wx_acc * cy - wy_rate * wx_rate * sy, wy_acc, -wx_acc * sy - wy_rate * wx_rate * cy};
  j.dw = dw_wobble + cross(w_wobble, rate * j.e3);
  j.w = w_wobble + rate * j.e3;
  return j;
}
// R = [e1 e2 e3]·Rz(q): Rᵀx and R x.
template <class T>
[[gnu::always_inline]] inline V3<T> to_local(const JointLink<T>& j, const V3<T>& x) {
  const T x1 = dot(j.e1, x), x2 = dot(j.e2, x);
  return {j.c * x1 + j.s * x2, j.c * x2 - j.s * x1, dot(j.e3, x)};
}
template <class T>
[[gnu::always_inline]] inline V3<T> from_local(const JointLink<T>& j, const V3<double>& x) {
  return (j.c * x.x - j.s * x.y) * j.e1 + (j.s * x.x + j.c * x.y) * j.e2 + x.z * j.e3;
}
// Position, velocity and acceleration of the point at `offset` (coordinates after the joint) in the joint's
// parent frame: r = d + R·offset differentiated with the link's ω, ω̇.
template <class T>
struct PointMotion {
  V3<T> r, v, a;
};
template <class T>
[[gnu::always_inline]] inline PointMotion<T> point_motion(const JointLink<T>& j, const V3<double>& offset) {
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

// cos and sin of (a + δ) from those of a and a small (or not) δ.
void turn(double c, double s, double delta, double& c_out, double& s_out) {
  double cd, sd;
  cos_sin(delta, cd, sd);
  c_out = c * cd - s * sd;
  s_out = s * cd + c * sd;
}

// Whether every value of a dynamic channel (c0, c1, s1, … at `coefficients`) stays below kSmallAngle.
bool always_small(const double* coefficients, int order) {
  double bound = 0;
  for (int i = 0; i < 2 * order + 1; ++i) bound += std::abs(coefficients[i]);
  return bound < kSmallAngle;
}

// Node data: the main-axis half per fast node, the instrument's inputs per node (slow-major, each slow node
// padded to whole packs).
struct MainAxisNodes {
  // F₀ = a + 2ω_c × v + g ẑ₀ of o3t; Ω, Ω̇ of frame 3t; ω_c; Ω + ω_ie (frame-3t coordinates)
  V3Array F0, W, dW, coriolis, W_total;
  void resize(std::size_t n) {
    for (V3Array* a : {&F0, &W, &dW, &coriolis, &W_total}) a->resize(n);
  }
};
struct InstrumentInputs {
  std::vector<double> a_i, a_p, a_o, w_ia;  // [g], [g], [g], [rad/s]
  void resize(std::size_t n) {
    for (auto* v : {&a_i, &a_p, &a_o, &w_ia}) v->resize(n);
  }
};

// Main-axis half (frame 3t, a function of θ1 alone) at the fast nodes, in frame-3t coordinates.
struct MainAxisInputs {
  const double* coefficients;  // dx1 … dthy1
  int order;
  const double *cos_theta, *sin_theta;  // padded
  int M;
  double rate, g;
  V3<double> pB, coriolis_1t, gravity_1t, earth_1t;
  Matrix3d RB;
};
template <int kOrder, class T>
[[gnu::always_inline]] inline void main_axis_loop(const MainAxisInputs& in, MainAxisNodes& out) {
  const JointCoefficients<kOrder> coefficients{in.coefficients, in.order};
  const Columns B(in.RB);
  const V3<T> coriolis_1t = broadcast<T>(in.coriolis_1t), gravity_1t = broadcast<T>(in.gravity_1t),
              earth_1t = broadcast<T>(in.earth_1t);
  for (int j = 0; j < in.M; j += kLanes<T>) {
    const JointLink<T> main =
        joint_link(coefficients, load<T>(in.cos_theta + j), load<T>(in.sin_theta + j), in.rate);
    const PointMotion<T> o3t = point_motion(main, in.pB);
    const V3<T> F0 = o3t.a + 2.0 * cross(coriolis_1t, o3t.v) + in.g * gravity_1t;
    // x in frame-3t coordinates: R_Bᵀ (R_jointᵀ x).
    const auto J = std::size_t(j);
    out.F0.set(J, B.transpose_times(to_local(main, F0)));
    out.W.set(J, B.transpose_times(to_local(main, main.w)));
    out.dW.set(J, B.transpose_times(to_local(main, main.dw)));
    out.coriolis.set(J, B.transpose_times(to_local(main, coriolis_1t)));
    out.W_total.set(J, B.transpose_times(to_local(main, main.w + earth_1t)));
  }
}

// Platform nodes of one slow node: frame 5 relative to frame 3t, composed with the main-axis half of the
// same fast node, then the instrument's axes through P = R_C·mounting. Writes a_i, a_p, a_o [g] and ω_IA
// at nodes first … first + M − 1 (and the padding after them).
struct PlatformInputs {
  const double* coefficients;  // dx3 … dthy3
  int order;
  const double *cos_gamma, *sin_gamma;  // nominal platform angle at the fast nodes, padded
  double cos_offset, sin_offset;        // the slow node's drift
  int M;
  double rate, inverse_g;
  V3<double> pC;
  Matrix3d P;
};
template <int kOrder, class T>
[[gnu::always_inline]] inline void platform_loop(const PlatformInputs& in, const MainAxisNodes& main,
                                                 InstrumentInputs& out, std::size_t first) {
  const JointCoefficients<kOrder> coefficients{in.coefficients, in.order};
  const Columns P(in.P);
  for (int j = 0; j < in.M; j += kLanes<T>) {
    const auto J = std::size_t(j);
    const T cos_gamma = load<T>(in.cos_gamma + j), sin_gamma = load<T>(in.sin_gamma + j);
    const T cg = cos_gamma * in.cos_offset - sin_gamma * in.sin_offset;
    const T sg = sin_gamma * in.cos_offset + cos_gamma * in.sin_offset;
    const JointLink<T> platform = joint_link(coefficients, cg, sg, in.rate);
    const PointMotion<T> o5 = point_motion(platform, in.pC);
    const V3<T> W = main.W.get<T>(J);
    const V3<T> Wr = cross(W, o5.r);
    const V3<T> f = main.F0.get<T>(J) + cross(main.dW.get<T>(J), o5.r) + cross(W, Wr) + 2.0 * cross(W, o5.v) +
                    o5.a + 2.0 * cross(main.coriolis.get<T>(J), Wr + o5.v);
    const V3<T> w = main.W_total.get<T>(J) + platform.w;
    const V3<T> f5 = to_local(platform, f), w5 = to_local(platform, w);
    store(&out.a_i[first + J], in.inverse_g * dot(f5, P.c0));
    store(&out.a_p[first + J], in.inverse_g * dot(f5, P.c1));
    store(&out.a_o[first + J], in.inverse_g * dot(f5, P.c2));
    store(&out.w_ia[first + J], dot(w5, P.c0));
  }
}

// The loops for the harmonic order at hand, four nodes at a time when the wobbles are small (always, for
// real centrifuges), compiled for each instruction set the machine may have (AVX-512, AVX2, baseline) and
// chosen when the library is loaded.
#if defined(__x86_64__) && defined(__ELF__) && defined(__GNUC__) && !defined(__clang__)
#define CCAL_CLONED [[gnu::target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")]]
#else
#define CCAL_CLONED
#endif
CCAL_CLONED void main_axis_nodes(const MainAxisInputs& in, bool small, MainAxisNodes& out) {
  switch (in.order) {
    case 0:
      return small ? main_axis_loop<0, Pack>(in, out) : main_axis_loop<0, double>(in, out);
    case 1:
      return small ? main_axis_loop<1, Pack>(in, out) : main_axis_loop<1, double>(in, out);
    case 2:
      return small ? main_axis_loop<2, Pack>(in, out) : main_axis_loop<2, double>(in, out);
    default:
      return small ? main_axis_loop<kRuntimeOrder, Pack>(in, out)
                   : main_axis_loop<kRuntimeOrder, double>(in, out);
  }
}
CCAL_CLONED void platform_nodes(const PlatformInputs& in, bool small, const MainAxisNodes& main,
                                InstrumentInputs& out, std::size_t first) {
  switch (in.order) {
    case 0:
      return small ? platform_loop<0, Pack>(in, main, out, first)
                   : platform_loop<0, double>(in, main, out, first);
    case 1:
      return small ? platform_loop<1, Pack>(in, main, out, first)
                   : platform_loop<1, double>(in, main, out, first);
    case 2:
      return small ? platform_loop<2, Pack>(in, main, out, first)
                   : platform_loop<2, double>(in, main, out, first);
    default:
      return small ? platform_loop<kRuntimeOrder, Pack>(in, main, out, first)
                   : platform_loop<kRuntimeOrder, double>(in, main, out, first);
  }
}

}  // namespace

struct RunMeanKernel::Data {
  struct RunTables {
    double rate = 0;  // nominal Ω [rad/s]
    double duration = 0;
    bool counter = false;
    int M = 0;
    detail::FastPhaseTable table{2};
    std::vector<double> cos_theta, sin_theta;  // θ1(0) + θ_j
    std::vector<double> cos_gamma, sin_gamma;  // φ0 − θ_j (counter-rotating) or φ0
    std::vector<double> cos_half, sin_half;    // mΩT/2, m = 0..M/2
    Matrix3d mount;
  };
  Geometry geometry;
  ErrorLayout layout;
  Site site;
  OutputPolynomial output;
  QuadratureOptions quadrature;
  std::vector<RunTables> runs;
  // Slow-time nodes and their Lagrange monomials for Q = 1..kMaxSlowNodes.
  std::vector<std::vector<double>> slow_nodes;
  std::vector<Eigen::MatrixXd> lagrange;

  Data(const Geometry& g, const ErrorLayout& l, const Site& s, const InstrumentModel& instrument,
       const QuadratureOptions& q)
      : geometry(g), layout(l), site(s), output(instrument), quadrature(q) {}
};

namespace {

// Per-thread scratch space, grown when a larger rule is met and then reused.
struct Scratch {
  std::vector<double> nu_re, nu_im, weights;
  MainAxisNodes main;
  InstrumentInputs inputs;
  std::size_t fast = 0, nodes = 0;
  void reserve(int M, int Q) {
    const auto n = std::size_t(padded(M) * Q), harmonics = std::size_t((M / 2 + 1) * Q);
    if (nodes < n) {
      weights.resize(n);
      inputs.resize(n);
      nodes = n;
    }
    if (nu_re.size() < harmonics) {
      nu_re.resize(harmonics);
      nu_im.resize(harmonics);
    }
    if (fast < std::size_t(padded(M))) {
      main.resize(std::size_t(padded(M)));
      fast = std::size_t(padded(M));
    }
  }
};

}  // namespace

RunMeanKernel::RunMeanKernel(const Geometry& geometry, const ErrorLayout& layout, const Site& site,
                             const std::vector<Run>& runs, const InstrumentModel& instrument,
                             const ReductionOptions& options) {
  if (options.chain.frozen_platform)
    throw std::invalid_argument("RunMeanKernel: the frozen-platform chain is not supported");
  auto data = std::make_unique<Data>(geometry, layout, site, instrument, options.quadrature);
  const std::vector<TermSpec> terms = instrument.terms();
  const int degree = polynomial_degree(terms);
  for (const Run& run : runs) {
    Data::RunTables t;
    t.rate = nominal_rate(run, geometry, site);
    t.duration = run.duration;
    t.counter = run.mode == PlatformMode::counter_rotating;
    const bool kink = t.counter && has_non_smooth_term(terms);
    t.M = options.quadrature.fast_nodes > 0
              ? options.quadrature.fast_nodes
              : (kink ? 512 : fast_nodes_for(degree, layout.harmonic_order() + 1));
    if (t.M < 2 || t.M % 2 != 0)
      throw std::invalid_argument(
          fmt::format("RunMeanKernel: {} fast nodes; an even number ≥ 2 is needed", t.M));
    t.table = detail::FastPhaseTable(t.M);
    const double phi0 = initial_phase(run, geometry, site);
    for (int j = 0; j < t.M; ++j) {
      const double theta = t.table.phase(j);
      // The same sums run_quadrature forms for the joint angles.
      const double theta1 = run.arm_azimuth + theta;
      const double gamma = phi0 - (t.counter ? theta : 0.0);
      t.cos_theta.push_back(std::cos(theta1));
      t.sin_theta.push_back(std::sin(theta1));
      t.cos_gamma.push_back(std::cos(gamma));
      t.sin_gamma.push_back(std::sin(gamma));
    }
    // Padding up to whole packs: harmless angle 0, never summed.
    for (int j = t.M; j < padded(t.M); ++j)
      for (auto* v : {&t.cos_theta, &t.cos_gamma}) v->push_back(1.0);
    for (int j = t.M; j < padded(t.M); ++j)
      for (auto* v : {&t.sin_theta, &t.sin_gamma}) v->push_back(0.0);
    for (int m = 0; m <= t.M / 2; ++m) {
      const double half_kappa = t.rate * t.duration * double(m) / 2.0;
      t.cos_half.push_back(std::cos(half_kappa));
      t.sin_half.push_back(std::sin(half_kappa));
    }
    t.mount = mounting_matrix(run.mounting);
    data->runs.push_back(std::move(t));
  }
  data->slow_nodes.resize(detail::kMaxSlowNodes + 1);
  data->lagrange.resize(detail::kMaxSlowNodes + 1);
  for (int Q = 1; Q <= detail::kMaxSlowNodes; ++Q) {
    data->slow_nodes[std::size_t(Q)] = detail::slow_time_nodes(Q);
    data->lagrange[std::size_t(Q)] = detail::lagrange_monomials(data->slow_nodes[std::size_t(Q)]);
  }
  data_ = std::move(data);
}

RunMeanKernel::~RunMeanKernel() = default;
RunMeanKernel::RunMeanKernel(RunMeanKernel&&) noexcept = default;
RunMeanKernel& RunMeanKernel::operator=(RunMeanKernel&&) noexcept = default;

std::size_t RunMeanKernel::run_count() const { return data_->runs.size(); }

void RunMeanKernel::means(std::span<const double> errors, std::span<double> out) const {
  const Data& d = *data_;
  if (errors.size() != std::size_t(d.layout.size()) || out.size() != d.runs.size())
    throw std::invalid_argument(
        fmt::format("RunMeanKernel::means: {} errors for a layout of {}, {} outputs for {} runs",
                    errors.size(), d.layout.size(), out.size(), d.runs.size()));
  thread_local Scratch scratch;
  const Eigen::Map<const Eigen::VectorXd> e(errors.data(), Eigen::Index(errors.size()));
  // A, B (without the arm stretch, which depends on the run's rate) and C.
  const ChainBlocks<double> blocks =
      chain_blocks<double>(d.geometry, d.layout, e, d.site, 0.0, d.geometry.beta);
  const double* main_coefficients = errors.data() + d.layout.harmonic_index(dx1, 0, false);
  const double* platform_coefficients = errors.data() + d.layout.harmonic_index(dx3, 0, false);
  const int order = d.layout.harmonic_order();
  const double g = d.site.g;
  const bool main_small = always_small(main_coefficients + 3 * (2 * order + 1), order) &&
                          always_small(main_coefficients + 4 * (2 * order + 1), order);
  const bool platform_small = always_small(platform_coefficients + 3 * (2 * order + 1), order) &&
                              always_small(platform_coefficients + 4 * (2 * order + 1), order);

  for (std::size_t r = 0; r < d.runs.size(); ++r) {
    const Data::RunTables& t = d.runs[r];
    const int M = t.M;
    const double theta1_rate = t.rate + e[domega];
    const double gamma_rate = t.counter ? -(theta1_rate + e[dOmega]) : 0.0;
    const double drift = t.counter ? std::abs(e[dOmega]) * t.duration * (M / 4) : 0.0;
    const int Q = t.counter
                      ? (d.quadrature.slow_nodes > 0 ? d.quadrature.slow_nodes
                                                     : slow_nodes_for(drift, d.quadrature.slow_tolerance))
                      : 1;
    if (Q > detail::kMaxSlowNodes)
      throw std::invalid_argument("RunMeanKernel: at most 16 slow-time nodes (monomial Lagrange basis)");
    scratch.reserve(M, Q);

    // Weights (quadrature.hpp): κ/2 = m(Ω + Δω)T/2, its cosine and sine turned from the nominal mΩT/2.
    const double omega_T = theta1_rate * t.duration;
    const Eigen::MatrixXd& a = d.lagrange[std::size_t(Q)];
    for (int m = 0; m <= M / 2; ++m) {
      double c, s;
      turn(t.cos_half[std::size_t(m)], t.sin_half[std::size_t(m)], double(m) * e[domega] * t.duration / 2.0,
           c, s);
      detail::harmonic_slow_moments<double>(omega_T * double(m) / 2.0, c, s, a,
                                            &scratch.nu_re[std::size_t(m * Q)],
                                            &scratch.nu_im[std::size_t(m * Q)]);
    }
    detail::dft_weights<double>(t.table, Q, scratch.nu_re.data(), scratch.nu_im.data(),
                                scratch.weights.data());

    // Main-axis half at each fast node, carried into frame-3t coordinates.
    MainAxisInputs main{main_coefficients,
                        order,
                        t.cos_theta.data(),
                        t.sin_theta.data(),
                        M,
                        theta1_rate,
                        g,
                        to_v3(blocks.pB),
                        to_v3(blocks.coriolis_1t),
                        to_v3(blocks.gravity_1t),
                        to_v3(blocks.earth_1t),
                        blocks.RB};
    main.pB.x += e[arm_stretch] * theta1_rate * theta1_rate;
    main_axis_nodes(main, main_small, scratch.main);

    // Platform nodes, slow-major like the weights.
    PlatformInputs platform{platform_coefficients,
                            order,
                            t.cos_gamma.data(),
                            t.sin_gamma.data(),
                            1.0,
                            0.0,
                            M,
                            gamma_rate,
                            1.0 / g,
                            to_v3(blocks.pC),
                            blocks.RC * t.mount};
    const std::vector<double>& x_nodes = d.slow_nodes[std::size_t(Q)];
    for (int q = 0; q < Q; ++q) {
      const double slow_offset =
          t.counter ? -e[dOmega] * (0.5 * (1.0 + x_nodes[std::size_t(q)]) * t.duration) : 0.0;
      cos_sin(slow_offset, platform.cos_offset, platform.sin_offset);
      platform_nodes(platform, platform_small, scratch.main, scratch.inputs, std::size_t(q * padded(M)));
    }
    double mean = 0;
    for (int q = 0; q < Q; ++q)
      for (int j = 0; j < M; ++j) {
        const auto n = std::size_t(q * padded(M) + j);
        mean +=
            scratch.weights[std::size_t(q * M + j)] * d.output(scratch.inputs.a_i[n], scratch.inputs.a_p[n],
                                                               scratch.inputs.a_o[n], scratch.inputs.w_ia[n]);
      }
    out[r] = mean;
  }
}

}  // namespace ccal
