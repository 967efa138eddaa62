#include "ccal/reduction/run_means.hpp"

#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstring>
#include <array>
#include <cmath>
#include <stdexcept>

#include "ccal/core/frames.hpp"
#include "ccal/model/kinematics.hpp"
#include "ccal/reduction/quadrature.hpp"
#include "run_means_nodes.hpp"
#include "run_means_tables.hpp"

namespace ccal {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using run_nodes::harmonic_moments_lanes;
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

OutputPolynomial::OutputPolynomial(const InstrumentModel& model) : rate(model.rate_gain) {
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

}  // namespace run_nodes


namespace {

using run_nodes::KernelTables;
using run_nodes::OutputPolynomial;
using run_nodes::RunGroup;
using run_nodes::RunTables;
using run_nodes::Scratch;

// The runs in groups of the same nodes (RunGroup), in order of first appearance, and each group's tables of
// its nodes' angles; padding lanes hold the harmless angle 0 and are never summed.
void group_runs(KernelTables& d) {
  for (std::size_t r = 0; r < d.runs.size(); ++r) {
    const RunTables& t = d.runs[r];
    auto group = std::find_if(d.groups.begin(), d.groups.end(), [&](const RunGroup& g) {
      const RunTables& u = d.runs[g.runs.front()];
      return u.M == t.M && u.counter == t.counter && u.duration == t.duration && u.mount == t.mount;
    });
    if (group == d.groups.end()) group = d.groups.insert(d.groups.end(), RunGroup{{}, t.M, {}, {}, {}, {}, false});
    group->runs.push_back(r);
  }
  for (RunGroup& g : d.groups) {
    for (const std::size_t r : g.runs) {
      const RunTables& t = d.runs[r];
      g.cos_theta.insert(g.cos_theta.end(), t.cos_theta.begin(), t.cos_theta.end());
      g.sin_theta.insert(g.sin_theta.end(), t.sin_theta.begin(), t.sin_theta.end());
    }
    for (int q = 0; q < detail::kMaxSlowNodes; ++q)
      for (const std::size_t r : g.runs) {
        const RunTables& t = d.runs[r];
        g.cos_gamma.insert(g.cos_gamma.end(), t.cos_gamma.begin(), t.cos_gamma.end());
        g.sin_gamma.insert(g.sin_gamma.end(), t.sin_gamma.begin(), t.sin_gamma.end());
      }
    const RunTables& first = d.runs[g.runs.front()];
    const auto same_bits = [](const std::vector<double>& a, const std::vector<double>& b) {
      return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
    };
    g.shared_angles = std::all_of(g.runs.begin(), g.runs.end(), [&](std::size_t r) {
      return same_bits(d.runs[r].cos_theta, first.cos_theta) && same_bits(d.runs[r].sin_theta, first.sin_theta);
    });
    for (auto [c, s] : {std::pair{&g.cos_theta, &g.sin_theta}, std::pair{&g.cos_gamma, &g.sin_gamma}}) {
      const auto n = std::size_t(padded(int(c->size())));
      c->resize(n, 1.0);
      s->resize(n, 0.0);
    }
  }
}

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
        // + 0.0: no −0 in the tables the batch path splats (run_means_batch.cpp, splat).
        t.dft_cos.push_back(c_m * t.table.cos_k[std::size_t(m * j % t.M)] + 0.0);
        t.dft_sin.push_back(c_m * t.table.sin_k[std::size_t(m * j % t.M)] + 0.0);
      }
    const double phi0 = initial_phase(run, geometry, site);
    for (int j = 0; j < t.M; ++j) {
      const double theta = t.table.phase(j);
      // The same sums run_quadrature forms for the joint angles.
      const double theta1 = run.arm_azimuth + theta;
      const double gamma = phi0 - (t.counter ? theta : 0.0);
      t.cos_theta.push_back(std::cos(theta1) + 0.0);  // (+ 0.0: as dft_cos)
      t.sin_theta.push_back(std::sin(theta1) + 0.0);
      t.cos_gamma.push_back(std::cos(gamma) + 0.0);
      t.sin_gamma.push_back(std::sin(gamma) + 0.0);
    }
    for (int m = 0; m <= t.M / 2; ++m) {
      const double half_kappa = t.rate * t.duration * double(m) / 2.0;
      t.cos_half.push_back(std::cos(half_kappa));
      t.sin_half.push_back(std::sin(half_kappa));
    }
    t.mount = mounting_matrix(run.mounting);
    data->runs.push_back(std::move(t));
  }
  group_runs(*data);
  data->slow_nodes.resize(detail::kMaxSlowNodes + 1);
  data->lagrange.resize(detail::kMaxSlowNodes + 1);
  data->zero_re.resize(1);  // Q = 0: none
  data->zero_im.resize(1);
  for (int Q = 1; Q <= detail::kMaxSlowNodes; ++Q) {
    data->slow_nodes[std::size_t(Q)] = detail::slow_time_nodes(Q);
    data->lagrange[std::size_t(Q)] = detail::slow_lagrange_monomials(Q);
    std::vector<double>& re = data->zero_re.emplace_back(std::size_t(Q));
    std::vector<double>& im = data->zero_im.emplace_back(std::size_t(Q));
    detail::harmonic_slow_moments<double>(0.0, 1.0, 0.0, data->lagrange[std::size_t(Q)], re.data(),
                                          im.data());
  }
  data_ = std::move(data);
}

RunMeanKernel::~RunMeanKernel() = default;
RunMeanKernel::RunMeanKernel(RunMeanKernel&&) noexcept = default;
RunMeanKernel& RunMeanKernel::operator=(RunMeanKernel&&) noexcept = default;

namespace {

using run_nodes::slow_node_count;
using run_nodes::TrialTerms;
using run_nodes::turn;

// A group's nodes as the loops number them: the main-axis half at n < G·M, the platform half at
// n = q·G·M + g·M + j < Q·G·M.
struct GroupNodes {
  int M, G, Q;
  int fast() const { return G * M; }
  int all() const { return Q * G * M; }
};

// ν_mq of every harmonic m = 0 … M/2 of every run g of the group (spectral_weights.hpp's
// harmonic_slow_moments) at nu[(g·(M/2 + 1) + m)·Q + q]: κ/2 = m(Ω + Δω)T/2, its cosine and sine turned from
// the nominal mΩT/2 by mΔωT/2. The harmonics m ≥ 1 of all the runs go through harmonic_moments_lanes, the
// same operations eight at a time, when each of them takes J_p's recursion (|κ/2| ≥ 4 + Q: always but for
// runs of a few revolutions); m = 0, κ = 0, takes the series.
void slow_moments(const KernelTables& d, const RunGroup& group, const GroupNodes& nodes, double domega,
                  Scratch& scratch) {
  const int H = nodes.M / 2 + 1, Q = nodes.Q;
  const Eigen::MatrixXd& a = d.lagrange[std::size_t(Q)];
  int count = 0;
  bool recursion = true, small_turns = true;
  for (int g = 0; g < nodes.G; ++g) {
    const RunTables& t = d.runs[group.runs[std::size_t(g)]];
    const double omega_T = (t.rate + domega) * t.duration;
    const auto at = std::size_t(g * H * Q);  // m = 0: κ = 0, the same for every trial
    run_nodes::zero_harmonic_moments(d, Q, omega_T, &scratch.nu_re[at], &scratch.nu_im[at]);
    for (int m = 1; m < H; ++m, ++count) {
      const double turn_angle = double(m) * domega * t.duration / 2.0;
      const double half_kappa = omega_T * double(m) / 2.0;
      scratch.lane_kappa[std::size_t(count)] = half_kappa;
      scratch.lane_cos[std::size_t(count)] = t.cos_half[std::size_t(m)];
      scratch.lane_sin[std::size_t(count)] = t.sin_half[std::size_t(m)];
      scratch.lane_turn[std::size_t(count)] = turn_angle;
      small_turns = small_turns && std::abs(turn_angle) < kSmallAngle;
      recursion = recursion && !(std::abs(half_kappa) < 4.0 + Q);
    }
  }
  const int lanes = padded(count);
  for (int i = count; i < lanes; ++i)  // padding: any κ ≠ 0, never read
    scratch.lane_kappa[std::size_t(i)] = 1.0, scratch.lane_cos[std::size_t(i)] = 1.0,
    scratch.lane_sin[std::size_t(i)] = 0.0, scratch.lane_turn[std::size_t(i)] = 0.0;
  // cos, sin of mΩT/2 turned by mΔωT/2 (turn): the small turns in lanes, with cos_sin's operations.
  if (small_turns)
    run_nodes::small_turns_lanes(scratch.lane_turn.data(), scratch.lane_cos.data(), scratch.lane_sin.data(),
                                 lanes);
  else
    for (int i = 0; i < count; ++i)
      turn(scratch.lane_cos[std::size_t(i)], scratch.lane_sin[std::size_t(i)],
           scratch.lane_turn[std::size_t(i)], scratch.lane_cos[std::size_t(i)],
           scratch.lane_sin[std::size_t(i)]);
  if (recursion)
    harmonic_moments_lanes(scratch.lane_kappa.data(), scratch.lane_cos.data(), scratch.lane_sin.data(), lanes,
                           a, scratch.lane_re.data(), scratch.lane_im.data());
  int i = 0;
  for (int g = 0; g < nodes.G; ++g)
    for (int m = 1; m < H; ++m, ++i) {
      const auto at = std::size_t((g * H + m) * Q);
      if (!recursion) {
        detail::harmonic_slow_moments<double>(
            scratch.lane_kappa[std::size_t(i)], scratch.lane_cos[std::size_t(i)],
            scratch.lane_sin[std::size_t(i)], a, &scratch.nu_re[at], &scratch.nu_im[at]);
        continue;
      }
      for (int q = 0; q < Q; ++q) {
        scratch.nu_re[at + std::size_t(q)] = scratch.lane_re[std::size_t(q * lanes + i)];
        scratch.nu_im[at + std::size_t(q)] = scratch.lane_im[std::size_t(q * lanes + i)];
      }
    }
}

// Each run's rates at its nodes and weights: θ̇1 = Ω + Δω with B's arm stretch c·θ̇1² for the main-axis half,
// γ̇ = −(θ̇1 + ΔΩ) (counter-rotating) or 0 for the platform half.
void run_rates_and_weights(const KernelTables& d, const RunGroup& group, const GroupNodes& nodes,
                           const TrialTerms& trial, const Eigen::Map<const Eigen::VectorXd>& e,
                           Scratch& scratch) {
  const int M = nodes.M;
  for (int g = 0; g < nodes.G; ++g) {
    const RunTables& t = d.runs[group.runs[std::size_t(g)]];
    const double theta1_rate = t.rate + e[ch::domega];
    const double gamma_rate = t.counter ? -(theta1_rate + e[ch::dOmega]) : 0.0;
    const auto nu = std::size_t(g * (M / 2 + 1) * nodes.Q);
    // The quadrature weights (quadrature.hpp) from the run's ν (slow_moments), slow node q's at + q·fast().
    run_nodes::quadrature_weights_lanes(t.dft_cos.data(), t.dft_sin.data(), t.M, nodes.Q, &scratch.nu_re[nu],
                                        &scratch.nu_im[nu], scratch.weights.data() + g * M, nodes.fast());
    double arm_x = trial.blocks.pB[0];
    arm_x += e[ch::arm_stretch] * theta1_rate * theta1_rate;
    std::fill_n(scratch.main_rate.begin() + g * M, M, theta1_rate);
    std::fill_n(scratch.arm_x.begin() + g * M, M, arm_x);
    for (int q = 0; q < nodes.Q; ++q)
      std::fill_n(scratch.platform_rate.begin() + q * nodes.fast() + g * M, M, gamma_rate);
  }
}

// The main-axis half at each fast node of the group's runs, carried into frame-3t coordinates.
void main_axis_half(const RunGroup& group, const GroupNodes& nodes, const TrialTerms& trial,
                    Scratch& scratch) {
  const ChainBlocks<double>& blocks = trial.blocks;
  const MainAxisInputs main{trial.main_coefficients,
                            trial.order,
                            trial.main_ripple,
                            group.cos_theta.data(),
                            group.sin_theta.data(),
                            scratch.main_rate.data(),
                            scratch.arm_x.data(),
                            nodes.fast(),
                            trial.g,
                            to_v3(blocks.pB),
                            to_v3(blocks.coriolis_1t),
                            to_v3(blocks.gravity_1t),
                            to_v3(blocks.earth_1t),
                            blocks.RB};
  main_axis_nodes(main, trial.main_series, scratch.main);
}

// The main-axis half's G·M nodes repeated for slow nodes 1 … Q − 1 (node n reads fast node n mod G·M).
void repeat_main_axis_half(const GroupNodes& nodes, Scratch& scratch) {
  MainAxisNodes& m = scratch.main;
  const int n = nodes.fast();
  for (std::vector<double>* v : {&m.F0.x, &m.F0.y, &m.F0.z, &m.W.x, &m.W.y, &m.W.z, &m.dW.x, &m.dW.y, &m.dW.z,
                                 &m.coriolis.x, &m.coriolis.y, &m.coriolis.z, &m.W_total.x, &m.W_total.y,
                                 &m.W_total.z, &m.ripple_angle, &m.ripple_rate, &m.ripple_acc})
    for (int q = 1; q < nodes.Q; ++q) std::copy_n(v->begin(), n, v->begin() + q * n);
}

// The platform half at every node; slow node q drifts by −ΔΩ t_q, t_q = (1 + x_q) T/2, alike for the runs of
// a group. A fixed platform does not turn: no ripple of its own, nothing to follow (kinematics.hpp,
// run_motion).
void platform_half(const RunTables& t, const RunGroup& group, const GroupNodes& nodes,
                   const TrialTerms& trial, double dOmega, const std::vector<double>& x_nodes,
                   Scratch& scratch) {
  for (int q = 0; q < nodes.Q; ++q) {
    const double slow_offset =
        t.counter ? -dOmega * (0.5 * (1.0 + x_nodes[std::size_t(q)]) * t.duration) : 0.0;
    double c, s;
    cos_sin(slow_offset, c, s);
    std::fill_n(scratch.cos_offset.begin() + q * nodes.fast(), nodes.fast(), c);
    std::fill_n(scratch.sin_offset.begin() + q * nodes.fast(), nodes.fast(), s);
  }
  const int all = nodes.all();
  std::fill(scratch.cos_offset.begin() + all, scratch.cos_offset.begin() + padded(all), 1.0);
  std::fill(scratch.sin_offset.begin() + all, scratch.sin_offset.begin() + padded(all), 0.0);
  const PlatformInputs platform{trial.platform_coefficients,
                                trial.order,
                                t.counter ? trial.platform_ripple : nullptr,
                                t.counter && trial.phase_locked && trial.main_ripple != nullptr,
                                group.cos_gamma.data(),
                                group.sin_gamma.data(),
                                scratch.cos_offset.data(),
                                scratch.sin_offset.data(),
                                scratch.platform_rate.data(),
                                all,
                                1.0 / trial.unit,
                                to_v3(trial.blocks.pC),
                                trial.blocks.RC * t.mount};
  platform_nodes(platform, trial.platform_series, scratch.main, scratch.inputs);
}

// ⟨output⟩ of run g = Σ_q Σ_j w_qj y(a_i, a_p, a_o, ω_IA at its node qj), the padding skipped: the products
// w_qj y at every node (run_nodes::weighted_outputs_lanes), summed node by node in this order.
double weighted_output(const Scratch& scratch, const GroupNodes& nodes, int g) {
  double mean = 0;
  for (int q = 0; q < nodes.Q; ++q)
    for (int j = 0; j < nodes.M; ++j)
      mean += scratch.products[std::size_t(q * nodes.fast() + g * nodes.M + j)];
  return mean;
}

// The mean output of each run of a group for the trial's errors: the rates and weights, the two halves of
// the chain at all the group's nodes, the weighted sums.
void group_means(const KernelTables& d, const RunGroup& group, const TrialTerms& trial,
                 const Eigen::Map<const Eigen::VectorXd>& e, Scratch& scratch, std::span<double> out) {
  const RunTables& t = d.runs[group.runs.front()];  // the group's nodes are each run's
  const GroupNodes nodes{group.M, int(group.runs.size()), slow_node_count(t, d.quadrature, e[ch::dOmega])};
  scratch.reserve(nodes.M, nodes.G, nodes.Q);
  slow_moments(d, group, nodes, e[ch::domega], scratch);
  run_rates_and_weights(d, group, nodes, trial, e, scratch);
  main_axis_half(group, nodes, trial, scratch);
  repeat_main_axis_half(nodes, scratch);
  platform_half(t, group, nodes, trial, e[ch::dOmega], d.slow_nodes[std::size_t(nodes.Q)], scratch);
  run_nodes::weighted_outputs_lanes(d.output, scratch.weights.data(), scratch.inputs, padded(nodes.all()),
                                    scratch.products.data());
  for (int g = 0; g < nodes.G; ++g) out[group.runs[std::size_t(g)]] = weighted_output(scratch, nodes, g);
}

}  // namespace

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
  const TrialTerms trial = run_nodes::trial_terms(d, e);
  for (const RunGroup& group : d.groups) group_means(d, group, trial, e, scratch, out);
}

void RunMeanKernel::means(std::span<const double> errors, std::span<double> out) const {
  Workspace workspace;
  means(errors, out, workspace);
}

}  // namespace ccal
