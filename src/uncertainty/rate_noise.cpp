#include "ccal/uncertainty/rate_noise.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <tuple>
#include <vector>

#include "../core/cloned_loops.hpp"
#include "ccal/core/scalar.hpp"
#include "ccal/reduction/quadrature.hpp"
#include "ccal/reduction/run_average.hpp"

namespace ccal {

namespace {

// cos and sin of the angles the Fourier sums of one revolution's M nodes need, computed once per M and shared
// by every run (each with the same expression as a direct call would use, so the sums are unchanged to the
// last bit): the analysis angles 2π((m·j) mod M)/M and the synthesis angles m·θ_j, θ_j = 2πj/M,
// for m = 1 … M/2 − 1 and j = 0 … M − 1.
struct NodeTrig {
  int M = 0;
  std::vector<double> analysis_cos, analysis_sin, synthesis_cos, synthesis_sin;  // index (m − 1)·M + j
  explicit NodeTrig(int nodes) : M(nodes) {
    const auto size = std::size_t(std::max(M / 2 - 1, 0) * M);
    analysis_cos.resize(size), analysis_sin.resize(size), synthesis_cos.resize(size),
        synthesis_sin.resize(size);
    for (int m = 1; m < M / 2; ++m)
      for (int j = 0; j < M; ++j) {
        const std::size_t at = index(m, j);
        const double a = 2 * std::numbers::pi * double((m * j) % M) / M;
        analysis_cos[at] = std::cos(a), analysis_sin[at] = std::sin(a);
        const double th = 2 * std::numbers::pi * j / M;
        synthesis_cos[at] = std::cos(double(m) * th), synthesis_sin[at] = std::sin(double(m) * th);
      }
  }
  std::size_t index(int m, int j) const { return std::size_t((m - 1) * M + j); }
};

// Real Fourier coefficients of samples at θ_j = 2πj/M: G = a0 + Σ_{m=1}^{M/2−1} (a_m cos mθ + b_m sin mθ)
// (the Nyquist term is dropped: M is chosen well above the integrand's band).
struct Fourier {
  double a0 = 0;
  std::vector<double> a, b;  // index m − 1
};
Fourier fourier(const std::vector<double>& g, const NodeTrig& trig) {
  const int M = int(g.size());
  Fourier f;
  for (double v : g) f.a0 += v / M;
  for (int m = 1; m < M / 2; ++m) {
    double am = 0, bm = 0;
    for (int j = 0; j < M; ++j) {
      am += g[std::size_t(j)] * trig.analysis_cos[trig.index(m, j)];
      bm += g[std::size_t(j)] * trig.analysis_sin[trig.index(m, j)];
    }
    f.a.push_back(2 * am / M);
    f.b.push_back(2 * bm / M);
  }
  return f;
}
// dG/dθ and the zero-mean primitive ∫(G − a0) dθ at node j.
double derivative_at_node(const Fourier& f, const NodeTrig& trig, int j) {
  double d = 0;
  for (std::size_t i = 0; i < f.a.size(); ++i) {
    const int m = int(i + 1);
    const std::size_t at = trig.index(m, j);
    d += double(m) * (f.b[i] * trig.synthesis_cos[at] - f.a[i] * trig.synthesis_sin[at]);
  }
  return d;
}
double primitive_at_node(const Fourier& f, const NodeTrig& trig, int j) {
  double p = 0;
  for (std::size_t i = 0; i < f.a.size(); ++i) {
    const int m = int(i + 1);
    const std::size_t at = trig.index(m, j);
    p += (f.a[i] * trig.synthesis_sin[at] - f.b[i] * trig.synthesis_cos[at]) / double(m);
  }
  return p;
}
// The same primitive at any angle θ.
double primitive(const Fourier& f, double th) {
  double p = 0;
  for (std::size_t i = 0; i < f.a.size(); ++i) {
    const double m = double(i + 1);
    p += (f.a[i] * std::sin(m * th) - f.b[i] * std::cos(m * th)) / m;
  }
  return p;
}

// The number of nodes over one revolution: the integrand's band is the output's polynomial degree times the
// inputs' harmonics, plus two for the products with the derivatives' own harmonics.
int revolution_nodes(const Experiment& ex) {
  const std::vector<TermSpec> terms = ex.instrument.terms();
  return 2 * fast_nodes_for(std::max(polynomial_degree(terms), 1) + 1, ex.layout.harmonic_order() + 1);
}

// σ / N of a run's mean from the derivatives of its output with respect to the drive's angle, rate and
// acceleration at the M nodes of one revolution (model.md §3.2). A relative-rate fluctuation n moves the
// angle by q̇∫n, the rate by q̇ n, the acceleration by q̇ ṅ:
//   h/q̇ = p(θ(s)) + c0 + ā (T − s),  p = G_r − Ω dG_c/dθ − P_a(θ)/Ω,  c0 = P_a(θ(T))/Ω,
// with P_a the zero-mean θ-primitive of G_a and ā its mean (the secular part of ∫ₛᵀ G_a).
double gain_from_derivatives(const std::vector<double>& Ga, const std::vector<double>& Gr,
                             const std::vector<double>& Gc, const NodeTrig& trig, double fast_rate,
                             double drive_rate, double T) {
  const int M = trig.M;
  const Fourier fa = fourier(Ga, trig), fc = fourier(Gc, trig);
  double p_mean = 0, p_square = 0;
  for (int j = 0; j < M; ++j) {
    const double p = Gr[std::size_t(j)] - fast_rate * derivative_at_node(fc, trig, j) -
                     primitive_at_node(fa, trig, j) / fast_rate;
    p_mean += p / M;
    p_square += p * p / M;
  }
  const double c0 = primitive(fa, std::fmod(fast_rate * T, 2 * std::numbers::pi)) / fast_rate;
  const double slope = fa.a0;
  const double integral = T * p_square + 2 * p_mean * (c0 * T + slope * T * T / 2) + c0 * c0 * T +
                          c0 * slope * T * T + slope * slope * T * T * T / 3;
  return std::abs(drive_rate) * std::sqrt(std::max(integral, 0.0)) / T;
}

// The output's derivatives at the M nodes: ∂/∂θ1, ∂/∂θ̇1, ∂/∂θ̈1 of the main axis's joint (with γ when the
// platform follows it) and ∂/∂γ, ∂/∂γ̇, ∂/∂γ̈ of the platform's.
struct NodeDerivatives {
  std::vector<double> Ga1, Gr1, Gc1, Ga3, Gr3, Gc3;
};

// Most of a design's candidate rows' time: the whole chain in dual numbers at every node, inlined into one
// loop (CCAL_FLATTEN) and compiled for each instruction set (an 8-wide dual is one AVX-512 register): 3.6 s
// → 1.0 s of the bundled example's 9,990 candidates on one core, the same bits on every instruction set.
CCAL_CLONED CCAL_FLATTEN NodeDerivatives node_derivatives(const DynamicChain<Dual>& chain,
                                                          const RunMotion<double>& motion,
                                                          const InstrumentModel& instrument,
                                                          const std::vector<TermSpec>& terms,
                                                          const Eigen::Matrix3d& mount, double follow_sign,
                                                          double fast_rate, int M) {
  const auto nodes = std::size_t(M);
  NodeDerivatives out;
  for (auto* v : {&out.Ga1, &out.Gr1, &out.Gc1, &out.Ga3, &out.Gr3, &out.Gc3}) v->resize(nodes);
  for (int j = 0; j < M; ++j) {
    const double t = 2 * std::numbers::pi * j / M / fast_rate;
    const JointState<double> s = motion.at(t);
    JointState<Dual> d;
    d.theta1 = make_dual(s.theta1, 0);
    d.theta1_rate = make_dual(s.theta1_rate, 1);
    d.theta1_acc = make_dual(s.theta1_acc, 2);
    d.gamma = make_dual(s.gamma, 3);
    d.gamma_rate = make_dual(s.gamma_rate, 4);
    d.gamma_acc = make_dual(s.gamma_acc, 5);
    d.beta = make_dual(s.beta, -1);
    d.beta_rate = make_dual(s.beta_rate, -1);
    d.theta1_ripple_rate = make_dual(s.theta1_ripple_rate, -1);
    const SensedInput<Dual> state = chain(d);
    const Vec3<Dual> a = mount.cast<Dual>() * state.specific_force;
    const Vec3<Dual> w = mount.cast<Dual>() * state.angular_rate;
    const auto g = instrument_output<Dual>(instrument, terms, a, w[0]).derivatives();
    const auto at = std::size_t(j);
    out.Ga1[at] = g[0] + follow_sign * g[3];
    out.Gr1[at] = g[1] + follow_sign * g[4];
    out.Gc1[at] = g[2] + follow_sign * g[5];
    out.Ga3[at] = g[3];
    out.Gr3[at] = g[4];
    out.Gc3[at] = g[5];
  }
  return out;
}

// σ / N of one run's mean for the main axis ([0]) and the platform drive ([1]), from one evaluation of the
// output's derivatives at each node (both drives' joints are differentiated together).
std::array<double, 2> run_gains(const Experiment& ex, const Eigen::VectorXd& e, const ccal::Run& run,
                                const NodeTrig& trig, bool want_main, bool want_platform) {
  const bool counter = run.mode == PlatformMode::counter_rotating;
  want_platform = want_platform && counter;  // a fixed platform does not turn: no platform noise
  if (!want_main && !want_platform) return {0.0, 0.0};
  const double rate = nominal_rate(run, ex.geometry, ex.site);
  const double phi0 = initial_phase(run, ex.geometry, ex.site);
  const RunMotion<double> motion =
      run_motion<double>(rate, run.arm_azimuth, phi0, run.mode, ex.geometry, ex.layout, e);
  const double fast_rate = motion.theta1_rate;  // the fast phase θ = (Ω + Δω) t
  // The main axis's own joint: θ1, and γ with it when the platform is phase-locked to it.
  const double follow_sign = motion.platform_follows_main ? -1.0 : 0.0;

  // Derivatives of the output with respect to (θ1, θ̇1, θ̈1, γ, γ̇, γ̈) at the M nodes of one revolution.
  const std::vector<TermSpec> terms = ex.instrument.terms();
  const Eigen::Matrix3d mount = mounting_matrix(run.mounting).transpose();
  // The chain with its time-invariant blocks composed once (equal to exact_state to round-off); the arm's
  // stretch follows the mean rate, whose derivative is the rate's (slot 1), as in exact_state.
  const DynamicChain<Dual> chain(ex.geometry, ex.layout, e, ex.site, make_dual(motion.theta1_rate, 1),
                                 make_dual(motion.beta, -1));
  const NodeDerivatives g =
      node_derivatives(chain, motion, ex.instrument, terms, mount, follow_sign, fast_rate, trig.M);
  const auto& [Ga1, Gr1, Gc1, Ga3, Gr3, Gc3] = g;
  const double T = run.duration;
  return {want_main ? gain_from_derivatives(Ga1, Gr1, Gc1, trig, fast_rate, motion.theta1_rate, T) : 0.0,
          want_platform ? gain_from_derivatives(Ga3, Gr3, Gc3, trig, fast_rate, motion.gamma_rate, T) : 0.0};
}

}  // namespace

std::vector<Tolerance> rate_noise_sources(const Config& cfg) {
  std::vector<Tolerance> out;
  const Experiment ex = cfg.experiment();
  if (!ex.rate_noise.any()) return out;
  const RateNoiseGains gains =
      rate_noise_gains(ex, cfg.centrifuge.errors, ex.rate_noise.main > 0, ex.rate_noise.platform > 0);
  for (auto [drive_gain, density, name] :
       {std::tuple{&gains.main, ex.rate_noise.main, "main_rate_noise"},
        std::tuple{&gains.platform, ex.rate_noise.platform, "platform_rate_noise"}}) {
    if (!(density > 0)) continue;
    const Eigen::VectorXd& gain = *drive_gain;
    for (std::size_t j = 0; j < ex.plan.runs.size(); ++j) {
      if (!(gain[Eigen::Index(j)] > 0)) continue;
      Tolerance t;
      t.parameter = rate_noise_parameter(int(j));
      t.id = std::string(name) + "@" + ex.plan.runs[j].name;
      t.bound = density * gain[Eigen::Index(j)];
      t.distribution = Distribution::normal;
      out.push_back(std::move(t));
    }
  }
  return out;
}

Eigen::VectorXd rate_noise_gain(const Experiment& ex, const Eigen::VectorXd& e, int drive) {
  const RateNoiseGains both = rate_noise_gains(ex, e, drive == ch::ripple1, drive == ch::ripple3);
  return drive == ch::ripple1 ? both.main : both.platform;
}

RateNoiseGains rate_noise_gains(const Experiment& ex, const Eigen::VectorXd& e, bool main, bool platform) {
  const NodeTrig trig(revolution_nodes(ex));
  RateNoiseGains gains;
  gains.main = gains.platform = Eigen::VectorXd::Zero(Eigen::Index(ex.plan.runs.size()));
  for (std::size_t j = 0; j < ex.plan.runs.size(); ++j) {
    const auto [m, p] = run_gains(ex, e, ex.plan.runs[j], trig, main, platform);
    gains.main[Eigen::Index(j)] = m;
    gains.platform[Eigen::Index(j)] = p;
  }
  return gains;
}

}  // namespace ccal
