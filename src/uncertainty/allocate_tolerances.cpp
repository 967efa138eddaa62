#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <boost/math/policies/policy.hpp>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>

#include "allocation_groups.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/core/units.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/setup/input_correlation.hpp"
#include "ccal/uncertainty/allocate.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/gaussian_copula.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "ccal/uncertainty/rate_noise.hpp"

namespace ccal {
namespace {

// The smallest accepted target, as a fraction of the coefficient's expanded uncertainty at the configured
// tolerances; the largest is the inverse multiple.
constexpr double kMinTargetFraction = 1 / kAllocationScaleLimit;

// Each target against its coefficient: one per free term, positive, and not beyond a million-fold
// tightening of every source.
void attach_targets(const BudgetDetail& b, const std::vector<AllocationTarget>& targets, double kp,
                    AllocationDetail& r) {
  for (const AllocationTarget& t : targets) {
    const auto it = std::find(b.coefficients.begin(), b.coefficients.end(), t.coefficient);
    if (it == b.coefficients.end())
      throw InputError(fmt::format("target on '{}': not a free term of the identification; accepted: {}",
                                   t.coefficient, fmt::join(b.coefficients, ", ")));
    const auto k = std::size_t(it - b.coefficients.begin());
    if (r.coefficients[k].has_target)
      throw OptionError(t.field, t.coefficient, "has two targets; accepted: one target per coefficient");
    // Tolerances scale in proportion to the target: beyond a million-fold tightening of every source the
    // allocation is meaningless (and towards 1e-300 the variances underflow and every tolerance becomes 0);
    // beyond a million-fold loosening no tolerance can follow (max_scale) and the squares overflow (1e308).
    const double configured = kp * b.standard_uncertainty[Eigen::Index(k)],
                 least = kMinTargetFraction * configured, most = configured / kMinTargetFraction;
    const std::string given = t.text.empty() ? fmt::format("{}={:g}", t.coefficient, t.expanded) : t.text;
    const std::string accepted = fmt::format(
        "accepted: a target on {} from {:.4g} to {:.4g} {} ({:g} to {:g} × its configured U = "
        "{:.4g} {})",
        t.coefficient, least * b.display_scale[k], most * b.display_scale[k], b.units[k], kMinTargetFraction,
        1 / kMinTargetFraction, configured * b.display_scale[k], b.units[k]);
    if (!(std::isfinite(t.expanded) && t.expanded > 0))
      throw OptionError(t.field, given, "is not a positive expanded uncertainty; " + accepted);
    if (t.expanded < least)
      throw OptionError(t.field, given,
                        "is tighter than a million-fold tightening of every tolerance can meet; " + accepted);
    if (t.expanded > most)
      throw OptionError(
          t.field, given,
          "is looser than a million-fold loosening of every tolerance would reach; " + accepted);
    r.coefficients[k].has_target = true;
    r.coefficients[k].target = t.expanded;
    r.targets.push_back(k);
  }
}

// The drives' rate noise (model.md §3.2) is no tolerance: it stays as it is, so each target leaves the
// tolerances √(T_k² − (k_p u_noise,k)²); a target the noise alone reaches cannot be met.
std::vector<double> tolerance_targets(double kp, const Eigen::VectorXd& noise_variance,
                                      const AllocationDetail& r) {
  const auto nt = r.targets.size();
  std::vector<double> tolerance_target(nt);
  for (std::size_t i = 0; i < nt; ++i) {
    const AllocatedCoefficient& c = r.coefficients[r.targets[i]];
    const double floor = kp * std::sqrt(noise_variance[Eigen::Index(r.targets[i])]);
    if (!(c.target > floor * (1 + 1e-9)))
      throw InputError(fmt::format(
          "target on {}: the drives' rate noise alone gives U = {:.4g} {} (model.md §3.2), at or above the "
          "target {:.4g} {}; no tolerance can meet it; accepted: a target above {:.4g} {}, or less rate "
          "noise "
          "([centrifuge] main_rate_noise, platform_rate_noise)",
          c.id, floor * c.display_scale, c.unit, c.target * c.display_scale, c.unit, floor * c.display_scale,
          c.unit));
    tolerance_target[i] = std::sqrt(c.target * c.target - floor * floor);
  }

  return tolerance_target;
}

// The problem's rows: the targets (their tolerance parts, tolerance_target), in the order given, then, unless
// o.let_others_grow, every other free coefficient that the tolerances reach, held at its configured
// tolerance part k_p √(Σ_g c_kg²) (so that U_k(λ) ≤ U_k(1): the rate noise stays as it is). Each source's
// least scale is floor/bound. Marks the held coefficients.
void allocation_problem(const Config& cfg, const BudgetDetail& b, const std::vector<double>& tolerance_target,
                        double kp, const AllocateOptions& o, AllocationProblem& P, AllocationDetail& r) {
  const auto ns = b.sources.size();
  P = AllocationProblem{};
  if (!cfg.correlations.empty()) P.correlation = input_correlation(cfg.tolerances, cfg.correlations).matrix;
  P.standard_uncertainty.resize(Eigen::Index(ns));
  P.cost.resize(Eigen::Index(ns));
  P.min_scale.resize(Eigen::Index(ns));
  for (std::size_t s = 0; s < ns; ++s) {
    const Tolerance& t = cfg.tolerances[s];
    P.standard_uncertainty[Eigen::Index(s)] = b.sources[s].standard_uncertainty;
    P.cost[Eigen::Index(s)] = t.cost;
    P.group.push_back(t.group);
    P.min_scale[Eigen::Index(s)] = t.floor / t.bound;
    if (P.min_scale[Eigen::Index(s)] > o.max_scale)
      throw OptionError(
          "max_scale", fmt::format("{:g}", o.max_scale),
          fmt::format("is below the floor of {} ({:g} of its bound); accepted: a max scale of at "
                      "least {:g}, or a lower floor in [tolerances]",
                      t.id, P.min_scale[Eigen::Index(s)], P.min_scale[Eigen::Index(s)]));
  }
  std::vector<std::size_t> rows = r.targets;
  std::vector<double> target = tolerance_target;
  Eigen::MatrixXd J(1, Eigen::Index(ns));
  for (std::size_t k = 0; k < r.coefficients.size() && !o.let_others_grow; ++k) {
    if (r.coefficients[k].has_target) continue;
    for (std::size_t s = 0; s < ns; ++s) J(0, Eigen::Index(s)) = b.sources[s].sensitivity[Eigen::Index(k)];
    const Eigen::RowVectorXd e = J.cwiseProduct(P.standard_uncertainty.transpose());
    const double configured =
        kp * (P.correlation.size() > 0
                  ? std::sqrt(e.dot(e * P.correlation))
                  : merge_groups(J, P.standard_uncertainty, P.cost, P.group).effect.norm());
    if (!(configured > 0)) continue;  // no tolerance reaches it: nothing to hold
    r.coefficients[k].held = true;
    rows.push_back(k);
    target.push_back(configured);
  }
  P.sensitivity.resize(Eigen::Index(rows.size()), Eigen::Index(ns));
  P.target.resize(Eigen::Index(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    P.target[Eigen::Index(i)] = target[i];
    for (std::size_t s = 0; s < ns; ++s)
      P.sensitivity(Eigen::Index(i), Eigen::Index(s)) = b.sources[s].sensitivity[Eigen::Index(rows[i])];
  }
  P.coverage_factor = kp;
  P.max_scale = o.max_scale;
}

// The targets that the floors make impossible, each with the least U they allow (tolerances at their
// floors, the others at 0, the rate noise as it is) and its factor above the target.
void refuse_unreachable(const AllocationSolution& sol, const Eigen::VectorXd& noise_variance, double kp,
                        const AllocationDetail& r) {
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < r.targets.size(); ++i) {
    if (!sol.unreachable[i]) continue;
    const AllocatedCoefficient& c = r.coefficients[r.targets[i]];
    const double tol = sol.least_expanded[Eigen::Index(i)],
                 least = std::hypot(tol, kp * std::sqrt(noise_variance[Eigen::Index(r.targets[i])]));
    lines.push_back(fmt::format(
        "target on {} = {:.4g} {}: the floors allow at least U = {:.4g} {} ({:.3g} × "
        "the target)",
        c.id, c.target * c.display_scale, c.unit, least * c.display_scale, c.unit, least / c.target));
  }
  throw InputError(
      fmt::format("{}; no allocation meets {} with every tolerance at or above its floor; "
                  "accepted: targets above those values, or lower floors ([tolerances] floor)",
                  fmt::join(lines, "; "), lines.size() == 1 ? "it" : "them"));
}

// Every free coefficient's uncertainty at the allocated tolerances (groups added with their signs); returns
// the allocated u per coefficient and fills the coefficients' expanded uncertainties and prices.
Eigen::VectorXd report_coefficients(const BudgetDetail& b, const AllocationProblem& P,
                                    const AllocationSolution& sol, const Eigen::VectorXd& noise_variance,
                                    double kp, Eigen::MatrixXd& J, AllocationDetail& r) {
  const auto nk = b.coefficients.size();
  const auto ns = b.sources.size();
  const auto nt = r.targets.size();
  J = Eigen::MatrixXd::Zero(Eigen::Index(nk), Eigen::Index(ns));
  for (std::size_t s = 0; s < ns; ++s) J.col(Eigen::Index(s)) = b.sources[s].sensitivity;
  const Eigen::VectorXd u_alloc_s = P.standard_uncertainty.cwiseProduct(sol.scale);
  Eigen::VectorXd tolerance_variance;  // Σ_st E_ks R_st E_kt, E = J diag(λ u_0); with groups alone Σ_g c_kg²
  if (P.correlation.size() > 0) {
    const Eigen::MatrixXd E = J * u_alloc_s.asDiagonal();
    tolerance_variance = (E * P.correlation * E.transpose()).diagonal();
  } else {
    const Groups allocated = merge_groups(J, u_alloc_s, P.cost, P.group);
    tolerance_variance = (allocated.effect * allocated.effect.transpose()).diagonal();
  }
  const Eigen::VectorXd u_alloc = (tolerance_variance + noise_variance).cwiseSqrt();
  for (std::size_t k = 0; k < nk; ++k) {
    AllocatedCoefficient& c = r.coefficients[k];
    c.configured_expanded = kp * b.standard_uncertainty[Eigen::Index(k)];
    c.allocated_expanded = kp * u_alloc[Eigen::Index(k)];
    const double u_configured = b.standard_uncertainty[Eigen::Index(k)];
    const double noise = noise_variance[Eigen::Index(k)];
    c.common_expanded = kp * std::sqrt(sol.common_scale * sol.common_scale *
                                           std::max(u_configured * u_configured - noise, 0.0) +
                                       noise);
    c.lpu_std = u_alloc[Eigen::Index(k)];
    // Named in the output: a coefficient without a target that the allocation made worse (1e-9: far above
    // the solver's round-off on a held row, 1e-13 of the variance, far below any change worth a word).
    c.grew = !c.has_target && c.allocated_expanded > c.configured_expanded * (1 + 1e-9);
  }
  for (std::size_t i = 0; i < nt; ++i) {
    AllocatedCoefficient& c = r.coefficients[r.targets[i]];
    c.multiplier = sol.multiplier[Eigen::Index(i)];
    // Raising T_k by a factor 1 + ε scales a_k by 1/(1 + ε)², i.e. relaxes the normalised constraint to
    // 1 + 2ε; the optimal objective changes by −μ_k per unit of relaxation.
    c.price = -2 * c.multiplier;
    c.active = sol.active[i];
  }

  return u_alloc;
}

void report_sources(const Config& cfg, const BudgetDetail& b, const AllocationSolution& sol,
                    const Eigen::MatrixXd& J, const Eigen::VectorXd& u_alloc, AllocationDetail& r) {
  const auto ns = b.sources.size();
  const auto nt = r.targets.size();
  for (std::size_t s = 0; s < ns; ++s) {
    const Tolerance& t = cfg.tolerances[s];
    AllocatedSource a;
    static_cast<Tolerance&>(a) = t;
    a.standard_uncertainty = b.sources[s].standard_uncertainty;
    a.scale = sol.scale[Eigen::Index(s)];
    a.allocated_bound = a.scale * t.bound;
    a.allocated_standard_uncertainty = a.scale * a.standard_uncertainty;
    a.least_scale = t.floor / t.bound;
    a.at_floor = t.floor > 0 && a.scale <= a.least_scale * (1 + 1e-12);
    a.share = Eigen::VectorXd::Zero(Eigen::Index(nt));
    for (std::size_t i = 0; i < nt; ++i) {
      const auto k = Eigen::Index(r.targets[i]);
      const double effect = J(k, Eigen::Index(s)) * a.allocated_standard_uncertainty;
      const double var = u_alloc[k] * u_alloc[k];
      a.share[Eigen::Index(i)] = var > 0 ? effect * effect / var : 0.0;
    }
    r.sources.push_back(std::move(a));
  }
  // The cross terms at the allocated tolerances, as the budget computes them (each effect J_ks u_s scaled by λ_s).
  BudgetDetail allocated = b;
  for (std::size_t s = 0; s < ns; ++s) allocated.sources[s].effect *= sol.scale[Eigen::Index(s)];
  const Eigen::VectorXd cross = correlation_variance(allocated);
  for (std::size_t k = 0; k < r.coefficients.size(); ++k) {
    const double var = u_alloc[Eigen::Index(k)] * u_alloc[Eigen::Index(k)];
    r.coefficients[k].correlation_share = var > 0 ? cross[Eigen::Index(k)] / var : 0.0;
  }
  std::stable_sort(r.sources.begin(), r.sources.end(),
                   [](const AllocatedSource& x, const AllocatedSource& y) { return x.scale < y.scale; });
}

// Monte Carlo on the allocated tolerances through the nonlinear pipeline of the mode, against the targets.
void verify(const Config& cfg, const AllocationSolution& sol, const Eigen::VectorXd& u_alloc, double kp,
            const AllocateOptions& o, AllocationDetail& r) {
  const auto nk = r.coefficients.size();
  const auto ns = cfg.tolerances.size();
  std::vector<Tolerance> scaled = cfg.tolerances;
  for (std::size_t s = 0; s < ns; ++s) scaled[s].bound *= sol.scale[Eigen::Index(s)];
  for (Tolerance& t : rate_noise_sources(cfg)) scaled.push_back(std::move(t));  // as it is
  CalibrationModel model;
  try {
    model = calibration_model(cfg.experiment(), cfg.identification, scaled, cfg.centrifuge.errors, *o.mode);
  } catch (const IllPosedFit& e) {
    throw plan_cannot_identify(e);
  }
  PropagationOptions mo;
  mo.trials = o.verify_trials;
  mo.seed = o.seed;
  mo.threads = o.threads;
  mo.coverage_probability = o.coverage_probability;
  mo.progress = o.progress;
  mo.on_progress = o.on_progress;
  if (o.on_progress) o.on_progress(0, o.verify_trials);  // may throw Cancelled: stop before the verification
  const MonteCarloDetail mc = run_monte_carlo(scaled, cfg.correlations, model.n_outputs(),
                                              model.output_names(), calibration_trial(model), mo, &u_alloc);
  AllocationVerification& v = r.verification;
  v.trials = mc.trials;
  v.seed = mc.seed;
  v.threads = mc.threads;
  v.seconds = mc.seconds;
  v.notes = mc.notes;
  const double M = double(mc.trials);
  const double p_end = (1 + o.coverage_probability) / 2;
  const double density = std::exp(-kp * kp / 2) / std::sqrt(2 * std::numbers::pi);
  v.half_width_rel_error = std::sqrt(p_end * (1 - p_end)) / (kp * density * std::sqrt(M));
  v.std_rel_error = 1 / std::sqrt(2 * M);
  v.allowance = 3 * v.half_width_rel_error;
  v.passed = true;
  for (std::size_t k = 0; k < nk; ++k) {
    AllocatedCoefficient& c = r.coefficients[k];
    const OutputSummary& s = mc.outputs[k];
    c.mc_mean = s.mean;
    c.mc_std = s.std_dev;
    c.mc_low = s.low_symmetric;
    c.mc_high = s.high_symmetric;
    c.mc_half_width = std::max(s.high_symmetric - s.mean, s.mean - s.low_symmetric);
    if (!c.has_target) continue;
    c.verdict = c.mc_half_width <= c.target                       ? Verdict::pass
                : c.mc_half_width <= c.target * (1 + v.allowance) ? Verdict::pass_within_sampling
                                                                  : Verdict::fail;
    if (c.verdict == Verdict::fail) v.passed = false;
  }
}

// What a value of the table's rows alone cannot say: the tolerances' costs, the verification's M against p,
// the threads the system can start, and the targets (parsed in the free terms' display units).
std::vector<AllocationTarget> checked_targets(const Config& cfg, const AllocateOptions& o) {
  if (cfg.tolerances.empty())
    throw InputError(cfg.source + ": [tolerances] is empty; the allocation needs at least one source");
  gaussian_copula(cfg);  // the verification's draws: a pair they cannot make is refused before any work
  if (o.verify_trials > 0) check_coverage_interval(o.verify_trials, o.coverage_probability, "verify_trials");
  for (const Tolerance& t : cfg.tolerances)
    if (!kToleranceCostRange.accepts(t.cost))
      throw InputError(
          fmt::format("{}: tolerances.{}.cost: {} is out of range for the allocation; accepted: "
                      "a relative cost weight from {}",
                      cfg.source, t.id, option_number_text(t.cost), kToleranceCostRange.text()));
  check_thread_count(o.threads, "threads");
  std::vector<std::string> units;
  for (const auto& id : cfg.identification.free_terms)
    units.push_back(coefficient_unit(cfg.instrument.output_unit, id, cfg.instrument.g_symbol));
  std::vector<AllocationTarget> targets;
  for (const auto& t : o.targets) targets.push_back(parse_allocation_target(t, cfg.identification.free_terms, units));
  return targets;  // at least one: the row's (a required list)
}

}  // namespace

AllocationDetail allocate_tolerances(const Config& cfg, const AllocateOptions& options) {
  check_options(options, option_table<AllocateOptions>());
  const std::vector<AllocationTarget> targets = checked_targets(cfg, options);
  AllocateOptions o = options;
  o.mode = options.mode.value_or(cfg.mode);
  const double kp = normal_coverage_factor(o.coverage_probability);

  BudgetOptions bo;
  bo.mode = o.mode;
  bo.compare_with_paper = false;
  BudgetDetail b;
  try {
    b = compute_budget(cfg, bo);
  } catch (const IllPosedFit& e) {
    throw plan_cannot_identify(e);
  }
  const auto nk = b.coefficients.size();

  AllocationDetail r;
  r.mode = *o.mode;
  r.coverage_probability = o.coverage_probability;
  r.coverage_factor = kp;
  r.max_scale = o.max_scale;
  for (std::size_t k = 0; k < nk; ++k) {
    AllocatedCoefficient c;
    c.id = b.coefficients[k];
    c.unit = b.units[k];
    c.display_scale = b.display_scale[k];
    r.coefficients.push_back(c);
  }
  attach_targets(b, targets, kp, r);
  Eigen::VectorXd noise_variance = Eigen::VectorXd::Zero(Eigen::Index(nk));
  for (const RateNoiseBudget& n : b.rate_noise) noise_variance += n.covariance.diagonal();
  const std::vector<double> tolerance_target = tolerance_targets(kp, noise_variance, r);
  r.let_others_grow = o.let_others_grow;
  AllocationProblem P;
  allocation_problem(cfg, b, tolerance_target, kp, o, P, r);
  const AllocationSolution sol = solve_allocation(P);
  if (std::find(sol.unreachable.begin(), sol.unreachable.end(), true) != sol.unreachable.end())
    refuse_unreachable(sol, noise_variance, kp, r);
  r.objective = sol.objective;
  r.configured_objective = P.cost.sum();
  r.common_scale = sol.common_scale;
  r.common_objective = sol.common_objective;
  r.iterations = sol.iterations;
  r.converged = sol.converged;
  r.method = sol.method;
  r.dual_gap = sol.dual_gap;
  Eigen::MatrixXd J;
  const Eigen::VectorXd u_alloc = report_coefficients(b, P, sol, noise_variance, kp, J, r);
  report_sources(cfg, b, sol, J, u_alloc, r);
  if (o.verify_trials == 0) return r;
  verify(cfg, sol, u_alloc, kp, o, r);
  return r;
}

}  // namespace ccal
