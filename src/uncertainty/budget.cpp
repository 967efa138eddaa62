#include "ccal/uncertainty/budget.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

#include "../core/cloned_loops.hpp"
#include "ccal/core/scalar.hpp"
#include "ccal/core/units.hpp"
#include "ccal/uncertainty/option_rows.hpp"
#include "ccal/model/first_order.hpp"
#include "ccal/setup/input_correlation.hpp"
#include "ccal/uncertainty/chain_inputs.hpp"

namespace ccal {

namespace {

// H⁺ of the model's design (the design is data here), by the column-scaled QR of solve_least_squares.
Eigen::MatrixXd design_pseudo_inverse(const Observations<double>& model, const IdentificationSpec& spec) {
  const auto nfree = Eigen::Index(spec.free_terms.size());
  const Eigen::MatrixXd H = model.regressors.leftCols(nfree);
  const Eigen::Index runs = H.rows();
  Eigen::MatrixXd pinv(nfree, runs);
  for (Eigen::Index j = 0; j < runs; ++j)
    pinv.col(j) = solve_least_squares<double>(H, Eigen::VectorXd::Unit(runs, j));
  return pinv;
}

// The instrument with everything that depends on the angular rate removed: the specific-force path.
InstrumentModel force_only(InstrumentModel ins) {
  ins.rate_gain = 0.0;
  for (std::size_t k = 0; k < ins.term_ids.size(); ++k)
    if (ins.term_ids[k] == "K_w") ins.coefficients[Eigen::Index(k)] = 0.0;
  return ins;
}

// A run's exact mean in 8-wide duals with the whole chain inlined into one function: out of line, each dual
// operation is a call (most of the time of a design's candidate rows for the drive errors). Inlining
// changes no result (no contraction, no reassociation).
CCAL_FLATTEN RunAverage<Dual> exact_average_dual(const Experiment& ex, const VecX<Dual>& e,
                                                 const ccal::Run& run, const ReductionOptions& reduction) {
  return average_run<Dual>(ex.geometry, ex.layout, e, ex.site, run, &ex.instrument, {}, reduction);
}

// ∂ȳ/∂e (runs × parameters) by forward-mode AD: one Dual pass per kDualWidth parameters through the truth
// reduction.
Eigen::MatrixXd output_jacobian_ad(const Experiment& ex, const IdentificationSpec& spec,
                                   const std::vector<int>& parameters, const Eigen::VectorXd& at,
                                   ModelMode mode, const ReductionOptions& reduction) {
  const auto runs = Eigen::Index(ex.plan.runs.size());
  Eigen::MatrixXd dy(runs, Eigen::Index(parameters.size()));
  const int n = ex.layout.size();
  for (std::size_t first = 0; first < parameters.size(); first += kDualWidth) {
    VecX<Dual> e(n);
    for (int i = 0; i < n; ++i) e[i] = make_dual(at[i], -1);
    const int width = int(std::min<std::size_t>(kDualWidth, parameters.size() - first));
    for (int k = 0; k < width; ++k) e[parameters[first + std::size_t(k)]].derivatives()[k] = 1.0;
    for (Eigen::Index j = 0; j < runs; ++j) {
      const ccal::Run& run = ex.plan.runs[std::size_t(j)];
      const RunAverage<Dual> avg = mode == ModelMode::exact ? exact_average_dual(ex, e, run, reduction)
                                                            : paper_average<Dual>(ex, e, run, &ex.instrument,
                                                                                  {}, spec.paper_cross_terms);
      for (int k = 0; k < width; ++k) dy(j, Eigen::Index(first) + k) = avg.output.derivatives()[k];
    }
  }
  return dy;
}

// ∂ȳ/∂e at zero errors from the closed-form linearisation of the exact chain (exact_first_order, which equals
// the AD Jacobian of the chain, tests/model/first_order_test.cpp), split by path: at each quadrature node the
// output's gradient in (a, ω_IA) times the node's kinematic sensitivities, averaged with the rule's weights.
// The drive errors move the nodes and weights themselves and go through AD (twice when the paths are split:
// the whole output and the force path alone). With zero errors and ΔΩ = 0 the integrand is periodic in the
// fast phase, so one slow node suffices; its band limit in the fast phase is (polynomial degree − 1) + (N +
// 1) for a harmonic of order ≤ N.
// The drives' columns (whose first-order terms depend on t, which the nodes above do not carry) by automatic
// differentiation of the whole chain: their total in the force path, or, with `split`, the force path alone
// and the rest in the rate path.
void drive_columns_by_ad(const Experiment& ex, const IdentificationSpec& spec, const std::vector<int>& drive,
                         const std::vector<Eigen::Index>& drive_columns, const ReductionOptions& reduction,
                         bool split, Eigen::MatrixXd& force, Eigen::MatrixXd& rate) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const Eigen::MatrixXd total = output_jacobian_ad(ex, spec, drive, zero, ModelMode::exact, reduction);
  if (!split) {  // only the sum of the paths is asked for: the drive columns' total, in the force path
    for (std::size_t d = 0; d < drive.size(); ++d) {
      force.col(drive_columns[d]) = total.col(Eigen::Index(d));
      rate.col(drive_columns[d]).setZero();
    }
    return;
  }
  Experiment f = ex;
  f.instrument = force_only(ex.instrument);
  const Eigen::MatrixXd through_force = output_jacobian_ad(f, spec, drive, zero, ModelMode::exact, reduction);
  for (std::size_t d = 0; d < drive.size(); ++d) {
    force.col(drive_columns[d]) = through_force.col(Eigen::Index(d));
    rate.col(drive_columns[d]) = total.col(Eigen::Index(d)) - through_force.col(Eigen::Index(d));
  }
}

void output_jacobian_linearised(const Experiment& ex, const IdentificationSpec& spec,
                                const std::vector<int>& parameters, const ReductionOptions& reduction,
                                bool split, Eigen::MatrixXd& force, Eigen::MatrixXd& rate) {
  const auto runs = Eigen::Index(ex.plan.runs.size());
  const auto np = Eigen::Index(parameters.size());
  force = Eigen::MatrixXd::Zero(runs, np);
  rate = Eigen::MatrixXd::Zero(runs, np);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const std::vector<TermSpec> terms = ex.instrument.terms();
  const int degree = std::max(polynomial_degree(terms), 1);
  std::vector<int> drive;
  std::vector<Eigen::Index> drive_columns;
  for (Eigen::Index c = 0; c < np; ++c)
    if (channels()[ex.layout.parameter_channel(parameters[std::size_t(c)])].link == Link::drive) {
      drive.push_back(parameters[std::size_t(c)]);
      drive_columns.push_back(c);
    }
  for (Eigen::Index j = 0; j < runs; ++j) {
    const ccal::Run& run = ex.plan.runs[std::size_t(j)];
    const double rate_nominal = nominal_rate(run, ex.geometry, ex.site);
    const double phi0 = initial_phase(run, ex.geometry, ex.site);
    const RunMotion<double> motion =
        run_motion<double>(rate_nominal, run.arm_azimuth, phi0, run.mode, ex.geometry.beta, zero);
    QuadratureOptions qo = reduction.quadrature;
    if (qo.fast_nodes == 0)
      qo.fast_nodes = has_non_smooth_term(terms) && run.mode == PlatformMode::counter_rotating
                          ? 512
                          : fast_nodes_for(degree - 1 + ex.layout.harmonic_order() + 1, 1);
    qo.slow_nodes = 1;
    const RunQuadrature<double> quad = run_quadrature<double>(motion, run.duration, run.mode, 0.0, qo);
    const Eigen::Matrix3d mount = mounting_matrix(run.mounting).transpose();
    for (std::size_t n = 0; n < quad.nodes.size(); ++n) {
      const JointState<double>& node = quad.nodes[n];
      // The node's joint state is the run's state at t = (θ1 − θ1(0))/Ω; exact_first_order's drive columns
      // (which depend on t) are not used.
      const double t = (node.theta1 - motion.theta1_0) / motion.theta1_rate;
      const FirstOrderResult fo = exact_first_order(ex.geometry, ex.layout, ex.site, motion, run.mode, t);
      const Eigen::Vector3d a = mount * fo.nominal.head<3>(), w = mount * fo.nominal.tail<3>();
      // Gradient of the output in (a_i, a_p, a_o, ω_IA) by a 4-direction dual evaluation.
      const Vec3<Dual> ad(make_dual(a[0], 0), make_dual(a[1], 1), make_dual(a[2], 2));
      const Dual out = instrument_output(ex.instrument, terms, ad, make_dual(w[0], 3));
      const Eigen::RowVector3d grad_a = out.derivatives().head<3>().transpose() * mount;
      const Eigen::RowVector3d grad_w = out.derivatives()[3] * mount.row(0);
      const double weight = quad.weights[n];
      for (Eigen::Index c = 0; c < np; ++c) {
        const auto col = fo.sensitivity.col(parameters[std::size_t(c)]);
        force(j, c) += weight * grad_a.dot(col.head<3>());
        rate(j, c) += weight * grad_w.dot(col.tail<3>());
      }
    }
  }
  if (!drive.empty()) drive_columns_by_ad(ex, spec, drive, drive_columns, reduction, split, force, rate);
}

}  // namespace

OutputJacobian output_jacobian(const Experiment& ex, const IdentificationSpec& spec,
                               const std::vector<int>& parameters, const Eigen::VectorXd& at, ModelMode mode,
                               const ReductionOptions& reduction, DerivativeMethod method, bool split) {
  // The measuring chain's inputs have columns of their own (chain_inputs.hpp), shown in the force path: they
  // are no path of the centrifuge's motion.
  if (std::any_of(parameters.begin(), parameters.end(), is_chain_parameter)) {
    std::vector<int> layout_parameters, chain_parameters;
    for (int p : parameters) (is_chain_parameter(p) ? chain_parameters : layout_parameters).push_back(p);
    const OutputJacobian motion =
        output_jacobian(ex, spec, layout_parameters, at, mode, reduction, method, split);
    const Eigen::MatrixXd chain = chain_output_columns(ex, spec, chain_parameters, at, mode, reduction);
    const auto runs = Eigen::Index(ex.plan.runs.size());
    OutputJacobian j;
    j.method = motion.method;
    j.total.resize(runs, Eigen::Index(parameters.size()));
    if (split) j.force_path = j.rate_path = Eigen::MatrixXd::Zero(runs, Eigen::Index(parameters.size()));
    Eigen::Index next_motion = 0, next_chain = 0;
    for (std::size_t c = 0; c < parameters.size(); ++c) {
      const auto col = Eigen::Index(c);
      if (is_chain_parameter(parameters[c])) {
        j.total.col(col) = chain.col(next_chain);
        if (split) j.force_path.col(col) = chain.col(next_chain);
        ++next_chain;
      } else {
        j.total.col(col) = motion.total.col(next_motion);
        if (split) {
          j.force_path.col(col) = motion.force_path.col(next_motion);
          j.rate_path.col(col) = motion.rate_path.col(next_motion);
        }
        ++next_motion;
      }
    }
    return j;
  }
  OutputJacobian j;
  const bool linearised =
      method == DerivativeMethod::linearised && mode == ModelMode::exact && at.isZero(0.0);
  j.method = linearised ? DerivativeMethod::linearised : DerivativeMethod::automatic;
  if (linearised) {
    output_jacobian_linearised(ex, spec, parameters, reduction, split, j.force_path, j.rate_path);
    j.total = j.force_path + j.rate_path;
  } else {
    j.total = output_jacobian_ad(ex, spec, parameters, at, mode, reduction);
    if (split) {
      Experiment f = ex;
      f.instrument = force_only(ex.instrument);
      j.force_path = output_jacobian_ad(f, spec, parameters, at, mode, reduction);
      j.rate_path = j.total - j.force_path;
    }
  }
  if (!split) j.force_path = j.rate_path = Eigen::MatrixXd();
  return j;
}

SensitivityTable sensitivities(const Experiment& ex, const IdentificationSpec& spec,
                               const std::vector<int>& parameters, const Eigen::VectorXd& at,
                               const Eigen::VectorXd& known, ModelMode mode,
                               const ReductionOptions& reduction, DerivativeMethod method) {
  SensitivityTable t;
  t.coefficients = spec.free_terms;
  t.parameters = parameters;
  const Eigen::MatrixXd pinv =
      design_pseudo_inverse(observe<double>(ex, at, known, spec, mode, reduction), spec);
  const OutputJacobian j = output_jacobian(ex, spec, parameters, at, mode, reduction, method);
  t.method = j.method;
  if (j.method == DerivativeMethod::linearised) {
    t.force_path = pinv * j.force_path;
    t.rate_path = pinv * j.rate_path;
    t.total = t.force_path + t.rate_path;
  } else {
    t.total = pinv * j.total;
    t.force_path = pinv * j.force_path;
    t.rate_path = t.total - t.force_path;
  }
  return t;
}

std::vector<CompensationChoice> compensation_choices(const Experiment& ex, const IdentificationSpec& spec,
                                                     const Eigen::VectorXd& at, const Eigen::VectorXd& known,
                                                     ModelMode mode, bool with_paper,
                                                     const ReductionOptions& reduction) {
  std::vector<CompensationChoice> out;
  if (!ex.site.earth_rotation) return out;
  auto bias = [&](ModelMode m, bool coriolis) {
    Experiment model = ex;
    (coriolis ? model.site.apply_coriolis : model.site.sense_earth_rate) = false;
    const auto with =
        identify_coefficients<double>(observe<double>(ex, ex, at, known, spec, m, reduction), spec);
    const auto without =
        identify_coefficients<double>(observe<double>(ex, model, at, known, spec, m, reduction), spec);
    return Eigen::VectorXd(without - with);
  };
  for (bool coriolis : {false, true}) {
    CompensationChoice c;
    c.id = coriolis ? "coriolis" : "earth_rate";
    c.description = coriolis ? "Coriolis force 2 w_ie x v left out of the model"
                             : "Earth rate on the instrument left out of the model";
    c.bias = bias(mode, coriolis);
    if (with_paper) c.paper_bias = bias(ModelMode::paper, coriolis);
    out.push_back(std::move(c));
  }
  return out;
}

namespace {

// Each tolerance's line of the budget (u(xᵢ), cᵢ, uᵢ(y) = cᵢ u(xᵢ), and its paths), and the covariance of the
// coefficients from the correlation groups: sources of one group add their effects, groups add variances.
void add_tolerance_sources(const Config& config, const SensitivityTable& table, const SensitivityTable* paper,
                           BudgetDetail& r) {
  const auto nk = Eigen::Index(r.coefficients.size());
  const CorrelationGroups groups = correlation_groups(config.tolerances);
  Eigen::MatrixXd group_effect = Eigen::MatrixXd::Zero(nk, groups.count);
  for (std::size_t s = 0; s < config.tolerances.size(); ++s) {
    const Tolerance& t = config.tolerances[s];
    SourceBudget b;
    static_cast<Tolerance&>(b) = t;
    b.standard_uncertainty = standard_uncertainty(t.bound, t.distribution);
    b.sensitivity = table.total.col(Eigen::Index(s));
    b.effect = b.sensitivity * b.standard_uncertainty;
    b.effect_force = table.force_path.col(Eigen::Index(s)) * b.standard_uncertainty;
    b.effect_rate = table.rate_path.col(Eigen::Index(s)) * b.standard_uncertainty;
    if (paper != nullptr) b.paper_effect = paper->total.col(Eigen::Index(s)) * b.standard_uncertainty;
    if (is_chain_parameter(t.parameter)) {
      b.paper_counterpart = false;  // the paper's rules have no measuring chain
    } else {
      const ErrorKind kind = channels()[config.centrifuge.layout.parameter_channel(t.parameter)].kind;
      b.paper_counterpart = kind != ErrorKind::main_ripple && kind != ErrorKind::platform_ripple;
    }
    group_effect.col(groups.of[s]) += b.effect;
    r.sources.push_back(std::move(b));
  }
  if (!config.correlations.empty()) {
    const InputCorrelation inputs = input_correlation(config.tolerances, config.correlations);
    r.input_correlation = inputs.matrix;
    r.input_factor = inputs.factor;
    group_effect = independent_effects(r);
  }
  r.covariance = group_effect * group_effect.transpose();
}

// The drives' rate noise: independent per run, so H⁺ diag(σ_j²) H⁺ᵀ (model.md §3.2), added to the
// covariance.
void add_rate_noise(const Experiment& ex, const IdentificationSpec& spec, const Eigen::VectorXd& at,
                    const Eigen::VectorXd& known, const BudgetOptions& options, BudgetDetail& r) {
  if (!ex.rate_noise.any()) return;
  const Eigen::MatrixXd pinv =
      design_pseudo_inverse(observe<double>(ex, at, known, spec, r.mode, options.reduction), spec);
  // Both drives' gains from one pass over the runs' nodes.
  const RateNoiseGains gains = rate_noise_gains(ex, at, ex.rate_noise.main > 0, ex.rate_noise.platform > 0);
  for (auto [gain, density, id] :
       {std::tuple{&gains.main, ex.rate_noise.main, "main_rate_noise"},
        std::tuple{&gains.platform, ex.rate_noise.platform, "platform_rate_noise"}}) {
    if (!(density > 0)) continue;
    RateNoiseBudget n;
    n.id = id;
    n.density = density;
    n.run_sd = density * *gain;
    const Eigen::MatrixXd effects = pinv * n.run_sd.asDiagonal();
    n.covariance = effects * effects.transpose();
    n.effect = n.covariance.diagonal().cwiseSqrt();
    r.covariance += n.covariance;
    r.rate_noise.push_back(std::move(n));
  }
}

// u, U = k u and the correlation matrix from the covariance.
void set_totals(BudgetDetail& r) {
  const auto nk = Eigen::Index(r.coefficients.size());
  r.standard_uncertainty = r.covariance.diagonal().cwiseSqrt();
  r.expanded_uncertainty = r.coverage.factor * r.standard_uncertainty;
  r.correlation = Eigen::MatrixXd::Identity(nk, nk);
  for (Eigen::Index i = 0; i < nk; ++i)
    for (Eigen::Index j = 0; j < nk; ++j)
      if (i != j && r.standard_uncertainty[i] > 0 && r.standard_uncertainty[j] > 0)
        r.correlation(i, j) = r.covariance(i, j) / (r.standard_uncertainty[i] * r.standard_uncertainty[j]);
}

// Exact vs paper: flagged where they differ by more than the factor (or in sign) and the larger of the two
// matters, i.e. reaches 1e-3 of the coefficient's total standard uncertainty (a factor between two
// negligible numbers is no finding).
void flag_paper_disagreements(double factor, BudgetDetail& r) {
  for (SourceBudget& b : r.sources) {
    for (Eigen::Index k = 0; k < Eigen::Index(r.coefficients.size()); ++k) {
      const double x = std::abs(b.effect[k]), p = std::abs(b.paper_effect[k]);
      const double big = std::max(x, p), small = std::min(x, p);
      const bool material = big >= 1e-3 * r.standard_uncertainty[k] && big > 0.0;
      const bool opposite = b.effect[k] * b.paper_effect[k] < 0;
      b.disagrees.push_back(b.paper_counterpart && material && (opposite || big > factor * small));
    }
  }
}

// Each source's and each noise's share of every coefficient's variance, and the sources ranked by their
// largest share (ties in tolerance order).
void rank_by_share(BudgetDetail& r) {
  const auto nk = Eigen::Index(r.coefficients.size());
  std::vector<double> largest(r.sources.size(), 0.0);
  for (std::size_t s = 0; s < r.sources.size(); ++s) {
    SourceBudget& b = r.sources[s];
    b.share = Eigen::VectorXd::Zero(nk);
    for (Eigen::Index k = 0; k < nk; ++k) {
      const double var = r.covariance(k, k);
      b.share[k] = var > 0 ? b.effect[k] * b.effect[k] / var : 0.0;
    }
    largest[s] = b.share.size() ? b.share.maxCoeff() : 0.0;
  }
  for (RateNoiseBudget& n : r.rate_noise) {
    n.share = Eigen::VectorXd::Zero(nk);
    for (Eigen::Index k = 0; k < nk; ++k)
      if (r.covariance(k, k) > 0) n.share[k] = n.covariance(k, k) / r.covariance(k, k);
  }
  std::vector<std::size_t> order(r.sources.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return largest[a] > largest[b]; });
  for (std::size_t pos = 0; pos < order.size(); ++pos) r.sources[order[pos]].rank = int(pos) + 1;
}

}  // namespace

Eigen::MatrixXd independent_effects(const BudgetDetail& b) {
  Eigen::MatrixXd effects(Eigen::Index(b.coefficients.size()), Eigen::Index(b.sources.size()));
  for (std::size_t s = 0; s < b.sources.size(); ++s) effects.col(Eigen::Index(s)) = b.sources[s].effect;
  return independent_effects(b, effects);
}

Eigen::MatrixXd independent_effects(const BudgetDetail& b, const Eigen::MatrixXd& effects) {
  if (b.input_factor.size() > 0) return effects * b.input_factor;
  const CorrelationGroups groups = correlation_groups(b.sources);
  Eigen::MatrixXd g = Eigen::MatrixXd::Zero(effects.rows(), groups.count);
  for (std::size_t s = 0; s < b.sources.size(); ++s) g.col(groups.of[s]) += effects.col(Eigen::Index(s));
  return g;
}

Eigen::VectorXd correlation_variance(const BudgetDetail& b) {
  Eigen::VectorXd out = independent_effects(b).rowwise().squaredNorm();
  for (const SourceBudget& s : b.sources) out -= s.effect.cwiseAbs2();
  return out;
}

namespace {

constexpr std::string_view kDerivativeNames[] = {"automatic", "linearised"};  // DerivativeMethod's order

constexpr OptionSpec<BudgetOptions> kBudgetRows[] = {
    rows::mode<&BudgetOptions::mode>(
        "Kinematics: exact (full chain) or paper (Wang & Ren first-order rules); "
        "default: the configuration's [identification] mode"),
    rows::coverage_probability(&BudgetOptions::coverage_probability,
                               "Coverage probability p of the expanded uncertainty U = k u, in {range}: k = "
                               "1.96 for 0.95, the normal LPU total's"),
    rows::coverage_factor(&BudgetOptions::coverage_factor),
    {"derivatives", enum_member<&BudgetOptions::derivatives>(kDerivativeNames), "METHOD",
     "How the sensitivities are differentiated: linearised (closed-form chain Jacobian at zero errors, AD "
     "elsewhere; fast) or automatic (forward-mode AD through everything); same numbers"},
};

}  // namespace

OptionTable<BudgetOptions> options_of(std::type_identity<BudgetOptions>) { return kBudgetRows; }

BudgetDetail compute_budget(const Config& config, const BudgetOptions& options) {
  check_options(options, option_table<BudgetOptions>());
  rows::check_coverage_choice(options.coverage_probability, options.coverage_factor);
  const ModelMode mode = options.mode.value_or(config.mode);
  const Experiment ex = config.experiment();
  const IdentificationSpec& spec = config.identification;
  const Eigen::VectorXd& at = config.centrifuge.errors;
  const Eigen::VectorXd known = spec.compensate ? at : Eigen::VectorXd::Zero(at.size());

  BudgetDetail r;
  std::vector<int> parameters;
  for (const Tolerance& t : config.tolerances) parameters.push_back(t.parameter);
  const SensitivityTable table =
      sensitivities(ex, spec, parameters, at, known, mode, options.reduction, options.derivatives);
  SensitivityTable paper;
  const bool compare = mode == ModelMode::exact && options.compare_with_paper;
  if (compare)
    paper = sensitivities(ex, spec, parameters, at, known, ModelMode::paper, options.reduction,
                          options.derivatives);
  r.derivatives = table.method;
  r.mode = mode;
  r.coefficients = spec.free_terms;
  r.coverage = normal_coverage(options.coverage_probability.value_or(kDefaultCoverageProbability), options.coverage_factor);
  for (const auto& id : r.coefficients) {
    r.units.push_back(coefficient_unit(config.instrument.output_unit, id, config.instrument.g_symbol));
    r.display_scale.push_back(to_unit(1.0, config.instrument.output_unit));
  }
  add_tolerance_sources(config, table, compare ? &paper : nullptr, r);
  add_rate_noise(ex, spec, at, known, options, r);
  set_totals(r);
  if (compare) flag_paper_disagreements(options.disagreement_factor, r);
  rank_by_share(r);
  r.compensation = compensation_choices(ex, spec, at, known, mode, compare, options.reduction);
  return r;
}

}  // namespace ccal
