#pragma once
// Time means over a run, spectrally accurate (docs/model.md §8).
//
// On a run the integrand is F(t) = Φ(Ωt, t): periodic (2π) in the fast phase θ = Ωt, because both joint
// angles advance with it (θ1 = θ1(0) + θ, γ = φ0 − cθ − ΔΩ t with c = 1 on a counter-rotating platform and
// c = 0 with ΔΩ = 0 on a fixed one), and slowly varying in t only through the platform mismatch ΔΩ t. With
// the fast phase sampled at M equispaced nodes θ_j and the slow time at Q nodes s_q T,
//     Φ(θ, t) ≈ Σ_m Σ_q φ_m(x_q) L_q(x) e^{imθ},  t = T(1 + x)/2   (DFT in θ, Lagrange interpolation in x)
// and each harmonic is integrated exactly against the interpolant over the whole run, partial last revolution
// included:
//     (1/T) ∫₀ᵀ L_q e^{imΩt} dt = e^{iκ/2} Σ_p a_qp J_p(κ/2),   J_p(k) = ½ ∫₋₁¹ x^p e^{ikx} dx,  κ = mΩT.
// The mean is then Σ_{j,q} w_jq Φ(θ_j, s_q T): a fixed rule whose weights depend only on Ω, ΔΩ and T. It is
// exact for integrands band-limited below M/2 in θ and polynomial of degree < Q in t, and converges
// spectrally otherwise. The weights are templated so that Ω and ΔΩ can carry automatic derivatives.
//
// A trapezoid-over-whole-revolutions + Gauss–Legendre-over-the-partial-one rule is also provided for the
// locked case (ΔΩ = 0), as an independent check.

#include <Eigen/Core>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "ccal/core/scalar.hpp"
#include "ccal/model/centrifuge.hpp"
#include "ccal/model/kinematics.hpp"
#include "ccal/reduction/detail/spectral_weights.hpp"

namespace ccal {

struct QuadratureOptions {
  int fast_nodes = 0;  // M per revolution; 0 = automatic from the band limit (see fast_nodes_for)
  int slow_nodes = 0;  // Q in time; 0 = automatic from |ΔΩ| T
  // Relative accuracy asked of the automatic Q (the interpolation error in slow time relative to the
  // integrand's swing). 1e-16 is round-off; a Monte Carlo whose spread is 1e-3 of the swing needs far less.
  double slow_tolerance = 1e-16;
};

// Nodes of a run's mean: joint states and weights (Σ weights = 1).
template <class S>
struct RunQuadrature {
  std::vector<JointState<S>> nodes;
  std::vector<S> weights;
  // The spectral rule's nodes are stored slow-major: node q·fast_nodes + j has fast phase θ_j, so the
  // main-axis state of nodes j, M + j, 2M + j … is the same (0 for other rules).
  int fast_nodes = 0;
};

// M for an integrand that is a polynomial of degree `polynomial_degree` in inputs whose harmonic content in
// the fast phase reaches `input_harmonics` (1 for static errors, N + 1 with dynamic errors of order N):
// the band limit D = (degree + 2)·harmonics (two extra orders for the O(ε²) harmonics of exact rotations),
// and M = 2D + 2 rounded up to a multiple of 4, at least 12.
int fast_nodes_for(int polynomial_degree, int input_harmonics);
// Q for a phase drift of `drift` radians over the run: the smallest Q ≤ 10 with drift^Q / Q! < 1e-16.
int slow_nodes_for(double drift, double tolerance = 1e-16);

// The spectral rule for one run of duration T.
template <class S>
RunQuadrature<S> run_quadrature(const RunMotion<S>& motion, double duration, PlatformMode mode,
                                const S& platform_mismatch, const QuadratureOptions& options) {
  using std::cos;
  using std::sin;
  const int M = options.fast_nodes > 0 ? options.fast_nodes : fast_nodes_for(3, 1);
  const bool counter = mode == PlatformMode::counter_rotating;
  // The drift ΔΩT shifts the phase of the n-th harmonic of γ by nΔΩT; the integrand's significant harmonics
  // reach about M/4 (M is twice the band limit).
  const double drift = counter ? std::abs(value_of(platform_mismatch)) * duration * (M / 4) : 0.0;
  const int Q =
      counter ? (options.slow_nodes > 0 ? options.slow_nodes : slow_nodes_for(drift, options.slow_tolerance))
              : 1;
  if (Q > detail::kMaxSlowNodes)
    throw std::invalid_argument("run_quadrature: at most 16 slow-time nodes (monomial Lagrange basis)");
  const std::vector<double> x_nodes = detail::slow_time_nodes(Q);
  const Eigen::MatrixXd& a = detail::slow_lagrange_monomials(Q);

  // With t = T(1 + x)/2:  (1/T)∫₀ᵀ L_q e^{imΩt} dt = e^{iκ/2} Σ_p a_qp J_p(κ/2),  κ = mΩT.
  const int half = M / 2;
  std::vector<S> nu_re(std::size_t((half + 1) * Q)), nu_im(nu_re.size());
  const S omega_T = motion.theta1_rate * duration;
  for (int m = 0; m <= half; ++m) {
    const S half_kappa = omega_T * double(m) / 2.0;
    detail::harmonic_slow_moments<S>(half_kappa, cos(half_kappa), sin(half_kappa), a, &nu_re[m * Q],
                                     &nu_im[m * Q]);
  }
  const detail::FastPhaseTable table(M);
  RunQuadrature<S> out;
  out.fast_nodes = M;
  out.weights.resize(std::size_t(M * Q));
  detail::dft_weights<S>(table, Q, nu_re.data(), nu_im.data(), out.weights.data());
  out.nodes.reserve(M * Q);
  for (int q = 0; q < Q; ++q) {
    const S slow_offset = counter ? S(-platform_mismatch * (0.5 * (1.0 + x_nodes[q]) * duration)) : S(0);
    for (int j = 0; j < M; ++j) {
      const double theta = table.phase(j);
      JointState<S> js;
      js.theta1 = motion.theta1_0 + theta;
      js.theta1_rate = motion.theta1_rate;
      js.beta = motion.beta;
      js.gamma = motion.gamma_0 - (counter ? theta : 0.0) + slow_offset;
      js.gamma_rate = motion.gamma_rate;
      motion.add_ripple(js);  // the drives' rate ripple at the node's nominal angles
      out.nodes.push_back(js);
    }
  }
  return out;
}

// Reference rule for the locked case (fixed platform, or counter-rotating with ΔΩ = 0): the trapezoid rule
// with M nodes per revolution over the whole revolutions (exact for band-limited periodic integrands, and
// independent of their number) plus Gauss–Legendre with `gauss_nodes` nodes over the partial revolution.
RunQuadrature<double> trapezoid_gauss_quadrature(const RunMotion<double>& motion, double duration,
                                                 int nodes_per_revolution, int gauss_nodes);

}  // namespace ccal
