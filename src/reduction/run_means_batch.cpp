// The run-mean kernel for a batch of trials (run_means.hpp, RunMeanKernel::means of many error vectors): the
// trials that share their rule go through the chain kPackLanes at a time, one trial per SIMD lane, each node
// of a run once for all of them. Every lane takes the operations the one-trial path (run_means.cpp,
// run_means_nodes.cpp) takes for that trial's node, in the same order, so that a trial's means have the same
// bits on either path and whatever the trials beside it; what changes is what the lanes share: the node
// tables are the same in every lane (no padding of a run's nodes to whole packs), the main-axis half of a
// fast node is used by its slow nodes straight from registers (not stored and repeated), and a trial's rates
// and drifts are held in registers rather than filled into every node.
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "../core/cloned_loops.hpp"
#include "ccal/reduction/run_means.hpp"
#include "run_means_lanes.hpp"
#include "run_means_tables.hpp"

namespace ccal {
namespace run_nodes {
namespace {

constexpr auto kBatchLanes = std::size_t(kPackLanes);

// x in every lane, as T{} + x: one broadcast. (`x − Pack{}`, which keeps a −0, GCC 12 builds in the AVX-512
// clone from eight masked broadcasts, one a lane.) The tables splat reads hold no −0 (run_means.cpp,
// tables_of), so that their values are the one-trial path's bit for bit.
[[gnu::always_inline]] inline Pack splat(double x) { return Pack{} + x; }

// The packed values of one pack of trials for one group of runs (BatchScratch), as the loops read them.
// frame: pB y, z (0, 1); ω_c, ĝ, ω_ie of frame 1t (2, 5, 8); R_B column-major (11); p_C (20); P (23).
constexpr int kFrameValues = 32;
struct BatchLanes {
  const KernelTables* d;
  const RunGroup* group;
  int M, G, Q, order;
  const double *main_coefficients, *platform_coefficients;
  const double* main_ripple;      // null: no ripple of the main drive in these trials
  const double* platform_ripple;  // null: none of the platform drive (or a fixed platform)
  bool follows_main;
  bool tiny;  // every wobble and ripple angle below kTinyAngle: their series to q³
  const double *frame, *run_rates, *offsets, *harmonics, *zero_moments;
  double *nu_re, *nu_im, *weights, *products, *means;
  double g, inverse_g;
};

template <class T>
[[gnu::always_inline]] inline V3<T> packed_v3(const double* p, int i) {
  return {value_at<T>(p, i), value_at<T>(p, i + 1), value_at<T>(p, i + 2)};
}
// T{} + x in every lane, as the one-trial path broadcasts a trial's vectors (a −0 becomes +0 there too).
[[gnu::always_inline]] inline V3<Pack> as_broadcast(const V3<Pack>& v) {
  return {Pack{} + v.x, Pack{} + v.y, Pack{} + v.z};
}

// ν_mq of each run's harmonics m ≥ 1 (harmonic_moments_lanes' and small_turns_lanes' operations per lane),
// then the quadrature weights (quadrature_weights_lanes' per lane) at node q·G·M + g·M + j.
CCAL_CLONED CCAL_FLATTEN void batch_weights_lanes(const BatchLanes& b) {
  const int half = b.M / 2, Q = b.Q;
  const Eigen::MatrixXd& a = b.d->lagrange[std::size_t(Q)];
  for (int h = 0; h < b.G * half; ++h) {
    const Pack k = value_at<Pack>(b.harmonics, 4 * h), c0 = value_at<Pack>(b.harmonics, 4 * h + 1),
               s0 = value_at<Pack>(b.harmonics, 4 * h + 2);
    Pack cd, sd;
    small_angle_cos_sin(value_at<Pack>(b.harmonics, 4 * h + 3), cd, sd);
    const Pack c = c0 * cd - s0 * sd, s = s0 * cd + c0 * sd;
    Pack mu_re[detail::kMaxSlowNodes], mu_im[detail::kMaxSlowNodes], nu_re[detail::kMaxSlowNodes],
        nu_im[detail::kMaxSlowNodes];
    detail::oscillatory_recursion(k, c, s, Q, mu_re, mu_im);
    detail::slow_moments_of(c, s, a, mu_re, mu_im, nu_re, nu_im);
    for (int q = 0; q < Q; ++q) {
      store(b.nu_re + std::size_t(h * Q + q) * kBatchLanes, nu_re[q]);
      store(b.nu_im + std::size_t(h * Q + q) * kBatchLanes, nu_im[q]);
    }
  }
  for (int g = 0; g < b.G; ++g) {
    const RunTables& t = b.d->runs[b.group->runs[std::size_t(g)]];
    for (int q = 0; q < Q; ++q)
      for (int j = 0; j < b.M; ++j) {
        Pack sum = Pack{} + value_at<Pack>(b.zero_moments, 2 * Q * g + q);
        for (int m = 1; m <= half; ++m) {
          const auto at = std::size_t((m - 1) * b.M + j);
          const int nu = (g * half + m - 1) * Q + q;
          sum = sum + (splat(t.dft_cos[at]) * value_at<Pack>(b.nu_re, nu) +
                       splat(t.dft_sin[at]) * value_at<Pack>(b.nu_im, nu));
        }
        store(b.weights + std::size_t(q * b.G * b.M + g * b.M + j) * kBatchLanes, sum / double(b.M));
      }
  }
}

// The main axis's part at fast node k that depends on its angle alone: the ripple's series at the nominal
// angle, the angle turned by it, and the link's shape there. Runs whose nodes share their angles share it.
template <int kOrder>
struct MainShape {
  RippleSeries<Pack> ripple{};
  JointShape<Pack> shape;
};
template <int kOrder, bool kRipple, bool kTiny>
[[gnu::always_inline]] inline MainShape<kOrder> main_shape(const BatchLanes& b,
                                                           const JointCoefficients<kOrder, Pack>& a, int k) {
  Pack c = splat(b.group->cos_theta[std::size_t(k)]), s = splat(b.group->sin_theta[std::size_t(k)]);
  MainShape<kOrder> m;
  if constexpr (kRipple) {
    m.ripple = ripple_series<kOrder, Pack, Pack>(b.main_ripple, b.order, c, s);
    turn_by<kTiny>(c, s, m.ripple.angle);
  }
  m.shape = joint_shape<kOrder, Pack, kTiny>(a, c, s);
  return m;
}

// The main axis's half at a fast node, in frame-3t coordinates (main_axis_loop's operations), with its
// ripple's δ1, δ̇1, δ̈1.
struct MainHalf {
  V3<Pack> F0, W, dW, coriolis, W_total;
  Pack ripple_angle{}, ripple_rate{}, ripple_acc{};
};
template <int kOrder, bool kRipple>
[[gnu::always_inline]] inline void main_half(const BatchLanes& b, const MainShape<kOrder>& m,
                                             const Columns<Pack>& B, const Pack& nominal_rate, const Pack& arm_x,
                                             MainHalf& out) {
  JointLink<Pack> main;
  if constexpr (!kRipple) {
    main = joint_motion(m.shape, nominal_rate);
  } else {
    const Pack rate_ripple = nominal_rate * m.ripple.relative, acc = (nominal_rate * nominal_rate) * m.ripple.slope;
    out.ripple_angle = m.ripple.angle;
    out.ripple_rate = rate_ripple;
    out.ripple_acc = acc;
    const Pack rate = nominal_rate + rate_ripple;
    main = joint_motion(m.shape, rate, &acc);
  }
  const V3<Pack> coriolis_1t = as_broadcast(packed_v3<Pack>(b.frame, 2)),
                 gravity_1t = as_broadcast(packed_v3<Pack>(b.frame, 5)),
                 earth_1t = as_broadcast(packed_v3<Pack>(b.frame, 8));
  const PointMotion<Pack> o3t = point_motion(
      main, V3<Pack>{arm_x, Pack{} + value_at<Pack>(b.frame, 0), Pack{} + value_at<Pack>(b.frame, 1)});
  const V3<Pack> F0 = o3t.a + 2.0 * cross(coriolis_1t, o3t.v) + b.g * gravity_1t;
  out.F0 = B.transpose_times(to_local(main, F0));
  out.W = B.transpose_times(to_local(main, main.w));
  out.dW = B.transpose_times(to_local(main, main.dw));
  out.coriolis = B.transpose_times(to_local(main, coriolis_1t));
  out.W_total = B.transpose_times(to_local(main, main.w + earth_1t));
}

// w·y at a platform node (platform_link's, platform_loop's and weighted_outputs_lanes' operations).
template <int kOrder, bool kRipple, bool kTiny>
[[gnu::always_inline]] inline Pack weighted_output_at(const BatchLanes& b,
                                                      const JointCoefficients<kOrder, Pack>& a,
                                                      const Columns<Pack>& P, const MainHalf& main, int n,
                                                      const Pack& nominal_rate, int q) {
  const Pack cos_gamma = splat(b.group->cos_gamma[std::size_t(n)]),
             sin_gamma = splat(b.group->sin_gamma[std::size_t(n)]);
  const Pack cos_offset = value_at<Pack>(b.offsets, 2 * q), sin_offset = value_at<Pack>(b.offsets, 2 * q + 1);
  Pack cg = cos_gamma * cos_offset - sin_gamma * sin_offset;
  Pack sg = sin_gamma * cos_offset + cos_gamma * sin_offset;
  JointLink<Pack> platform;
  if constexpr (!kRipple) {
    platform = joint_link<kOrder, Pack, Pack, kTiny>(a, cg, sg, nominal_rate);
  } else {
    Pack delta{}, rate = nominal_rate, acc{};
    if (b.platform_ripple) {
      const RippleSeries<Pack> r = ripple_series<kOrder, Pack, Pack>(b.platform_ripple, b.order, cg, sg);
      delta = r.angle;
      rate += nominal_rate * r.relative;
      acc = (nominal_rate * nominal_rate) * r.slope;
    }
    if (b.follows_main) {
      delta -= main.ripple_angle;
      rate -= main.ripple_rate;
      acc -= main.ripple_acc;
    }
    turn_by<kTiny>(cg, sg, delta);
    platform = joint_link<kOrder, Pack, Pack, kTiny>(a, cg, sg, rate, &acc);
  }
  const PointMotion<Pack> o5 = point_motion(platform, packed_v3<Pack>(b.frame, 20));
  const V3<Pack> Wr = cross(main.W, o5.r);
  const V3<Pack> f = main.F0 + cross(main.dW, o5.r) + cross(main.W, Wr) + 2.0 * cross(main.W, o5.v) + o5.a +
                     2.0 * cross(main.coriolis, Wr + o5.v);
  const V3<Pack> w = main.W_total + platform.w;
  const V3<Pack> f5 = to_local(platform, f), w5 = to_local(platform, w);
  const Pack y = output_at(b.d->output, b.inverse_g * dot(f5, P.c0), b.inverse_g * dot(f5, P.c1),
                           b.inverse_g * dot(f5, P.c2), dot(w5, P.c0));
  return load<Pack>(b.weights + std::size_t(n) * kBatchLanes) * y;
}

// Fast node k = g·M + j of run g: the main-axis half from its shape, then the platform half at each of its slow
// nodes, w·y stored per node.
template <int kOrder, bool kMainRipple, bool kPlatformRipple, bool kTiny>
[[gnu::always_inline]] inline void fast_node(const BatchLanes& b, const MainShape<kOrder>& shape,
                                             const JointCoefficients<kOrder, Pack>& platform_coefficients,
                                             const Columns<Pack>& B, const Columns<Pack>& P, int g, int k) {
  const Pack main_rate = value_at<Pack>(b.run_rates, 3 * g), platform_rate = value_at<Pack>(b.run_rates, 3 * g + 1),
             arm_x = value_at<Pack>(b.run_rates, 3 * g + 2);
  MainHalf main;
  main_half<kOrder, kMainRipple>(b, shape, B, main_rate, arm_x, main);
  const int fast = b.G * b.M;
  for (int q = 0; q < b.Q; ++q) {
    const int n = q * fast + k;
    store(b.products + std::size_t(n) * kBatchLanes,
          weighted_output_at<kOrder, kPlatformRipple, kTiny>(b, platform_coefficients, P, main, n, platform_rate,
                                                             q));
  }
}

// Every node of the group: the main axis's shape once per fast phase when the runs share their angles (else
// once per fast node), its half once per fast node, then the platform half at each of its slow nodes; w·y
// stored per node and summed per run in the one-trial path's order (slow node, then fast node). The shape
// shared is the one each run would compute: the same operations on the same values, so the same bits.
template <int kOrder, bool kMainRipple, bool kPlatformRipple, bool kTiny>
[[gnu::always_inline]] inline void batch_nodes(const BatchLanes& b) {
  const JointCoefficients<kOrder, Pack> main_coefficients{b.main_coefficients, b.order},
      platform_coefficients{b.platform_coefficients, b.order};
  const Columns<Pack> B(b.frame + 11 * kBatchLanes), P(b.frame + 23 * kBatchLanes);
  if (b.group->shared_angles) {
    for (int j = 0; j < b.M; ++j) {
      const MainShape<kOrder> shape = main_shape<kOrder, kMainRipple, kTiny>(b, main_coefficients, j);
      for (int g = 0; g < b.G; ++g)
        fast_node<kOrder, kMainRipple, kPlatformRipple, kTiny>(b, shape, platform_coefficients, B, P, g,
                                                               g * b.M + j);
    }
  } else {
    for (int k = 0; k < b.G * b.M; ++k) {
      const MainShape<kOrder> shape = main_shape<kOrder, kMainRipple, kTiny>(b, main_coefficients, k);
      fast_node<kOrder, kMainRipple, kPlatformRipple, kTiny>(b, shape, platform_coefficients, B, P, k / b.M, k);
    }
  }
  const int fast = b.G * b.M;
  for (int g = 0; g < b.G; ++g) {
    Pack mean{};
    for (int q = 0; q < b.Q; ++q)
      for (int j = 0; j < b.M; ++j)
        mean += load<Pack>(b.products + std::size_t(q * fast + g * b.M + j) * kBatchLanes);
    store(b.means + std::size_t(g) * kBatchLanes, mean);
  }
}

template <int kOrder, bool kTiny>
[[gnu::always_inline]] inline void batch_nodes_of_order(const BatchLanes& b) {
  const bool platform_ripple = b.platform_ripple || b.follows_main;
  if (b.main_ripple)
    return platform_ripple ? batch_nodes<kOrder, true, true, kTiny>(b)
                           : batch_nodes<kOrder, true, false, kTiny>(b);
  return platform_ripple ? batch_nodes<kOrder, false, true, kTiny>(b)
                         : batch_nodes<kOrder, false, false, kTiny>(b);
}

CCAL_CLONED CCAL_FLATTEN void batch_nodes_lanes(const BatchLanes& b) {
  if (b.order == 1) return b.tiny ? batch_nodes_of_order<1, true>(b) : batch_nodes_of_order<1, false>(b);
  return b.tiny ? batch_nodes_of_order<kRuntimeOrder, true>(b)
                : batch_nodes_of_order<kRuntimeOrder, false>(b);
}

}  // namespace
}  // namespace run_nodes

namespace {

using run_nodes::AngleSeries;
using run_nodes::BatchScratch;
using run_nodes::kBatchLanes;
using run_nodes::KernelTables;
using run_nodes::RunGroup;
using run_nodes::RunTables;
using run_nodes::TrialTerms;
using run_nodes::turn;

// A trial's rule, which the trials of one pack share: whether each drive has a ripple, and each group's
// number of slow nodes; or kRuleAlone, a trial for the one-trial path (wobbles or turns beyond the
// small-angle series, or runs too short for J_p's recursion: slow_moments' scalar series).
constexpr int kRuleAlone = -1;
constexpr std::size_t kRuleFlags = 3;
void rule_of(const KernelTables& d, const TrialTerms& trial, const double* e, int* key) {
  key[0] = kRuleAlone;
  if (trial.main_series == AngleSeries::library || trial.platform_series == AngleSeries::library) return;
  for (std::size_t k = 0; k < d.groups.size(); ++k) {
    const RunGroup& group = d.groups[k];
    const RunTables& first = d.runs[group.runs.front()];
    const int Q = run_nodes::slow_node_count(first, d.quadrature, e[ch::dOmega]);
    for (const std::size_t r : group.runs) {  // slow_moments' conditions for its lanes
      const RunTables& t = d.runs[r];
      const double omega_T = (t.rate + e[ch::domega]) * t.duration;
      for (int m = 1; m <= group.M / 2; ++m) {
        const double half_kappa = omega_T * double(m) / 2.0;
        if (std::abs(half_kappa) < 4.0 + Q) return;
      }
    }
    key[kRuleFlags + k] = Q;
  }
  key[0] = trial.main_ripple != nullptr;
  key[1] = trial.platform_ripple != nullptr;
  key[2] = trial.main_series == AngleSeries::tiny;  // the platform's too (trial_terms)
}

// value into lane `lane` of pack `i` of v.
inline void put_lane(std::vector<double>& v, std::size_t i, std::size_t lane, double value) {
  v[i * kBatchLanes + lane] = value;
}
void put_lane_v3(std::vector<double>& v, std::size_t i, std::size_t lane, const Eigen::Vector3d& x) {
  for (std::size_t c = 0; c < 3; ++c) put_lane(v, i + c, lane, x[Eigen::Index(c)]);
}
void put_lane_matrix(std::vector<double>& v, std::size_t i, std::size_t lane, const Eigen::Matrix3d& m) {
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t r = 0; r < 3; ++r) put_lane(v, i + 3 * c + r, lane, m(Eigen::Index(r), Eigen::Index(c)));
}

// Lane `lane`'s values for one group: the trial's errors e and terms, computed as the one-trial path computes
// them (run_rates_and_weights, slow_moments, platform_half, their PlatformInputs).
void fill_lane(const KernelTables& d, const RunGroup& group, int Q, const TrialTerms& trial, const double* e,
               std::size_t lane, BatchScratch& b) {
  const RunTables& first = d.runs[group.runs.front()];
  const int order = trial.order, channel = 2 * order + 1, half = group.M / 2;
  for (int i = 0; i < 5 * channel; ++i) {
    put_lane(b.main_coefficients, std::size_t(i), lane, trial.main_coefficients[i]);
    put_lane(b.platform_coefficients, std::size_t(i), lane, trial.platform_coefficients[i]);
  }
  for (int i = 0; i < 2 * order; ++i) {
    if (trial.main_ripple) put_lane(b.main_ripple, std::size_t(i), lane, trial.main_ripple[i]);
    if (trial.platform_ripple) put_lane(b.platform_ripple, std::size_t(i), lane, trial.platform_ripple[i]);
  }
  const ChainBlocks<double>& blocks = trial.blocks;
  put_lane(b.frame, 0, lane, blocks.pB[1]);
  put_lane(b.frame, 1, lane, blocks.pB[2]);
  put_lane_v3(b.frame, 2, lane, blocks.coriolis_1t);
  put_lane_v3(b.frame, 5, lane, blocks.gravity_1t);
  put_lane_v3(b.frame, 8, lane, blocks.earth_1t);
  put_lane_matrix(b.frame, 11, lane, blocks.RB);
  put_lane_v3(b.frame, 20, lane, blocks.pC);
  put_lane_matrix(b.frame, 23, lane, blocks.RC * first.mount);
  const double domega = e[ch::domega], dOmega = e[ch::dOmega];
  const std::vector<double>& x_nodes = d.slow_nodes[std::size_t(Q)];
  for (int q = 0; q < Q; ++q) {
    const double slow_offset =
        first.counter ? -dOmega * (0.5 * (1.0 + x_nodes[std::size_t(q)]) * first.duration) : 0.0;
    double c, s;
    cos_sin(slow_offset, c, s);
    put_lane(b.offsets, std::size_t(2 * q), lane, c);
    put_lane(b.offsets, std::size_t(2 * q + 1), lane, s);
  }
  double re[detail::kMaxSlowNodes], im[detail::kMaxSlowNodes];
  for (std::size_t g = 0; g < group.runs.size(); ++g) {
    const RunTables& t = d.runs[group.runs[g]];
    const double theta1_rate = t.rate + e[ch::domega];
    double arm_x = blocks.pB[0];
    arm_x += e[ch::arm_stretch] * theta1_rate * theta1_rate;
    put_lane(b.run_rates, 3 * g, lane, theta1_rate);
    put_lane(b.run_rates, 3 * g + 1, lane, t.counter ? -(theta1_rate + dOmega) : 0.0);
    put_lane(b.run_rates, 3 * g + 2, lane, arm_x);
    const double omega_T = (t.rate + domega) * t.duration;
    run_nodes::zero_harmonic_moments(d, Q, omega_T, re, im);
    for (int q = 0; q < Q; ++q) {
      put_lane(b.zero_moments, 2 * std::size_t(Q) * g + std::size_t(q), lane, re[q]);
      put_lane(b.zero_moments, 2 * std::size_t(Q) * g + std::size_t(Q + q), lane, im[q]);
    }
    for (int m = 1; m <= half; ++m) {
      const std::size_t h = 4 * (g * std::size_t(half) + std::size_t(m - 1));
      const double turn_angle = double(m) * domega * t.duration / 2.0;
      double c = t.cos_half[std::size_t(m)], s = t.sin_half[std::size_t(m)];
      // A turn beyond the small-angle series (|Δω| of a few σ on a long run) is made here, as slow_moments
      // makes it: the lanes then turn by 0, which leaves c and s as they are (c·1 − s·0, s·1 + c·0).
      const bool small = std::abs(turn_angle) < kSmallAngle;
      if (!small) turn(c, s, turn_angle, c, s);
      put_lane(b.harmonics, h, lane, omega_T * double(m) / 2.0);
      put_lane(b.harmonics, h + 1, lane, c);
      put_lane(b.harmonics, h + 2, lane, s);
      put_lane(b.harmonics, h + 3, lane, small ? turn_angle : 0.0);
    }
  }
}

// The means of the trials `pack` (at most kBatchLanes, all of one rule; unused lanes repeat the first) into
// out[trial·runs + run].
void pack_means(const KernelTables& d, const std::vector<std::size_t>& pack, const double* errors,
                std::span<double> out, BatchScratch& b) {
  const auto L = std::size_t(d.layout.size()), R = d.runs.size();
  const int order = d.layout.harmonic_order(), channel = 2 * order + 1;
  const TrialTerms& lead = b.terms[pack.front()];
  for (std::size_t k = 0; k < d.groups.size(); ++k) {
    const RunGroup& group = d.groups[k];
    const RunTables& first = d.runs[group.runs.front()];
    const int G = int(group.runs.size()), M = group.M,
              Q = b.key[pack.front() * (kRuleFlags + d.groups.size()) + kRuleFlags + k];
    const auto packs = [](int n) { return std::size_t(n) * kBatchLanes; };
    for (auto* v : {&b.main_coefficients, &b.platform_coefficients}) v->resize(packs(5 * channel));
    for (auto* v : {&b.main_ripple, &b.platform_ripple}) v->resize(packs(2 * order));
    b.frame.resize(packs(run_nodes::kFrameValues));
    b.run_rates.resize(packs(3 * G));
    b.offsets.resize(packs(2 * Q));
    b.zero_moments.resize(packs(2 * Q * G));
    b.harmonics.resize(packs(4 * G * (M / 2)));
    for (auto* v : {&b.nu_re, &b.nu_im}) v->resize(packs(G * (M / 2) * Q));
    for (auto* v : {&b.weights, &b.products}) v->resize(packs(Q * G * M));
    b.means.resize(packs(G));
    for (std::size_t lane = 0; lane < kBatchLanes; ++lane) {
      const std::size_t t = pack[std::min(lane, pack.size() - 1)];
      fill_lane(d, group, Q, b.terms[t], errors + t * L, lane, b);
    }
    const bool platform_ripple = first.counter && lead.platform_ripple;
    const run_nodes::BatchLanes lanes{&d,
                                      &group,
                                      M,
                                      G,
                                      Q,
                                      order,
                                      b.main_coefficients.data(),
                                      b.platform_coefficients.data(),
                                      lead.main_ripple ? b.main_ripple.data() : nullptr,
                                      platform_ripple ? b.platform_ripple.data() : nullptr,
                                      first.counter && lead.phase_locked && lead.main_ripple != nullptr,
                                      lead.main_series == AngleSeries::tiny,
                                      b.frame.data(),
                                      b.run_rates.data(),
                                      b.offsets.data(),
                                      b.harmonics.data(),
                                      b.zero_moments.data(),
                                      b.nu_re.data(),
                                      b.nu_im.data(),
                                      b.weights.data(),
                                      b.products.data(),
                                      b.means.data(),
                                      lead.g,
                                      1.0 / lead.unit};
    run_nodes::batch_weights_lanes(lanes);
    run_nodes::batch_nodes_lanes(lanes);
    for (std::size_t lane = 0; lane < pack.size(); ++lane)
      for (std::size_t g = 0; g < group.runs.size(); ++g)
        out[pack[lane] * R + group.runs[g]] = b.means[g * kBatchLanes + lane];
  }
}

}  // namespace

void RunMeanKernel::means(std::span<const double> errors, std::size_t trials, std::span<double> out,
                          Workspace& workspace) const {
  const Data& d = *data_;
  const auto L = std::size_t(d.layout.size()), R = d.runs.size();
  if (errors.size() != trials * L || out.size() != trials * R)
    throw std::invalid_argument(
        fmt::format("RunMeanKernel::means: {} errors for {} trials of a layout of {}, {} outputs for {} runs",
                    errors.size(), trials, L, out.size(), R));
  if (!workspace.buffers_) workspace.buffers_ = std::make_unique<Workspace::Buffers>();  // moved from
  BatchScratch& b = workspace.buffers_->batch;
  const std::size_t key_size = kRuleFlags + d.groups.size();
  b.terms.clear();
  b.key.assign(trials * key_size, 0);
  for (std::size_t t = 0; t < trials; ++t) {
    const Eigen::Map<const Eigen::VectorXd> e(errors.data() + t * L, Eigen::Index(L));
    b.terms.push_back(run_nodes::trial_terms(d, e));
    rule_of(d, b.terms.back(), e.data(), &b.key[t * key_size]);
  }
  // Packs of trials of one rule, in trial order; a trial alone takes the one-trial path.
  std::vector<char>& done = b.done;
  std::vector<std::size_t>& pack = b.pack;
  done.assign(trials, 0);
  for (std::size_t t = 0; t < trials; ++t) {
    if (done[t]) continue;
    const int* key = &b.key[t * key_size];
    if (key[0] == kRuleAlone) {
      means(errors.subspan(t * L, L), out.subspan(t * R, R), workspace);
      continue;
    }
    pack.clear();
    for (std::size_t u = t; u < trials && pack.size() < kBatchLanes; ++u)
      if (!done[u] && std::equal(key, key + key_size, &b.key[u * key_size])) {
        pack.push_back(u);
        done[u] = 1;
      }
    pack_means(d, pack, errors.data(), out, b);
  }
}

}  // namespace ccal
