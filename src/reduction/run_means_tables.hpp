#pragma once
// The run-mean kernel's tables (run_means.hpp) and what a trial's errors give every run alike, shared by its
// one-trial path (run_means.cpp) and its path of a batch of trials in SIMD lanes (run_means_batch.cpp).
// Internal to the library.
#include <fmt/format.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "ccal/model/error_sources.hpp"
#include "ccal/model/kinematics.hpp"
#include "ccal/reduction/detail/spectral_weights.hpp"
#include "ccal/reduction/quadrature.hpp"
#include "ccal/reduction/run_means.hpp"
#include "run_means_lanes.hpp"
#include "run_means_nodes.hpp"

namespace ccal::run_nodes {

// The tables of one run: everything of the run that does not depend on the errors.
struct RunTables {
  double rate = 0;  // nominal Ω [rad/s]
  double duration = 0;
  bool counter = false;
  int M = 0;
  detail::FastPhaseTable table{2};
  std::vector<double> cos_theta, sin_theta;  // θ1(0) + θ_j
  std::vector<double> cos_gamma, sin_gamma;  // φ0 − θ_j (counter-rotating) or φ0
  std::vector<double> cos_half, sin_half;    // mΩT/2, m = 0..M/2
  // The DFT of the weights (spectral_weights.hpp's dft_weights) as c_m cos(mθ_j), c_m sin(mθ_j) at
  // [(m − 1)M + j], m = 1..M/2, with c_m = 2 (1 at the Nyquist term): contiguous in j, so that the sums of
  // all nodes run side by side. Scaling by 2 is exact, so each weight is the same double as dft_weights'.
  std::vector<double> dft_cos, dft_sin;
  Eigen::Matrix3d mount;
};

// Runs that share their fast and slow nodes (the same M, platform mode, duration and mounting, so that a
// trial gives them the same number of slow nodes and the same drift at each): their nodes side by side in
// the same SIMD loops, numbered as run_means_nodes.hpp says (run g of G at g·M + j).
struct RunGroup {
  std::vector<std::size_t> runs;  // indices into KernelTables::runs, in the plan's order
  int M = 0;
  std::vector<double> cos_theta, sin_theta;  // node g·M + j, padded
  std::vector<double> cos_gamma, sin_gamma;  // node q·G·M + g·M + j for every q < kMaxSlowNodes, padded
  bool shared_angles = false;  // every run's θ1 at node j is the first run's (cos_theta, sin_theta bit for bit)
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
  std::vector<RunGroup> groups;
  // Slow-time nodes and their Lagrange monomials for Q = 1..kMaxSlowNodes.
  std::vector<std::vector<double>> slow_nodes;
  std::vector<Eigen::MatrixXd> lagrange;
  // ν_0q of the harmonic m = 0 for Q = 1..kMaxSlowNodes (at [Q][q]): κ/2 = 0·(Ω + Δω)T/2 = +0 and its cosine
  // and sine, 1 and 0 turned by 0·ΔωT/2, exactly 1 and +0 for every trial, so the same for all (a negative ΩT
  // would give κ/2 = −0: slow_moments_of_zero_harmonic computes that case).
  std::vector<std::vector<double>> zero_re, zero_im;

  KernelTables(const Geometry& g, const ErrorLayout& l, const Site& s, const InstrumentModel& instrument,
               const QuadratureOptions& q)
      : geometry(g), layout(l), site(s), output(instrument), quadrature(q) {}
};

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
  double g;     // gravity [m/s²]
  double unit;  // the g of the g-levels [m/s²]
  bool phase_locked;
  AngleSeries main_series, platform_series;
};

// The drive's rate ripple of `channel` (c1, s1, … after the channel's unused c0), nullptr when zero.
inline const double* nonzero_ripple(const double* errors, const ErrorLayout& layout, int channel, int order) {
  const double* c = errors + layout.harmonic_index(channel, 0, false) + 1;
  for (int i = 0; i < 2 * order; ++i)
    if (c[i] != 0.0) return c;
  return nullptr;
}

// A half stays in the small-angle loops where its two wobble channels (the 4th and 5th of its dynamic
// channels) and the angle its ripple adds (a phase-locked platform also turns by the main axis's) stay below
// kSmallAngle; the two halves take the series to q³ where both stay below kTinyAngle (one series for both, so
// that a batch's lanes take one).
inline TrialTerms trial_terms(const KernelTables& d, const Eigen::Map<const Eigen::VectorXd>& e) {
  const double* errors = e.data();
  const int order = d.layout.harmonic_order();
  TrialTerms trial{chain_blocks<double>(d.geometry, d.layout, e, d.site, 0.0, d.geometry.beta),
                   errors + d.layout.harmonic_index(ch::dx1, 0, false),
                   errors + d.layout.harmonic_index(ch::dx3, 0, false),
                   nonzero_ripple(errors, d.layout, ch::ripple1, order),
                   nonzero_ripple(errors, d.layout, ch::ripple3, order),
                   order,
                   d.site.g,
                   d.site.g_unit(),
                   d.geometry.platform_control == PlatformControl::phase_locked,
                   AngleSeries::library,
                   AngleSeries::library};
  // The largest angle each half turns by at a node: its two wobbles, its ripple (and a phase-locked platform
  // the main axis's too).
  const auto wobbles = [&](const double* coefficients) {
    return std::max(channel_bound(coefficients + 3 * (2 * order + 1), order),
                    channel_bound(coefficients + 4 * (2 * order + 1), order));
  };
  const double main_ripple_bound = ripple_angle_bound(trial.main_ripple, order);
  const double main_bound = std::max(wobbles(trial.main_coefficients), main_ripple_bound);
  const double platform_bound =
      std::max(wobbles(trial.platform_coefficients), ripple_angle_bound(trial.platform_ripple, order) +
                                                         (trial.phase_locked ? main_ripple_bound : 0.0));
  const auto series = [](double bound) {
    return bound < kTinyAngle    ? AngleSeries::tiny
           : bound < kSmallAngle ? AngleSeries::small
                                 : AngleSeries::library;
  };
  trial.main_series = series(main_bound);
  trial.platform_series = series(platform_bound);
  if (trial.main_series != AngleSeries::library && trial.platform_series != AngleSeries::library &&
      trial.main_series != trial.platform_series)
    trial.main_series = trial.platform_series = AngleSeries::small;
  return trial;
}

// The number of slow-time nodes as run_quadrature takes it: one on a fixed platform, else the configured
// number or enough for the platform's drift |ΔΩ| T M/4 over the run.
inline int slow_node_count(const RunTables& t, const QuadratureOptions& quadrature, double dOmega) {
  const double drift = t.counter ? std::abs(dOmega) * t.duration * (t.M / 4) : 0.0;
  const int Q = t.counter ? (quadrature.slow_nodes > 0 ? quadrature.slow_nodes
                                                       : slow_nodes_for(drift, quadrature.slow_tolerance))
                          : 1;
  if (Q > detail::kMaxSlowNodes)
    throw std::invalid_argument("RunMeanKernel: at most 16 slow-time nodes (monomial Lagrange basis)");
  return Q;
}

// cos and sin of (a + δ) from those of a and a small (or not) δ.
// ν_0q (q < Q) of a run whose ΩT is omega_T into re, im: zero_re, zero_im, or computed for a negative ΩT
// exactly as for any other harmonic.
inline void zero_harmonic_moments(const KernelTables& d, int Q, double omega_T, double* re, double* im) {
  const double half_kappa = omega_T * 0.0 / 2.0;
  if (std::signbit(half_kappa)) {
    detail::harmonic_slow_moments<double>(half_kappa, 1.0, 0.0, d.lagrange[std::size_t(Q)], re, im);
    return;
  }
  const auto q_count = std::size_t(Q);
  std::copy_n(d.zero_re[q_count].begin(), Q, re);
  std::copy_n(d.zero_im[q_count].begin(), Q, im);
}

inline void turn(double c, double s, double delta, double& c_out, double& s_out) {
  double cd, sd;
  cos_sin(delta, cd, sd);
  c_out = c * cd - s * sd;
  s_out = s * cd + c * sd;
}

// Scratch space of one thread, grown when a larger rule is met and then reused (RunMeanKernel::Workspace).
// A group's nodes n = q·G·M + g·M + j follow each other without padding, so that the loops fill whole SIMD
// vectors across runs and slow nodes; the main-axis half is repeated for every slow node.
struct Scratch {
  std::vector<double> nu_re, nu_im, weights, products;  // products: w y at each node
  // The harmonics m ≥ 1 of the group's runs side by side for harmonic_moments_lanes: κ/2, cos, sin, and ν.
  std::vector<double> lane_kappa, lane_cos, lane_sin, lane_turn, lane_re, lane_im;
  std::vector<double> main_rate, arm_x, platform_rate;  // θ̇1, B's offset x and γ̇ of the node's run
  std::vector<double> cos_offset, sin_offset;           // slow node q's drift at node n
  MainAxisNodes main;
  InstrumentInputs inputs;
  std::size_t nodes = 0;
  void reserve(int M, int G, int Q) {
    // The main-axis loop writes padded(G·M) nodes before they are repeated.
    const auto n = std::size_t(std::max(padded(Q * G * M), padded(G * M)));
    const auto harmonics = std::size_t(G * (M / 2 + 1) * Q), lanes = std::size_t(padded(G * (M / 2)));
    if (nodes < n) {
      for (auto* v : {&weights, &products, &main_rate, &arm_x, &platform_rate, &cos_offset, &sin_offset})
        v->resize(n);
      inputs.resize(n);
      main.resize(n);
      nodes = n;
    }
    if (nu_re.size() < harmonics) {
      nu_re.resize(harmonics);
      nu_im.resize(harmonics);
    }
    // Each grown on its own: a later group may have more lanes but fewer slow nodes (lanes·Q no larger).
    if (lane_kappa.size() < lanes)
      for (auto* v : {&lane_kappa, &lane_cos, &lane_sin, &lane_turn}) v->resize(lanes);
    if (lane_re.size() < lanes * std::size_t(Q)) {
      lane_re.resize(lanes * std::size_t(Q));
      lane_im.resize(lanes * std::size_t(Q));
    }
  }
};

// The scratch space of a batch of trials (run_means_batch.cpp): one pack of kPackLanes trials at a time, each
// value a pack of doubles (lane l: the pack's trial l).
struct BatchScratch {
  std::vector<TrialTerms> terms;  // per trial of the batch
  std::vector<int> key;           // per trial: its rule (slow nodes per group, ripples), −1: alone
  std::vector<char> done;         // per trial: its means computed
  std::vector<std::size_t> pack;  // the trials of the pack at hand
  std::vector<double> main_coefficients, platform_coefficients, main_ripple, platform_ripple;
  std::vector<double> frame;              // pB y, z; ω_c, ĝ, ω_ie of frame 1t; R_B; p_C; P = R_C·mounting
  std::vector<double> run_rates;          // per run of the group: θ̇1, γ̇, B's offset x
  std::vector<double> offsets;            // per slow node: cos, sin of its drift
  std::vector<double> harmonics;          // per run and harmonic m ≥ 1: κ/2, cos, sin of the nominal, turn
  std::vector<double> zero_moments;       // per run: ν_0q re, im
  std::vector<double> nu_re, nu_im;       // per run, harmonic m ≥ 1 and slow node
  std::vector<double> weights, products;  // per node
  std::vector<double> means;              // per run of the group
};

}  // namespace ccal::run_nodes

namespace ccal {
struct RunMeanKernel::Data : run_nodes::KernelTables {
  using KernelTables::KernelTables;
};
struct RunMeanKernel::Workspace::Buffers : run_nodes::Scratch {
  run_nodes::BatchScratch batch;
};
}  // namespace ccal
