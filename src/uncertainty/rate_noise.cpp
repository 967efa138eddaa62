#include "ccal/uncertainty/rate_noise.hpp"

#include <cmath>
#include <numbers>
#include <tuple>
#include <vector>

#include "ccal/core/scalar.hpp"
#include "ccal/reduction/quadrature.hpp"
#include "ccal/reduction/run_average.hpp"

namespace ccal {

namespace {

// Real Fourier coefficients of samples at θ_j = 2πj/M: G = a0 + Σ_{m=1}^{M/2−1} (a_m cos mθ + b_m sin mθ)
// (the Nyquist term is dropped: M is chosen well above the integrand's band).
struct Fourier {
  double a0 = 0;
  std::vector<double> a, b;  // index m − 1
};
Fourier fourier(const std::vector<double>& g) {
  const int M = int(g.size());
  Fourier f;
  for (double v : g) f.a0 += v / M;
  for (int m = 1; m < M / 2; ++m) {
    double am = 0, bm = 0;
    for (int j = 0; j < M; ++j) {
      const double th = 2 * std::numbers::pi * double((m * j) % M) / M;
      am += g[std::size_t(j)] * std::cos(th);
      bm += g[std::size_t(j)] * std::sin(th);
    }
    f.a.push_back(2 * am / M);
    f.b.push_back(2 * bm / M);
  }
  return f;
}
// dG/dθ and the zero-mean primitive ∫(G − a0) dθ at θ.
double derivative(const Fourier& f, double th) {
  double d = 0;
  for (std::size_t i = 0; i < f.a.size(); ++i) {
    const double m = double(i + 1);
    d += m * (f.b[i] * std::cos(m * th) - f.a[i] * std::sin(m * th));
  }
  return d;
}
double primitive(const Fourier& f, double th) {
  double p = 0;
  for (std::size_t i = 0; i < f.a.size(); ++i) {
    const double m = double(i + 1);
    p += (f.a[i] * std::sin(m * th) - f.b[i] * std::cos(m * th)) / m;
  }
  return p;
}

// σ / N of one run's mean (model.md §3.2).
double run_gain(const Experiment& ex, const Eigen::VectorXd& e, const ccal::Run& run, int drive) {
  const bool counter = run.mode == PlatformMode::counter_rotating;
  if (drive == ripple3 && !counter) return 0.0;
  const double rate = nominal_rate(run, ex.geometry, ex.site);
  const double phi0 = initial_phase(run, ex.geometry, ex.site);
  const RunMotion<double> motion =
      run_motion<double>(rate, run.arm_azimuth, phi0, run.mode, ex.geometry, ex.layout, e);
  const bool follows = drive == ripple1 && motion.platform_follows_main;
  const double q_rate = drive == ripple1 ? motion.theta1_rate : motion.gamma_rate;
  const double fast_rate = motion.theta1_rate;  // the fast phase θ = (Ω + Δω) t

  // Derivatives of the output with respect to (θ1, θ̇1, θ̈1, γ, γ̇, γ̈) at M nodes of one revolution. The
  // integrand's band: the output's polynomial degree times the inputs' harmonics, plus two for the products
  // with the derivatives' own harmonics.
  const std::vector<TermSpec> terms = ex.instrument.terms();
  const int M = 2 * fast_nodes_for(std::max(polynomial_degree(terms), 1) + 1, ex.layout.harmonic_order() + 1);
  const Eigen::Matrix3d mount = mounting_matrix(run.mounting).transpose();
  const auto nodes = std::size_t(M);
  std::vector<double> Ga(nodes), Gr(nodes), Gc(nodes);
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
    const InstrumentState<Dual> state = exact_state<Dual>(ex.geometry, ex.layout, e, ex.site, d);
    const Vec3<Dual> a = mount.cast<Dual>() * state.specific_force;
    const Vec3<Dual> w = mount.cast<Dual>() * state.angular_rate;
    const auto g = instrument_output<Dual>(ex.instrument, terms, a, w[0]).derivatives();
    // The drive's own joint: θ1 (the platform follows it when phase-locked) or γ.
    const double sign = follows ? -1.0 : 0.0;
    if (drive == ripple1) {
      Ga[std::size_t(j)] = g[0] + sign * g[3];
      Gr[std::size_t(j)] = g[1] + sign * g[4];
      Gc[std::size_t(j)] = g[2] + sign * g[5];
    } else {
      Ga[std::size_t(j)] = g[3];
      Gr[std::size_t(j)] = g[4];
      Gc[std::size_t(j)] = g[5];
    }
  }
  // A relative-rate fluctuation n moves the angle by q̇∫n, the rate by q̇ n, the acceleration by q̇ ṅ:
  //   h/q̇ = p(θ(s)) + c0 + ā (T − s),  p = G_r − Ω dG_c/dθ − P_a(θ)/Ω,  c0 = P_a(θ(T))/Ω,
  // with P_a the zero-mean θ-primitive of G_a and ā its mean (the secular part of ∫ₛᵀ G_a).
  const Fourier fa = fourier(Ga), fc = fourier(Gc);
  const double T = run.duration;
  double p_mean = 0, p_square = 0;
  for (int j = 0; j < M; ++j) {
    const double th = 2 * std::numbers::pi * j / M;
    const double p = Gr[std::size_t(j)] - fast_rate * derivative(fc, th) - primitive(fa, th) / fast_rate;
    p_mean += p / M;
    p_square += p * p / M;
  }
  const double c0 = primitive(fa, std::fmod(fast_rate * T, 2 * std::numbers::pi)) / fast_rate;
  const double slope = fa.a0;
  const double integral = T * p_square + 2 * p_mean * (c0 * T + slope * T * T / 2) + c0 * c0 * T +
                          c0 * slope * T * T + slope * slope * T * T * T / 3;
  return std::abs(q_rate) * std::sqrt(std::max(integral, 0.0)) / T;
}

}  // namespace

std::vector<Tolerance> rate_noise_sources(const Config& cfg) {
  std::vector<Tolerance> out;
  const Experiment ex = cfg.experiment();
  for (auto [drive, density, name] :
       {std::tuple{int(ripple1), ex.rate_noise.main, "main_rate_noise"},
        std::tuple{int(ripple3), ex.rate_noise.platform, "platform_rate_noise"}}) {
    if (!(density > 0)) continue;
    const Eigen::VectorXd gain = rate_noise_gain(ex, cfg.centrifuge.errors, drive);
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
  Eigen::VectorXd gain(Eigen::Index(ex.plan.runs.size()));
  for (std::size_t j = 0; j < ex.plan.runs.size(); ++j)
    gain[Eigen::Index(j)] = run_gain(ex, e, ex.plan.runs[j], drive);
  return gain;
}

}  // namespace ccal
