#include "statement_montecarlo.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <memory>

#include "../uncertainty/draw_quantiles.hpp"
#include "../uncertainty/montecarlo_batch.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/uncertainty/gaussian_copula.hpp"

namespace ccal::verbs {
namespace {

// What every copy of the trial reads (never written after it is built).
struct StatementTrialShared {
  std::size_t n_tolerances = 0;
  std::vector<Eigen::Index> model_index;  // per coefficient of the fit: its output of the calibration model
  Eigen::VectorXd to_fit;                 // SI → the fit's unit, per coefficient
  Eigen::VectorXd corrected;              // K̂ + b
  Eigen::VectorXd estimate;               // K̂
  Eigen::VectorXd reference;              // the calibration model's outputs at zero draws (SI)
  Eigen::MatrixXd known_root;             // L_N, L_N L_Nᵀ the noise model's Type A covariance (normal)
  Eigen::MatrixXd estimated_root;         // L_E, L_E L_Eᵀ the Type A part estimated from the residuals
  double type_a_dof = kInfiniteDof;       // its ν; ∞: normal too
  Eigen::MatrixXd design;                 // h of each run (rows), the fit's regressors of the free terms
  Eigen::VectorXd modelled;               // ŷ of each run, hᵀK̂ plus the fixed terms' part
};

// L with L Lᵀ = C for a covariance that may be singular: V √Λ from its eigen-decomposition, negative
// eigenvalues of round-off set to 0.
Eigen::MatrixXd covariance_root(const Eigen::MatrixXd& c) {
  if (c.size() == 0) return c;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (c + c.transpose()));
  return eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
}

// χ²_ν of an integer ν ≥ 1 (the fit's n − p) from ⌊ν/2⌋ uniforms and, for an odd ν, one standard normal.
int chi_squared_uniforms(double dof) { return int(dof) / 2; }
bool chi_squared_odd(double dof) { return int(dof) % 2 == 1; }

// χ²_ν = −2 ln(u_1 ⋯ u_k) + z² from the draws of those sources (uniforms on (−1, 1): u = (x + 1)/2, in (0, 1),
// never an end). The uniforms are multiplied in runs of 16, each product at least 2⁻⁸⁴⁸ (every u ≥ 2⁻⁵³), so
// that the product never underflows: one logarithm per 16 uniforms, by IEEE operations alone (draw_quantiles.hpp:
// the C library's log takes other code on a processor with fused multiply-add).
double chi_squared_of(const double* draws, int uniforms, bool odd) {
  double sum = 0;
  for (int k = 0; k < uniforms; k += 16) {
    double product = 1;
    for (int j = k; j < std::min(uniforms, k + 16); ++j) product *= 0.5 * (draws[j] + 1);
    sum -= 2 * ccal::draws::log_positive(product);
  }
  if (odd) sum += draws[uniforms] * draws[uniforms];
  return sum;
}

// The sources of the Monte Carlo: the configuration's tolerances (not the drives' rate noise: the Type A part
// holds it), then two standard normals per coefficient (the known and the estimated Type A parts) and, for a
// finite ν, the multivariate t's χ²_ν as a sum of ν/2 exponentials (each −2 ln u, u uniform: χ² of 2 degrees of
// freedom) and, for an odd ν, the square of one more standard normal: ⌊ν/2⌋ uniforms on (−1, 1) and one normal.
std::vector<Tolerance> statement_sources(const Config& config, const Identification& id, double dof) {
  std::vector<Tolerance> sources = config.tolerances;
  const auto add = [&sources](std::string name, Distribution d) {
    Tolerance t;
    t.id = std::move(name);
    t.bound = 1;
    t.distribution = d;
    sources.push_back(t);
  };
  for (const char* part : {"type_a_", "type_a_estimated_"})
    for (const std::string& name : id.fit.names) add(part + name, Distribution::normal);
  if (std::isfinite(dof)) {
    for (int k = 0; k < chi_squared_uniforms(dof); ++k)
      add(fmt::format("type_a_chi_squared_{}", k + 1), Distribution::uniform);
    if (chi_squared_odd(dof)) add("type_a_chi_squared_normal", Distribution::normal);
  }
  return sources;
}

// One trial: y = K̂ + b − C (f(e) − f(0)) + s L z, C the unit factors, f the calibration model at the drawn
// tolerances e, z standard normal, s = √(ν/χ²_ν) (1 for ν = ∞); then each run's ŷ + hᵀ(y − K̂). A batch of
// trials evaluates f of all of them in one call of the calibration model's batch (montecarlo_batch.hpp), each
// trial's bits those it has alone.
class StatementTrial final : public mc_batch::BatchTrial {
 public:
  StatementTrial(std::shared_ptr<const StatementTrialShared> shared, TrialFunction tolerances, int n_model)
      : shared_(std::move(shared)), tolerances_(std::move(tolerances)), f_(std::size_t(n_model)) {}
  std::unique_ptr<mc_batch::BatchTrial> fresh_copy() const override {
    return std::make_unique<StatementTrial>(shared_, tolerances_,
                                            int(f_.size()));  // tolerances_ copied fresh
  }

  void one(std::span<const double> draws, std::span<double> outputs) override {
    tolerances_(draws.first(shared_->n_tolerances), f_);
    finish(draws, f_, outputs);
  }
  void many(std::span<const double> draws, std::size_t trials, std::span<double> outputs) override {
    mc_batch::BatchCallable* batch = tolerances_.target<mc_batch::BatchCallable>();
    const std::size_t n_sources = draws.size() / std::max<std::size_t>(trials, 1),
                      n_out = outputs.size() / std::max<std::size_t>(trials, 1), n_model = f_.size(),
                      n_tolerances = shared_->n_tolerances;
    if (!batch) {
      for (std::size_t t = 0; t < trials; ++t)
        one(draws.subspan(t * n_sources, n_sources), outputs.subspan(t * n_out, n_out));
      return;
    }
    tolerance_draws_.resize(trials * n_tolerances);
    f_batch_.resize(trials * n_model);
    for (std::size_t t = 0; t < trials; ++t)
      std::copy_n(draws.data() + t * n_sources, n_tolerances, tolerance_draws_.data() + t * n_tolerances);
    batch->trial().many(tolerance_draws_, trials, f_batch_);
    for (std::size_t t = 0; t < trials; ++t)
      finish(draws.subspan(t * n_sources, n_sources),
             std::span<const double>(f_batch_.data() + t * n_model, n_model),
             outputs.subspan(t * n_out, n_out));
  }

 private:
  // The trial's outputs from its draws and f at its tolerances.
  void finish(std::span<const double> draws, std::span<const double> f, std::span<double> outputs) {
    const StatementTrialShared& s = *shared_;
    const auto nk = s.corrected.size();
    const Eigen::Map<const Eigen::VectorXd> z_known(draws.data() + s.n_tolerances, nk);
    const Eigen::Map<const Eigen::VectorXd> z_estimated(draws.data() + s.n_tolerances + std::size_t(nk), nk);
    double scale = 1;
    if (std::isfinite(s.type_a_dof)) {
      // χ² = 0 only at the engine's call with every draw zero (ν = 1: z = 0; a drawn normal is never 0), where
      // the t part is its expectation, 0, whatever the scale.
      const double chi_squared = chi_squared_of(draws.data() + s.n_tolerances + 2 * std::size_t(nk),
                                                chi_squared_uniforms(s.type_a_dof), chi_squared_odd(s.type_a_dof));
      if (chi_squared > 0) scale = std::sqrt(s.type_a_dof / chi_squared);
    }
    // Into the trial's own vectors (no allocation per trial).
    y_.noalias() = s.known_root * z_known;
    shift_.noalias() = s.estimated_root * z_estimated;
    y_ += s.corrected + scale * shift_;
    for (Eigen::Index k = 0; k < nk; ++k) {
      const auto m = s.model_index[std::size_t(k)];
      y_[k] -= s.to_fit[k] * (f[std::size_t(m)] - s.reference[m]);
    }
    for (Eigen::Index k = 0; k < nk; ++k) outputs[std::size_t(k)] = y_[k];
    shift_ = y_ - s.estimate;
    for (Eigen::Index r = 0; r < s.design.rows(); ++r)
      outputs[std::size_t(nk + r)] = s.modelled[r] + s.design.row(r).dot(shift_);
  }

  std::shared_ptr<const StatementTrialShared> shared_;
  TrialFunction tolerances_;
  std::vector<double> f_, tolerance_draws_, f_batch_;
  Eigen::VectorXd y_, shift_;
};

// What every trial of the statement's check shares: the fit's terms in the model's outputs, the factors to
// the fit's units, the corrected estimates, the model at zero draws, the roots of the Type A covariances
// (known and estimated, the latter's ν) and the fit's design.
std::shared_ptr<StatementTrialShared> statement_trial_shared(const Config& config, const Identification& id,
                                                             const std::vector<double>& to_fit,
                                                             const TypeAParts& type_a,
                                                             const std::vector<std::string>& model_names,
                                                             const TrialFunction& tolerances,
                                                             const CalibrationStatement& st) {
  const auto nk = Eigen::Index(id.fit.names.size());
  auto shared = std::make_shared<StatementTrialShared>();
  shared->n_tolerances = config.tolerances.size();
  shared->to_fit = Eigen::Map<const Eigen::VectorXd>(to_fit.data(), Eigen::Index(to_fit.size()));
  shared->corrected.resize(nk);
  for (Eigen::Index k = 0; k < nk; ++k) {
    const auto found = std::find(model_names.begin(), model_names.end(), id.fit.names[std::size_t(k)]);
    shared->model_index.push_back(Eigen::Index(found - model_names.begin()));
    shared->corrected[k] = st.coefficients[std::size_t(k)].corrected;
  }
  shared->estimate = id.fit.value;
  std::vector<double> reference(model_names.size());
  tolerances(std::vector<double>(config.tolerances.size(), 0.0), reference);
  shared->reference = Eigen::Map<const Eigen::VectorXd>(reference.data(), Eigen::Index(reference.size()));
  shared->known_root = covariance_root(type_a.known);
  shared->estimated_root = covariance_root(type_a.estimated);
  const bool estimated = type_a.estimated.size() > 0 && type_a.estimated.cwiseAbs().maxCoeff() > 0;
  shared->type_a_dof = estimated ? type_a.dof : kInfiniteDof;
  shared->design = id.design;
  shared->modelled = id.modelled;
  return shared;
}

}  // namespace

void check_statement_by_monte_carlo(const Config& config, const Identification& id,
                                    const std::vector<double>& to_fit, const TypeAParts& type_a,
                                    const StatementOptions& o, CalibrationStatement& st) {
  if (o.trials() <= 0 || config.tolerances.empty()) return;
  gaussian_copula(config);  // a pair the copula cannot draw, refused with its place in the file
  const CalibrationModel model = calibration_model(config.experiment(), config.identification,
                                                   config.tolerances, config.centrifuge.errors, st.mode);
  TrialFunction tolerances = calibration_trial(model);
  const std::vector<std::string> model_names = model.output_names();
  const auto shared = statement_trial_shared(config, id, to_fit, type_a, model_names, tolerances, st);

  std::vector<std::string> names = id.fit.names;
  for (const CoefficientStatement& out : st.outputs) names.push_back("run " + out.input.coefficient);
  ccal::PropagationOptions mo;
  mo.seed = o.seed.value_or(kDefaultSeed);
  mo.threads = o.threads.value_or(0);
  mo.coverage_probability = st.coverage_probability;
  const std::vector<Tolerance> sources = statement_sources(config, id, shared->type_a_dof);
  const TrialFunction trial = mc_batch::BatchCallable(
      std::make_unique<StatementTrial>(shared, std::move(tolerances), int(model_names.size())));
  // Adaptive in its verdict (JCGM 101 §7.9): while a quantity's check is within the sampling error of its ends
  // and the M its diagnosis names is within kStatementTrialsCap times the requested, M grows to that M (at least
  // doubled, at most the cap); a verdict that needs more than the cap stays unsettled without the cost. Trial
  // i's draws depend only on (seed, i), so M' trials extend the M before them, bit for bit: each run takes the
  // values of the one before (kept while another may follow) and evaluates only its new trials.
  const auto requested = std::uint64_t(o.trials());
  const std::uint64_t cap = std::min(kStatementTrialsCap * requested, std::uint64_t(kMaxMonteCarloTrials));
  ccal::MonteCarloDetail mc;
  Eigen::MatrixXd earlier;
  for (std::uint64_t trials = requested;;) {
    mo.trials = trials;
    mo.keep_samples = trials < cap;
    mo.earlier_samples = earlier.size() > 0 ? &earlier : nullptr;
    mc = run_monte_carlo(sources, config.correlations, int(names.size()), names, trial, mo);
    earlier = std::move(mc.samples);
    std::uint64_t wanted = 0;  // the most trials a verdict needs, of those the cap allows
    bool settled = true;
    const auto need = [&](const CoefficientStatement& q, const OutputSummary& m) {
      const std::uint64_t n = trials_to_settle(q, m, mc.trials);
      settled = settled && n == 0;
      if (n <= cap) wanted = std::max(wanted, n);
    };
    for (std::size_t k = 0; k < st.coefficients.size(); ++k) need(st.coefficients[k], mc.outputs[k]);
    for (std::size_t r = 0; r < st.outputs.size(); ++r)
      need(st.outputs[r], mc.outputs[st.coefficients.size() + r]);
    st.monte_carlo_settled = settled;
    if (wanted == 0 || trials >= cap) break;
    trials = std::min(cap, std::max(2 * trials, wanted));
  }
  st.monte_carlo_requested_trials = requested;
  st.monte_carlo_trials = mc.trials;
  st.monte_carlo_seed = mc.seed;
  for (std::size_t k = 0; k < st.coefficients.size(); ++k)
    check_by_monte_carlo(st.coefficients[k], mc.outputs[k], mc.trials);
  for (std::size_t r = 0; r < st.outputs.size(); ++r)
    check_by_monte_carlo(st.outputs[r], mc.outputs[st.coefficients.size() + r], mc.trials);
}

}  // namespace ccal::verbs
