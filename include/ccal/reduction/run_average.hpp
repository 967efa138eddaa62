#pragma once
// Reduction of a run to its observation: time means of the sensed inputs, of each regressor and of the
// instrument output (docs/model.md §8), by the spectral rule of quadrature.hpp over the exact chain, plus the
// closed forms of the error-free means (model.md §4.1) that check it.

#include <Eigen/Core>
#include <vector>

#include "ccal/core/scalar.hpp"
#include "ccal/model/centrifuge.hpp"
#include "ccal/model/instrument.hpp"
#include "ccal/model/kinematics.hpp"
#include "ccal/model/plan.hpp"
#include "ccal/model/site.hpp"
#include "ccal/reduction/quadrature.hpp"

namespace ccal {

// ⟨cos^k γ⟩ over a counter-rotating run, γ(t) = φ0 − Ωt, t ∈ [0, T], by the reduction formula
// ∫cos^k = cos^{k−1} sin / k + (k−1)/k ∫cos^{k−2}:  (1/ΩT) ∫_{φ0−ΩT}^{φ0} cos^k γ dγ.
double mean_cos_power(int k, double phi0, double omega_T);
// Z_k = ⟨a_iᵏ⟩ of the error-free IA input a_i = −A cos γ (Earth rotation off).
double nominal_power_mean(int k, double A, double phi0, double omega_T);

struct ReductionOptions {
  QuadratureOptions quadrature;
  ChainOptions chain;
  // Use the factored static chain when every main- and azimuth-axis dynamic error is exactly zero (value and
  // derivatives): same result, several times faster.
  bool allow_static_chain = true;
};

template <class S>
struct RunAverage {
  Vec3<S> input = Vec3<S>::Zero();  // ⟨a_i, a_p, a_o⟩ [g]
  S rate_ia{0};                     // ⟨ω_IA⟩ [rad/s]
  VecX<S> regressors;               // ⟨regressor⟩ of each requested term
  S output{0};                      // ⟨instrument output⟩ [output SI], if an instrument was given
};

// Highest power of the input among the terms (2 for the cross products, 1 for K_p/K_o/K_w).
int polynomial_degree(const std::vector<TermSpec>& terms);
bool has_non_smooth_term(const std::vector<TermSpec>& terms);

namespace detail {

// Whether any dynamic error of the main and azimuth axes (a Fourier coefficient of their runouts and wobbles)
// is non-zero, value or derivative: then the chain is the dynamic one.
template <class S, class Errors>
bool has_dynamic_errors(const ErrorLayout& layout, const Errors& e) {
  for (int c : {int(ch::dx1), int(ch::dy1), int(ch::dz1), int(ch::dthx1), int(ch::dthy1), int(ch::dx3), int(ch::dy3),
                int(ch::dz3), int(ch::dthx3), int(ch::dthy3)})
    for (int k = 0; k <= layout.harmonic_order(); ++k)
      for (bool sine : {false, true}) {
        if (k == 0 && sine) continue;
        if (!is_exactly_zero(S(e[layout.harmonic_index(c, k, sine)]))) return true;
      }
  return false;
}

// The run's quadrature options: the configured ones, with fast nodes enough for the polynomial degree and the
// harmonics when none are configured. |a_i| a_i has a kink where a_i changes sign: only algebraic
// convergence, so many nodes. Dynamic errors and the drives' ripple of order N put harmonics up to N + 1 into
// the inputs.
inline QuadratureOptions run_quadrature_options(const ReductionOptions& options, const ErrorLayout& layout,
                                                const Run& run, const std::vector<TermSpec>& regressor_terms,
                                                const std::vector<TermSpec>& truth_terms, bool harmonic) {
  QuadratureOptions qo = options.quadrature;
  if (qo.fast_nodes == 0) {
    const int degree = std::max(polynomial_degree(regressor_terms), polynomial_degree(truth_terms));
    const bool kink = run.mode == PlatformMode::counter_rotating &&
                      (has_non_smooth_term(regressor_terms) || has_non_smooth_term(truth_terms));
    qo.fast_nodes = kink ? 512 : fast_nodes_for(degree, harmonic ? layout.harmonic_order() + 1 : 1);
  }
  return qo;
}

// The weighted sums of one run: each node's inputs in the instrument's axes (through its mounting), the
// regressors and the instrument's output.
template <class S>
struct RunSums {
  const std::vector<TermSpec>& regressor_terms;
  const std::vector<TermSpec>& truth_terms;
  const InstrumentModel* instrument;
  Eigen::Matrix3d mount;
  bool identity_mount;
  RunAverage<S> avg;

  void add(const S& weight, const Vec3<S>& f5, const Vec3<S>& w5) {
    const Vec3<S> a = identity_mount ? f5 : Vec3<S>(mount.transpose().template cast<S>() * f5);
    const Vec3<S> w = identity_mount ? w5 : Vec3<S>(mount.transpose().template cast<S>() * w5);
    avg.input += weight * a;
    avg.rate_ia += weight * w[0];
    for (std::size_t k = 0; k < regressor_terms.size(); ++k)
      avg.regressors[Eigen::Index(k)] += weight * term_regressor(regressor_terms[k], a, w[0]);
    if (instrument) avg.output += weight * instrument_output(*instrument, truth_terms, a, w[0]);
  }
};

}  // namespace detail

template <class S, class Errors>
RunAverage<S> average_run(const Geometry& geo, const ErrorLayout& layout, const Errors& e, const Site& site,
                          const Run& run, const InstrumentModel* instrument,
                          const std::vector<TermSpec>& regressor_terms,
                          const ReductionOptions& options = {}) {
  const double rate = nominal_rate(run, geo, site);
  const double phi0 = initial_phase(run, geo, site);
  const RunMotion<S> motion = run_motion<S>(rate, run.arm_azimuth, phi0, run.mode, geo, layout, e);
  const bool dynamic = detail::has_dynamic_errors<S>(layout, e);
  std::vector<TermSpec> truth_terms;
  if (instrument) truth_terms = instrument->terms();
  const QuadratureOptions qo = detail::run_quadrature_options(options, layout, run, regressor_terms, truth_terms,
                                                              dynamic || motion.has_ripple());
  const RunQuadrature<S> quad = run_quadrature<S>(motion, run.duration, run.mode, S(e[ch::dOmega]), qo);

  detail::RunSums<S> sums{regressor_terms, truth_terms, instrument, mounting_matrix(run.mounting),
                          run.mounting == Mounting::ia_horizontal, {}};
  sums.avg.regressors = VecX<S>::Zero(Eigen::Index(regressor_terms.size()));
  if (options.allow_static_chain && !dynamic) {
    const StaticChain<S> chain(geo, layout, e, site, motion.theta1_rate, motion.beta, options.chain);
    for (std::size_t n = 0; n < quad.nodes.size(); ++n) {
      const JointState<S>& j = quad.nodes[n];
      const SensedInput<S> in =
          chain(j.theta1, j.gamma, j.theta1_rate, j.gamma_rate, j.theta1_acc, j.gamma_acc);
      sums.add(quad.weights[n], in.specific_force, in.angular_rate);
    }
  } else {
    const DynamicChain<S> chain(geo, layout, e, site, motion.theta1_rate, motion.beta, options.chain);
    // Nodes that share a fast phase share the main-axis half of the chain.
    const std::size_t M = std::size_t(quad.fast_nodes), N = quad.nodes.size();
    for (std::size_t j = 0; j < M; ++j) {
      const FrameMotion<S> upper = chain.main_axis(quad.nodes[j]);
      for (std::size_t n = j; n < N; n += M) {
        const SensedInput<S> in = chain.platform(upper, quad.nodes[n]);
        sums.add(quad.weights[n], in.specific_force, in.angular_rate);
      }
    }
  }
  return sums.avg;
}

}  // namespace ccal
