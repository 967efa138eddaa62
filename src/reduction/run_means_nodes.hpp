#pragma once
// The node loops of the run-mean kernel (run_means.hpp), internal to the library: the main-axis half of the
// chain at the fast nodes and the platform half at the nodes of one slow node, over structure-of-arrays node
// data, kPackLanes nodes per SIMD vector where the wobble angles allow (run_means_nodes.cpp).
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "ccal/model/instrument.hpp"

namespace ccal::run_nodes {

// Nodes are stored padded to whole packs of this many lanes.
inline constexpr int kPackLanes = 8;  // one AVX-512 register of doubles
inline int padded(int n) { return (n + kPackLanes - 1) / kPackLanes * kPackLanes; }

template <class T>
struct V3 {
  T x, y, z;
};
inline V3<double> to_v3(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

// Structure-of-arrays storage of 3-vectors, one per node.
struct V3Array {
  std::vector<double> x, y, z;
  void resize(std::size_t n) {
    x.resize(n);
    y.resize(n);
    z.resize(n);
  }
};

// Node data: the main-axis half per fast node, the instrument's inputs per node (slow-major, each slow node
// padded to whole packs).
struct MainAxisNodes {
  // F₀ = a + 2ω_c × v + g ẑ₀ of o3t; Ω, Ω̇ of frame 3t; ω_c; Ω + ω_ie (frame-3t coordinates)
  V3Array F0, W, dW, coriolis, W_total;
  // The main axis's rate ripple at each node: δ1, δ̇1, δ̈1 (for a platform phase-locked to the main axis).
  std::vector<double> ripple_angle, ripple_rate, ripple_acc;
  void resize(std::size_t n) {
    for (V3Array* a : {&F0, &W, &dW, &coriolis, &W_total}) a->resize(n);
    for (auto* v : {&ripple_angle, &ripple_rate, &ripple_acc}) v->resize(n);
  }
};
struct InstrumentInputs {
  std::vector<double> a_i, a_p, a_o, w_ia;  // [g], [g], [g], [rad/s]
  void resize(std::size_t n) {
    for (auto* v : {&a_i, &a_p, &a_o, &w_ia}) v->resize(n);
  }
};

// Inputs of the main-axis half (frame 3t, a function of θ1 alone), evaluated in frame-3t coordinates, at the
// fast nodes of one or more runs side by side (node i: run i / M's node i mod M).
struct MainAxisInputs {
  const double* coefficients;  // dx1 … dthy1
  int order;
  const double* ripple;  // c1, s1, …, cN, sN of the main drive's rate ripple, or nullptr for none
  const double *cos_theta, *sin_theta;  // padded
  const double* rate;                   // θ̇1 of the node's run, padded
  const double* arm_x;                  // x of B's offset with the run's arm stretch, padded
  int nodes;
  double g;
  V3<double> pB, coriolis_1t, gravity_1t, earth_1t;  // pB's x at arm_x
  Eigen::Matrix3d RB;
};
// Inputs of the platform half at all nodes of runs that share their fast and slow nodes, one after the other
// without padding (run_means.cpp: node n = q·G·M + g·M + j, slow node q, run g of G, fast node j): frame 5
// relative to frame 3t, composed with the main-axis half of the same fast node, then the instrument's axes
// through P = R_C·mounting (a_i, a_p, a_o [g] and ω_IA). The main-axis half (MainAxisNodes) is read at n
// too: its G·M nodes repeated for every slow node.
struct PlatformInputs {
  const double* coefficients;  // dx3 … dthy3
  int order;
  const double* ripple;  // c1, s1, …, cN, sN of the platform drive's rate ripple, or nullptr for none
  bool follows_main;     // phase-locked: γ also moves by −δ1 of the same fast node (MainAxisNodes)
  const double *cos_gamma, *sin_gamma;    // nominal platform angle at fast node j of node n, padded
  const double *cos_offset, *sin_offset;  // slow node q's drift at node n, padded
  const double* rate;                     // γ̇ of the node's run, padded
  int nodes;
  double inverse_g;
  V3<double> pC;
  Eigen::Matrix3d P;
};
// ν = e^{iκ/2} Σ_p a_qp J_p(κ/2) of spectral_weights.hpp's harmonic_slow_moments for `count` harmonics at
// once (a multiple of kPackLanes), each given κ/2, its cosine and sine, with the same operations in each lane
// as that function when it takes J_p's forward recursion, which the caller has checked it does for all
// (!(|κ/2| < 4 + Q)): spectral_weights.hpp's oscillatory_recursion and slow_moments_of on SIMD vectors.
// a: the Q × Q Lagrange monomials. Into nu_re, nu_im at [q·count + i].
void harmonic_moments_lanes(const double* half_kappa, const double* cos_half_kappa,
                            const double* sin_half_kappa, int count, const Eigen::MatrixXd& a, double* nu_re,
                            double* nu_im);
// The quadrature weights of one run at its M fast nodes for each of its Q slow nodes, from the DFT of the
// weights (dft_cos, dft_sin: c_m cos(mθ_j), c_m sin(mθ_j) at (m − 1)M + j) and the slow moments ν_mq (nu_re,
// nu_im at m·Q + q): w_qj = (ν_0q + Σ_{m=1}^{M/2} (dft_cos Re ν_mq + dft_sin Im ν_mq)) / M, summed over m in
// order, eight nodes at a time, each lane with the operations of one node. Slow node q's at weights +
// q·stride.
void quadrature_weights_lanes(const double* dft_cos, const double* dft_sin, int M, int Q, const double* nu_re,
                              const double* nu_im, double* weights, int stride);
// (c, s) ← the cosine and sine of (a + δ) from those of a, for `count` angles at once (a multiple of
// kPackLanes), each δ below kSmallAngle as the caller has checked: frames.hpp's cos_sin of δ (its
// small-angle series) and the rotation c·cos δ − s·sin δ, s·cos δ + c·sin δ, lane by lane.
void small_turns_lanes(const double* delta, double* c, double* s, int count);
// The instrument's output as a polynomial in a_i plus the other terms (instrument.hpp), for one pass per
// node.
struct OutputPolynomial {
  std::array<double, kMaxPower + 1> power{};  // K_n of a_iⁿ
  int degree = 0;
  double abs_square = 0, p = 0, o = 0, ip = 0, io = 0, pp = 0, oo = 0, po = 0;
  double rate = 0;  // s_ω + K_w
  bool cross = false;

  explicit OutputPolynomial(const InstrumentModel& model);  // run_means.cpp
};

// products[n] = weights[n] · y(a_i, a_p, a_o, ω_IA at node n) for n < nodes (a multiple of kPackLanes), eight
// nodes at a time, each lane with the operations of one node.
void weighted_outputs_lanes(const OutputPolynomial& output, const double* weights, const InstrumentInputs& in,
                            int nodes, double* products);

// How a trial's wobble and ripple angles are taken (run_means_lanes.hpp): one node at a time with the
// library's cosine and sine where one may exceed kSmallAngle, else in SIMD lanes by the series to q⁹, or to
// q³ where all stay below kTinyAngle.
enum class AngleSeries { library, small, tiny };

// Σ |c0| + |ck| + |sk|: a bound of every value of a dynamic channel (c0, c1, s1, … at `coefficients`), which
// decides its AngleSeries.
double channel_bound(const double* coefficients, int order);
// Σ (|ck| + |sk|)/k: a bound of a rate ripple's angle error δ (c1, s1, … at `coefficients`; 0 for nullptr).
double ripple_angle_bound(const double* coefficients, int order);
// The main-axis half at nodes 0 … nodes − 1 (and the padding).
void main_axis_nodes(const MainAxisInputs& in, AngleSeries series, MainAxisNodes& out);
// The platform half at nodes 0 … nodes − 1 (and the padding) of `out`.
void platform_nodes(const PlatformInputs& in, AngleSeries series, const MainAxisNodes& main,
                    InstrumentInputs& out);

}  // namespace ccal::run_nodes
