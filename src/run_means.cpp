#include "ccal/run_means.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <stdexcept>

#include "ccal/frames.hpp"
#include "ccal/kinematics.hpp"
#include "ccal/quadrature.hpp"

namespace ccal {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// The instrument's output as a polynomial in a_i plus the other terms (instrument.hpp), for one pass per node.
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
  double operator()(const Vector3d& a, double w_ia) const {
    double out = power[std::size_t(degree)];
    for (int n = degree - 1; n >= 0; --n) out = out * a[0] + power[std::size_t(n)];
    out += abs_square * std::abs(a[0]) * a[0] + rate * w_ia;
    if (cross)
      out += p * a[1] + o * a[2] + ip * a[0] * a[1] + io * a[0] * a[2] + pp * a[1] * a[1] + oo * a[2] * a[2] +
             po * a[1] * a[2];
    return out;
  }
};

// Motion of the frame after one joint of the chain (main axis or platform) relative to the frame before it:
// the joint's runout d(q), its wobbles Ry(θy(q))·Rx(θx(q)), then Rz(q), with q turning at q̇ (kinematics.hpp,
// exact_state). The five channels (x, y, z runout; x, y wobble) are consecutive in the error vector, each as
// c0, c1, s1, …, cN, sN.
struct JointLink {
  Vector3d e1, e2, e3;  // columns of Ry(θy)·Rx(θx)
  double c, s;          // cos q, sin q
  Vector3d d, d_rate, d_acc;
  Vector3d w, dw;  // angular velocity and acceleration of the frame after the joint

  // R = [e1 e2 e3]·Rz(q): Rᵀx and R x.
  Vector3d to_local(const Vector3d& x) const {
    const double x1 = e1.dot(x), x2 = e2.dot(x);
    return {c * x1 + s * x2, c * x2 - s * x1, e3.dot(x)};
  }
  Vector3d from_local(const Vector3d& x) const {
    return (c * x[0] - s * x[1]) * e1 + (s * x[0] + c * x[1]) * e2 + x[2] * e3;
  }
};

JointLink joint_link(const double* coefficients, int order, double c, double s, double rate) {
  // cos kq, sin kq by the angle-addition recurrence.
  std::array<double, 2 * 64 + 2> ck_sk;
  double* ck = ck_sk.data();
  double* sk = ck + 65;
  ck[1] = c;
  sk[1] = s;
  for (int k = 2; k <= order; ++k) {
    ck[k] = ck[k - 1] * c - sk[k - 1] * s;
    sk[k] = sk[k - 1] * c + ck[k - 1] * s;
  }
  double value[5], first[5], second[5];  // v, dv/dq, d²v/dq²
  const int stride = 2 * order + 1;
  for (int ch = 0; ch < 5; ++ch) {
    const double* a = coefficients + ch * stride;
    double v = a[0], d1 = 0, d2 = 0;
    for (int k = 1; k <= order; ++k) {
      const double term = a[2 * k - 1] * ck[k] + a[2 * k] * sk[k];
      v += term;
      d1 += double(k) * (a[2 * k] * ck[k] - a[2 * k - 1] * sk[k]);
      d2 -= double(k * k) * term;
    }
    value[ch] = v;
    first[ch] = d1;
    second[ch] = d2;
  }
  JointLink j;
  j.c = c;
  j.s = s;
  const double rate2 = rate * rate;
  j.d = {value[0], value[1], value[2]};
  j.d_rate = rate * Vector3d(first[0], first[1], first[2]);
  j.d_acc = rate2 * Vector3d(second[0], second[1], second[2]);
  double cx, sx, cy, sy;
  cos_sin(value[3], cx, sx);
  cos_sin(value[4], cy, sy);
  const double wx_rate = rate * first[3], wx_acc = rate2 * second[3];
  const double wy_rate = rate * first[4], wy_acc = rate2 * second[4];
  j.e1 = {cy, 0, -sy};
  j.e2 = {sy * sx, cx, cy * sx};
  j.e3 = {sy * cx, -sx, cy * cx};
  // ω = θ̇y ŷ + θ̇x e1 + q̇ e3;  ω̇ = θ̈y ŷ + θ̈x e1 + θ̇y θ̇x (ŷ × e1) + (θ̇y ŷ + θ̇x e1) × q̇ e3 (fixed axes).
  const Vector3d y_axis = Vector3d::UnitY();
  const Vector3d w_wobble = wy_rate * y_axis + wx_rate * j.e1;
  j.dw = wy_acc * y_axis + wx_acc * j.e1 + (wy_rate * wx_rate) * Vector3d(-sy, 0, -cy) +
         w_wobble.cross(rate * j.e3);
  j.w = w_wobble + rate * j.e3;
  return j;
}

// Velocity and acceleration of the point at `offset` (coordinates after the joint) in the joint's parent
// frame: d + R·offset differentiated with the link's ω, ω̇.
struct PointMotion {
  Vector3d r, v, a;
};
PointMotion point_motion(const JointLink& j, const Vector3d& offset) {
  const Vector3d q = j.from_local(offset);
  const Vector3d wq = j.w.cross(q);
  return {j.d + q, j.d_rate + wq, j.d_acc + j.dw.cross(q) + j.w.cross(wq)};
}

// cos and sin of (a + δ) from those of a and a small (or not) δ.
void turn(double c, double s, double delta, double& c_out, double& s_out) {
  double cd, sd;
  cos_sin(delta, cd, sd);
  c_out = c * cd - s * sd;
  s_out = s * cd + c * sd;
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
  std::vector<Vector3d> F0, W, dW, coriolis, W_total;
  void reserve(int M, int Q) {
    const auto n = std::size_t(M * Q), harmonics = std::size_t((M / 2 + 1) * Q);
    if (weights.size() < n) weights.resize(n);
    if (nu_re.size() < harmonics) {
      nu_re.resize(harmonics);
      nu_im.resize(harmonics);
    }
    if (F0.size() < std::size_t(M))
      for (auto* v : {&F0, &W, &dW, &coriolis, &W_total}) v->resize(std::size_t(M));
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
      throw std::invalid_argument(fmt::format("RunMeanKernel: {} fast nodes; an even number ≥ 2 is needed", t.M));
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
    throw std::invalid_argument(fmt::format("RunMeanKernel::means: {} errors for a layout of {}, {} outputs for {} runs",
                                            errors.size(), d.layout.size(), out.size(), d.runs.size()));
  thread_local Scratch scratch;
  const Eigen::Map<const Eigen::VectorXd> e(errors.data(), Eigen::Index(errors.size()));
  // A, B (without the arm stretch, which depends on the run's rate) and C.
  const ChainBlocks<double> blocks = chain_blocks<double>(d.geometry, d.layout, e, d.site, 0.0, d.geometry.beta);
  const Matrix3d RB_t = blocks.RB.transpose();
  const double* main_coefficients = errors.data() + d.layout.harmonic_index(dx1, 0, false);
  const double* platform_coefficients = errors.data() + d.layout.harmonic_index(dx3, 0, false);
  const int order = d.layout.harmonic_order();
  const double g = d.site.g, inverse_g = 1.0 / g;

  for (std::size_t r = 0; r < d.runs.size(); ++r) {
    const Data::RunTables& t = d.runs[r];
    const int M = t.M;
    const double theta1_rate = t.rate + e[domega];
    const double gamma_rate = t.counter ? -(theta1_rate + e[dOmega]) : 0.0;
    const double drift = t.counter ? std::abs(e[dOmega]) * t.duration * (M / 4) : 0.0;
    const int Q = t.counter ? (d.quadrature.slow_nodes > 0 ? d.quadrature.slow_nodes
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
      turn(t.cos_half[std::size_t(m)], t.sin_half[std::size_t(m)], double(m) * e[domega] * t.duration / 2.0, c, s);
      detail::harmonic_slow_moments<double>(omega_T * double(m) / 2.0, c, s, a, &scratch.nu_re[std::size_t(m * Q)],
                                            &scratch.nu_im[std::size_t(m * Q)]);
    }
    detail::dft_weights<double>(t.table, Q, scratch.nu_re.data(), scratch.nu_im.data(), scratch.weights.data());

    // Main-axis half at each fast node, carried into frame-3t coordinates.
    Vector3d pB = blocks.pB;
    pB[0] += e[arm_stretch] * theta1_rate * theta1_rate;
    for (int j = 0; j < M; ++j) {
      const JointLink main = joint_link(main_coefficients, order, t.cos_theta[std::size_t(j)],
                                        t.sin_theta[std::size_t(j)], theta1_rate);
      const PointMotion o3t = point_motion(main, pB);
      const Vector3d F0 = o3t.a + 2.0 * blocks.coriolis_1t.cross(o3t.v) + g * blocks.gravity_1t;
      auto to_3t = [&](const Vector3d& x) { return Vector3d(RB_t * main.to_local(x)); };
      scratch.F0[std::size_t(j)] = to_3t(F0);
      scratch.W[std::size_t(j)] = to_3t(main.w);
      scratch.dW[std::size_t(j)] = to_3t(main.dw);
      scratch.coriolis[std::size_t(j)] = to_3t(blocks.coriolis_1t);
      scratch.W_total[std::size_t(j)] = to_3t(main.w + blocks.earth_1t);
    }

    // Platform nodes: frame 5 relative to frame 3t, then the instrument's axes through P = R_C·mounting.
    const Matrix3d P_t = (blocks.RC * t.mount).transpose();
    const std::vector<double>& x_nodes = d.slow_nodes[std::size_t(Q)];
    double mean = 0;
    for (int q = 0; q < Q; ++q) {
      const double slow_offset = t.counter ? -e[dOmega] * (0.5 * (1.0 + x_nodes[std::size_t(q)]) * t.duration) : 0.0;
      double cd, sd;
      cos_sin(slow_offset, cd, sd);
      for (int j = 0; j < M; ++j) {
        const auto J = std::size_t(j);
        const double cg = t.cos_gamma[J] * cd - t.sin_gamma[J] * sd;
        const double sg = t.sin_gamma[J] * cd + t.cos_gamma[J] * sd;
        const JointLink platform = joint_link(platform_coefficients, order, cg, sg, gamma_rate);
        const PointMotion o5 = point_motion(platform, blocks.pC);
        const Vector3d& W = scratch.W[J];
        const Vector3d Wr = W.cross(o5.r);
        const Vector3d f = scratch.F0[J] + scratch.dW[J].cross(o5.r) + W.cross(Wr) + 2.0 * W.cross(o5.v) + o5.a +
                           2.0 * scratch.coriolis[J].cross(Wr + o5.v);
        const Vector3d w = scratch.W_total[J] + platform.w;
        const Vector3d a_instrument = inverse_g * (P_t * platform.to_local(f));
        const double w_ia = P_t.row(0).dot(platform.to_local(w));
        mean += scratch.weights[std::size_t(q * M + j)] * d.output(a_instrument, w_ia);
      }
    }
    out[r] = mean;
  }
}

}  // namespace ccal
