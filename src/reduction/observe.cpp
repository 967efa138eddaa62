#include "ccal/reduction/observe.hpp"

#include <cmath>

#include "ccal/core/scalar.hpp"
#include "ccal/model/first_order.hpp"
#include "paper_nodes.hpp"

namespace ccal {

std::vector<std::string> observation_columns(const IdentificationSpec& spec) {
  std::vector<std::string> columns = spec.free_terms;
  for (const auto& [id, value] : spec.fixed_terms) {
    (void)value;
    columns.push_back(id);
  }
  return columns;
}

namespace detail {

PaperRunNodes paper_run_nodes(const Experiment& ex, const ccal::Run& run,
                              const std::vector<TermSpec>& terms) {
  const Geometry& geo = ex.geometry;
  PaperRunNodes n;
  n.rate = nominal_rate(run, geo, ex.site);
  const double phi0 = initial_phase(run, geo, ex.site);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const RunMotion<double> nominal =
      run_motion<double>(n.rate, run.arm_azimuth, phi0, run.mode, geo.beta, zero);
  QuadratureOptions qo;
  qo.fast_nodes = fast_nodes_for(std::max(polynomial_degree(terms), 3), ex.layout.harmonic_order() + 1);
  const RunQuadrature<double> quad = run_quadrature<double>(nominal, run.duration, run.mode, 0.0, qo);
  const PaperFormOptions form{.lever_arms = true, .constant_coriolis = true};
  for (std::size_t k = 0; k < quad.nodes.size(); ++k) {
    const JointState<double>& j = quad.nodes[k];
    const FirstOrderResult fo = paper_first_order(geo, ex.layout, ex.site, j, form);
    n.weight.push_back(quad.weights[k]);
    n.cos_gamma.push_back(std::cos(j.gamma));
    n.sin_gamma.push_back(std::sin(j.gamma));
    n.coriolis.push_back(-fo.nominal[0] - (n.rate * n.rate * geo.R0 / ex.site.g_unit()) * std::cos(j.gamma));
    n.nominal_rate_ia.push_back(fo.nominal[3]);
    std::vector<std::pair<int, double>> force, rate;
    for (int i = 0; i < ex.layout.size(); ++i) {
      if (i == ch::domega) continue;  // in the amplitude A
      if (fo.sensitivity(0, i) != 0.0) force.emplace_back(i, fo.sensitivity(0, i));
      if (fo.sensitivity(3, i) != 0.0) rate.emplace_back(i, fo.sensitivity(3, i));
    }
    n.force_row.push_back(std::move(force));
    n.rate_row.push_back(std::move(rate));
  }
  return n;
}

template <class S>
RunAverage<S> paper_average(const Experiment& ex, const PaperRunNodes& nodes, const VecX<S>& e,
                            const InstrumentModel* instrument, const std::vector<TermSpec>& terms,
                            bool cross_terms) {
  const S omega = S(nodes.rate) + e[ch::domega];
  const S A = S(ex.geometry.R0) * omega * omega / S(ex.site.g_unit());
  std::vector<TermSpec> truth_terms;
  double k1 = 0.0;
  if (instrument) {
    truth_terms = instrument->terms();
    k1 = instrument->coefficient("K1").value_or(0.0);
  }
  RunAverage<S> avg;
  avg.regressors = VecX<S>::Zero(Eigen::Index(terms.size()));
  for (std::size_t n = 0; n < nodes.weight.size(); ++n) {
    const S a_power = -A * nodes.cos_gamma[n];  // the K2, K3 … input: amplitude only
    S a_pose = a_power;                         // with the pose errors, without the Coriolis term
    S w_ia = S(nodes.nominal_rate_ia[n]);
    for (const auto& [i, d] : nodes.force_row[n]) a_pose += d * e[i];
    for (const auto& [i, d] : nodes.rate_row[n]) w_ia += d * e[i];
    // a_i of §5.1: the pose errors and the constant Coriolis term, both first order in small quantities.
    const S a_k1 = a_pose - S(nodes.coriolis[n]);
    const Vec3<S> a_cross(a_k1, A * nodes.sin_gamma[n], S(1));
    const Vec3<S> a_plain(a_power, A * nodes.sin_gamma[n], S(1));
    const S weight = S(nodes.weight[n]);
    avg.input += weight * a_cross;
    avg.rate_ia += weight * w_ia;
    for (std::size_t k = 0; k < terms.size(); ++k) {
      // The paper's regressors: Z1 carries the errors, Z2, Z3 … are the nominal means (Eq.16/17). With cross
      // terms every term takes the same a_i, the Coriolis term included: the instrument cannot tell where a
      // specific force comes from, so δE = Σ n Kn a0ⁿ⁻¹ δa_i for every δa_i (model.md §5.1).
      const bool power = terms[k].kind == TermKind::power && terms[k].power != 1;
      const Vec3<S>& a = power && !cross_terms ? a_plain : a_cross;
      avg.regressors[Eigen::Index(k)] += weight * term_regressor(terms[k], a, w_ia);
    }
    if (instrument) {
      S out = cross_terms
                  ? instrument_output(*instrument, truth_terms, a_cross, w_ia)
                  : instrument_output(*instrument, truth_terms, a_plain, w_ia) + S(k1) * (a_k1 - a_power);
      // The paper's additive −ΔΩ (output in rad/s), a rate-path term: it goes with the instrument's rate
      // gain.
      avg.output += weight * (out - (instrument->rate_gain != 0.0 ? e[ch::dOmega] : S(0)));
    }
  }
  return avg;
}

template RunAverage<double> paper_average<double>(const Experiment&, const PaperRunNodes&,
                                                  const VecX<double>&, const InstrumentModel*,
                                                  const std::vector<TermSpec>&, bool);

}  // namespace detail

// The paper's reduction of one run (docs/model.md §5.1, §7.1): a_i from the first-order form with the
// frozen-γ rules and a constant Coriolis term, phases on the nominal rate, Δω in the amplitude
// A = R0 (Ω + Δω)² / g of every power term (Eq.14/19), pose errors and the Coriolis term in the K1 term only
// unless cross_terms (then in every term),
// the Earth-rate term on the IA heading, and the paper's additive −ΔΩ in the output.
template <class S>
RunAverage<S> paper_average(const Experiment& ex, const VecX<S>& e, const ccal::Run& run,
                            const InstrumentModel* instrument, const std::vector<TermSpec>& terms,
                            bool cross_terms) {
  return detail::paper_average<S>(ex, detail::paper_run_nodes(ex, run, terms), e, instrument, terms,
                                  cross_terms);
}

template RunAverage<double> paper_average<double>(const Experiment&, const VecX<double>&, const ccal::Run&,
                                                  const InstrumentModel*, const std::vector<TermSpec>&, bool);
template RunAverage<Dual> paper_average<Dual>(const Experiment&, const VecX<Dual>&, const ccal::Run&,
                                              const InstrumentModel*, const std::vector<TermSpec>&, bool);

void add_output_noise(Observations<double>& obs, const Experiment& ex, std::uint64_t seed) {
  const InstrumentModel& ins = ex.instrument;
  if (ins.noise_density == 0.0 && ins.quantum == 0.0) return;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  for (Eigen::Index j = 0; j < obs.output.size(); ++j) {
    const double T = ex.plan.runs[std::size_t(j)].duration;
    if (ins.noise_density > 0.0) obs.output[j] += ins.noise_density / std::sqrt(T) * normal(rng);
    if (ins.quantum > 0.0) obs.output[j] += ins.quantum / T * uniform(rng);
  }
}

FitProblem fit_problem(const Observations<double>& obs, const IdentificationSpec& spec) {
  FitProblem p;
  p.term_names = obs.columns;
  p.H = obs.regressors;
  p.y = obs.output - obs.known_rate;
  p.fixed = spec.fixed_terms;
  p.row_labels = obs.runs;
  return p;
}

}  // namespace ccal
