#include "ccal/reduction/run_means.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "ccal/core/frames.hpp"
#include "ccal/model/kinematics.hpp"
#include "ccal/reduction/quadrature.hpp"
#include "run_means_nodes.hpp"

namespace ccal {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using run_nodes::always_small;
using run_nodes::InstrumentInputs;
using run_nodes::MainAxisInputs;
using run_nodes::MainAxisNodes;
using run_nodes::padded;
using run_nodes::PlatformInputs;
using run_nodes::to_v3;

}  // namespace

// The kernel's tables and scratch space are named (not file-local): RunMeanKernel::Data and
// Workspace::Buffers, declared in the header, derive from them.
namespace run_nodes {

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

}  // namespace run_nodes

namespace {

// cos and sin of (a + δ) from those of a and a small (or not) δ.
void turn(double c, double s, double delta, double& c_out, double& s_out) {
  double cd, sd;
  cos_sin(delta, cd, sd);
  c_out = c * cd - s * sd;
  s_out = s * cd + c * sd;
}

}  // namespace

namespace run_nodes {

// The tables of one run: everything of the run that does not depend on the errors.
struct RunTables {
  double rate = 0;  // nominal Ω [rad/s]
  double duration = 0;
  bool counter = false;
  int M = 0;
  detail::FastPhaseTable table{2};
  std::vector<double> cos_theta, sin_theta;  // θ1(0) + θ_j
  // φ0 − θ_j (counter-rotating) or φ0 at node n = q·M + j, repeated for the most slow nodes a trial may take
  std::vector<double> cos_gamma, sin_gamma;
  std::vector<double> cos_half, sin_half;    // mΩT/2, m = 0..M/2
  // The DFT of the weights (spectral_weights.hpp's dft_weights) as c_m cos(mθ_j), c_m sin(mθ_j) at
  // [(m − 1)M + j], m = 1..M/2, with c_m = 2 (1 at the Nyquist term): contiguous in j, so that the sums of
  // all nodes run side by side. Scaling by 2 is exact, so each weight is the same double as dft_weights'.
  std::vector<double> dft_cos, dft_sin;
  Matrix3d mount;
};

// The kernel's tables. RunMeanKernel::Data is private to the class; its content is defined here so that the
// free functions of a trial's steps (below means) can take it.
struct KernelTables {
  Geometry geometry;
  ErrorLayout layout;
  Site site;
  OutputPolynomial output;
  QuadratureOptions quadrature;
  std::vector<RunTables> runs;
  // Slow-time nodes and their Lagrange monomials for Q = 1..kMaxSlowNodes.
  std::vector<std::vector<double>> slow_nodes;
  std::vector<Eigen::MatrixXd> lagrange;

  KernelTables(const Geometry& g, const ErrorLayout& l, const Site& s, const InstrumentModel& instrument,
               const QuadratureOptions& q)
      : geometry(g), layout(l), site(s), output(instrument), quadrature(q) {}
};

}  // namespace run_nodes

struct RunMeanKernel::Data : run_nodes::KernelTables {
  using KernelTables::KernelTables;
};

namespace run_nodes {

// Scratch space of one thread, grown when a larger rule is met and then reused (RunMeanKernel::Workspace).
// Nodes n = q·M + j follow each other without padding between slow nodes, so that the platform's loop
// fills whole SIMD vectors across them; the main-axis half is repeated for every slow node.
struct Scratch {
  std::vector<double> nu_re, nu_im, weights;
  std::vector<double> cos_offset, sin_offset;  // slow node q's drift at node n
  MainAxisNodes main;
  InstrumentInputs inputs;
  std::size_t nodes = 0;
  void reserve(int M, int Q) {
    // The main-axis loop writes padded(M) nodes before they are repeated.
    const auto n = std::size_t(std::max(padded(M * Q), padded(M))), harmonics = std::size_t((M / 2 + 1) * Q);
    if (nodes < n) {
      weights.resize(n);
      inputs.resize(n);
      main.resize(n);
      cos_offset.resize(n);
      sin_offset.resize(n);
      nodes = n;
    }
    if (nu_re.size() < harmonics) {
      nu_re.resize(harmonics);
      nu_im.resize(harmonics);
    }
  }
};

}  // namespace run_nodes

namespace {

using run_nodes::KernelTables;
using run_nodes::OutputPolynomial;
using run_nodes::RunTables;
using run_nodes::Scratch;

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
    RunTables t;
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
    for (int m = 1; m <= t.M / 2; ++m)
      for (int j = 0; j < t.M; ++j) {
        const double c_m = m == t.M / 2 ? 1.0 : 2.0;
        t.dft_cos.push_back(c_m * t.table.cos_k[std::size_t(m * j % t.M)]);
        t.dft_sin.push_back(c_m * t.table.sin_k[std::size_t(m * j % t.M)]);
      }
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
    const int repeated = t.M * detail::kMaxSlowNodes;
    for (int n = t.M; n < repeated; ++n) {
      t.cos_gamma.push_back(t.cos_gamma[std::size_t(n - t.M)]);
      t.sin_gamma.push_back(t.sin_gamma[std::size_t(n - t.M)]);
    }
    // Padding up to whole packs: harmless angle 0, never summed.
    for (int j = t.M; j < padded(t.M); ++j) t.cos_theta.push_back(1.0), t.sin_theta.push_back(0.0);
    for (int n = repeated; n < padded(repeated); ++n) t.cos_gamma.push_back(1.0), t.sin_gamma.push_back(0.0);
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
    data->lagrange[std::size_t(Q)] = detail::slow_lagrange_monomials(Q);
  }
  data_ = std::move(data);
}

RunMeanKernel::~RunMeanKernel() = default;
RunMeanKernel::RunMeanKernel(RunMeanKernel&&) noexcept = default;
RunMeanKernel& RunMeanKernel::operator=(RunMeanKernel&&) noexcept = default;

namespace {

// What a trial's errors give every run alike: the chain's blocks A, B (without the arm stretch, which
// depends on the run's rate) and C, the dynamic channels of the two halves, the drives' rate ripple, and
// whether the SIMD small-angle loops apply to each half.
struct TrialTerms {
  ChainBlocks<double> blocks;
  const double* main_coefficients;      // dx1 … dthy1
  const double* platform_coefficients;  // dx3 … dthy3
  const double* main_ripple;            // c1, s1, … of the main drive's rate ripple, nullptr when zero
  const double* platform_ripple;        // the same of the platform drive
  int order;
  double g;
  bool phase_locked, main_small, platform_small;
};

// The drive's rate ripple of `channel` (c1, s1, … after the channel's unused c0), nullptr when zero.
const double* nonzero_ripple(const double* errors, const ErrorLayout& layout, int channel, int order) {
  const double* c = errors + layout.harmonic_index(channel, 0, false) + 1;
  for (int i = 0; i < 2 * order; ++i)
    if (c[i] != 0.0) return c;
  return nullptr;
}

// A half stays in the small-angle loops where its two wobble channels (the 4th and 5th of its dynamic
// channels) and the angle its ripple adds (a phase-locked platform also turns by the main axis's) stay below
// kSmallAngle.
TrialTerms trial_terms(const KernelTables& d, const Eigen::Map<const Eigen::VectorXd>& e) {
  const double* errors = e.data();
  const int order = d.layout.harmonic_order();
  TrialTerms trial{chain_blocks<double>(d.geometry, d.layout, e, d.site, 0.0, d.geometry.beta),
                   errors + d.layout.harmonic_index(ch::dx1, 0, false),
                   errors + d.layout.harmonic_index(ch::dx3, 0, false),
                   nonzero_ripple(errors, d.layout, ch::ripple1, order),
                   nonzero_ripple(errors, d.layout, ch::ripple3, order),
                   order,
                   d.site.g,
                   d.geometry.platform_control == PlatformControl::phase_locked,
                   false,
                   false};
  const double main_ripple_bound = run_nodes::ripple_angle_bound(trial.main_ripple, order);
  trial.main_small = always_small(trial.main_coefficients + 3 * (2 * order + 1), order) &&
                     always_small(trial.main_coefficients + 4 * (2 * order + 1), order) &&
                     main_ripple_bound < kSmallAngle;
  trial.platform_small = always_small(trial.platform_coefficients + 3 * (2 * order + 1), order) &&
                         always_small(trial.platform_coefficients + 4 * (2 * order + 1), order) &&
                         run_nodes::ripple_angle_bound(trial.platform_ripple, order) +
                                 (trial.phase_locked ? main_ripple_bound : 0.0) <
                             kSmallAngle;
  return trial;
}

// The number of slow-time nodes as run_quadrature takes it: one on a fixed platform, else the configured
// number or enough for the platform's drift |ΔΩ| T M/4 over the run.
int slow_node_count(const RunTables& t, const QuadratureOptions& quadrature, double dOmega) {
  const double drift = t.counter ? std::abs(dOmega) * t.duration * (t.M / 4) : 0.0;
  const int Q = t.counter ? (quadrature.slow_nodes > 0 ? quadrature.slow_nodes
                                                       : slow_nodes_for(drift, quadrature.slow_tolerance))
                          : 1;
  if (Q > detail::kMaxSlowNodes)
    throw std::invalid_argument("RunMeanKernel: at most 16 slow-time nodes (monomial Lagrange basis)");
  return Q;
}

// The quadrature weights (quadrature.hpp): κ/2 = m(Ω + Δω)T/2, its cosine and sine turned from the nominal
// mΩT/2 by mΔωT/2.
void quadrature_weights(const RunTables& t, double domega, double theta1_rate, int Q,
                        const Eigen::MatrixXd& a, Scratch& scratch) {
  const double omega_T = theta1_rate * t.duration;
  for (int m = 0; m <= t.M / 2; ++m) {
    double c, s;
    turn(t.cos_half[std::size_t(m)], t.sin_half[std::size_t(m)], double(m) * domega * t.duration / 2.0, c, s);
    detail::harmonic_slow_moments<double>(omega_T * double(m) / 2.0, c, s, a,
                                          &scratch.nu_re[std::size_t(m * Q)],
                                          &scratch.nu_im[std::size_t(m * Q)]);
  }
  // w_jq = (ν_0q + Σ_m c_m (cos(mθ_j) Re ν_mq + sin(mθ_j) Im ν_mq)) / M, summed over m in dft_weights' order.
  const int M = t.M;
  for (int q = 0; q < Q; ++q) {
    double* w = &scratch.weights[std::size_t(q * M)];
    for (int j = 0; j < M; ++j) w[j] = scratch.nu_re[std::size_t(q)];
    for (int m = 1; m <= M / 2; ++m) {
      const double re = scratch.nu_re[std::size_t(m * Q + q)], im = scratch.nu_im[std::size_t(m * Q + q)];
      const double* c = &t.dft_cos[std::size_t((m - 1) * M)];
      const double* s = &t.dft_sin[std::size_t((m - 1) * M)];
      for (int j = 0; j < M; ++j) w[j] += c[j] * re + s[j] * im;
    }
    for (int j = 0; j < M; ++j) w[j] /= double(M);
  }
}

// The main-axis half at each fast node, carried into frame-3t coordinates; B's arm stretch c·θ̇1² added.
void main_axis_half(const RunTables& t, const TrialTerms& trial, double arm_stretch_error, double theta1_rate,
                    Scratch& scratch) {
  const ChainBlocks<double>& blocks = trial.blocks;
  MainAxisInputs main{trial.main_coefficients,
                      trial.order,
                      trial.main_ripple,
                      t.cos_theta.data(),
                      t.sin_theta.data(),
                      t.M,
                      theta1_rate,
                      trial.g,
                      to_v3(blocks.pB),
                      to_v3(blocks.coriolis_1t),
                      to_v3(blocks.gravity_1t),
                      to_v3(blocks.earth_1t),
                      blocks.RB};
  main.pB.x += arm_stretch_error * theta1_rate * theta1_rate;
  main_axis_nodes(main, trial.main_small, scratch.main);
}

// The main-axis half's M nodes repeated for slow nodes 1 … Q − 1 (node n = q·M + j reads fast node j).
void repeat_main_axis_half(int M, int Q, Scratch& scratch) {
  MainAxisNodes& m = scratch.main;
  for (std::vector<double>* v : {&m.F0.x, &m.F0.y, &m.F0.z, &m.W.x, &m.W.y, &m.W.z, &m.dW.x, &m.dW.y, &m.dW.z,
                                 &m.coriolis.x, &m.coriolis.y, &m.coriolis.z, &m.W_total.x, &m.W_total.y,
                                 &m.W_total.z, &m.ripple_angle, &m.ripple_rate, &m.ripple_acc})
    for (int q = 1; q < Q; ++q) std::copy_n(v->begin(), M, v->begin() + q * M);
}

// The platform half at every node n = q·M + j, slow-major like the weights; slow node q drifts by −ΔΩ t_q,
// t_q = (1 + x_q) T/2. A fixed platform does not turn: no ripple of its own, nothing to follow
// (kinematics.hpp, run_motion).
void platform_half(const RunTables& t, const TrialTerms& trial, double dOmega, double gamma_rate,
                   const std::vector<double>& x_nodes, int Q, Scratch& scratch) {
  const int nodes = Q * t.M;
  for (int q = 0; q < Q; ++q) {
    const double slow_offset =
        t.counter ? -dOmega * (0.5 * (1.0 + x_nodes[std::size_t(q)]) * t.duration) : 0.0;
    double c, s;
    cos_sin(slow_offset, c, s);
    std::fill_n(scratch.cos_offset.begin() + q * t.M, t.M, c);
    std::fill_n(scratch.sin_offset.begin() + q * t.M, t.M, s);
  }
  std::fill(scratch.cos_offset.begin() + nodes, scratch.cos_offset.begin() + padded(nodes), 1.0);
  std::fill(scratch.sin_offset.begin() + nodes, scratch.sin_offset.begin() + padded(nodes), 0.0);
  const PlatformInputs platform{trial.platform_coefficients,
                                trial.order,
                                t.counter ? trial.platform_ripple : nullptr,
                                t.counter && trial.phase_locked && trial.main_ripple != nullptr,
                                t.cos_gamma.data(),
                                t.sin_gamma.data(),
                                scratch.cos_offset.data(),
                                scratch.sin_offset.data(),
                                nodes,
                                gamma_rate,
                                1.0 / trial.g,
                                to_v3(trial.blocks.pC),
                                trial.blocks.RC * t.mount};
  platform_nodes(platform, trial.platform_small, scratch.main, scratch.inputs);
}

// ⟨output⟩ = Σ_q Σ_j w_qj y(a_i, a_p, a_o, ω_IA at node qj), the padding skipped.
double weighted_output(const OutputPolynomial& output, const Scratch& scratch, int M, int Q) {
  double mean = 0;
  for (std::size_t n = 0; n < std::size_t(Q * M); ++n)
    mean += scratch.weights[n] * output(scratch.inputs.a_i[n], scratch.inputs.a_p[n], scratch.inputs.a_o[n],
                                        scratch.inputs.w_ia[n]);
  return mean;
}

// One run's mean output for the trial's errors: the drives' rates θ̇1 = Ω + Δω and γ̇ = −(θ̇1 + ΔΩ)
// (counter-rotating) or 0, the weights, the two halves of the chain at the nodes, the weighted sum.
double run_mean(const KernelTables& d, const RunTables& t, const TrialTerms& trial,
                const Eigen::Map<const Eigen::VectorXd>& e, Scratch& scratch) {
  const double theta1_rate = t.rate + e[ch::domega];
  const double gamma_rate = t.counter ? -(theta1_rate + e[ch::dOmega]) : 0.0;
  const int Q = slow_node_count(t, d.quadrature, e[ch::dOmega]);
  scratch.reserve(t.M, Q);
  quadrature_weights(t, e[ch::domega], theta1_rate, Q, d.lagrange[std::size_t(Q)], scratch);
  main_axis_half(t, trial, e[ch::arm_stretch], theta1_rate, scratch);
  repeat_main_axis_half(t.M, Q, scratch);
  platform_half(t, trial, e[ch::dOmega], gamma_rate, d.slow_nodes[std::size_t(Q)], Q, scratch);
  return weighted_output(d.output, scratch, t.M, Q);
}

}  // namespace

struct RunMeanKernel::Workspace::Buffers : run_nodes::Scratch {};

RunMeanKernel::Workspace::Workspace() : buffers_(std::make_unique<Buffers>()) {}
RunMeanKernel::Workspace::~Workspace() = default;
RunMeanKernel::Workspace::Workspace(const Workspace&) : Workspace() {}
RunMeanKernel::Workspace& RunMeanKernel::Workspace::operator=(const Workspace&) { return *this; }
RunMeanKernel::Workspace::Workspace(Workspace&&) noexcept = default;
RunMeanKernel::Workspace& RunMeanKernel::Workspace::operator=(Workspace&&) noexcept = default;

void RunMeanKernel::means(std::span<const double> errors, std::span<double> out, Workspace& workspace) const {
  const Data& d = *data_;
  if (errors.size() != std::size_t(d.layout.size()) || out.size() != d.runs.size())
    throw std::invalid_argument(
        fmt::format("RunMeanKernel::means: {} errors for a layout of {}, {} outputs for {} runs",
                    errors.size(), d.layout.size(), out.size(), d.runs.size()));
  if (!workspace.buffers_) workspace.buffers_ = std::make_unique<Workspace::Buffers>();  // moved from
  Scratch& scratch = *workspace.buffers_;
  const Eigen::Map<const Eigen::VectorXd> e(errors.data(), Eigen::Index(errors.size()));
  const TrialTerms trial = trial_terms(d, e);
  for (std::size_t r = 0; r < d.runs.size(); ++r) out[r] = run_mean(d, d.runs[r], trial, e, scratch);
}

void RunMeanKernel::means(std::span<const double> errors, std::span<double> out) const {
  Workspace workspace;
  means(errors, out, workspace);
}

}  // namespace ccal
