#include "ccal/reduction/run_means.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
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
  // The drives' rate ripple (c1, s1, … after each channel's unused c0), nullptr when zero.
  auto ripple = [&](int channel) -> const double* {
    const double* c = errors.data() + d.layout.harmonic_index(channel, 0, false) + 1;
    for (int i = 0; i < 2 * order; ++i)
      if (c[i] != 0.0) return c;
    return nullptr;
  };
  const double* main_ripple = ripple(ripple1);
  const double* platform_ripple = ripple(ripple3);
  const double main_ripple_bound = run_nodes::ripple_angle_bound(main_ripple, order);
  const bool phase_locked = d.geometry.platform_control == PlatformControl::phase_locked;
  const bool main_small = always_small(main_coefficients + 3 * (2 * order + 1), order) &&
                          always_small(main_coefficients + 4 * (2 * order + 1), order) &&
                          main_ripple_bound < kSmallAngle;
  const bool platform_small =
      always_small(platform_coefficients + 3 * (2 * order + 1), order) &&
      always_small(platform_coefficients + 4 * (2 * order + 1), order) &&
      run_nodes::ripple_angle_bound(platform_ripple, order) + (phase_locked ? main_ripple_bound : 0.0) <
          kSmallAngle;

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
                        main_ripple,
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
    // A fixed platform does not turn: no ripple of its own, nothing to follow (kinematics.hpp, run_motion).
    PlatformInputs platform{platform_coefficients,
                            order,
                            t.counter ? platform_ripple : nullptr,
                            t.counter && phase_locked && main_ripple != nullptr,
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
