// The calibration experiment as a Monte Carlo model: draws of the tolerances → deviations of the identified
// coefficients (docs/model.md §10.2).
#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "calibration_cache.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/chain_inputs.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "montecarlo_batch.hpp"

namespace ccal {

struct CalibrationModel::State {
  Experiment experiment;
  IdentificationSpec spec;
  Eigen::VectorXd actual_errors;
  std::vector<int> parameters;
  ModelMode mode = ModelMode::exact;
  Eigen::VectorXd reference;
  ReductionOptions reduction;
  CalibrationTrialCache cache;
};

const CalibrationModel::State& CalibrationModel::state() const {
  if (!state_)
    throw std::invalid_argument("CalibrationModel: an empty model (it is built by calibration_model)");
  return *state_;
}
const Experiment& CalibrationModel::experiment() const { return state().experiment; }
const IdentificationSpec& CalibrationModel::spec() const { return state().spec; }
const Eigen::VectorXd& CalibrationModel::actual_errors() const { return state().actual_errors; }
const std::vector<int>& CalibrationModel::parameters() const { return state().parameters; }
ModelMode CalibrationModel::mode() const { return state().mode; }
const Eigen::VectorXd& CalibrationModel::reference() const { return state().reference; }
const ReductionOptions& CalibrationModel::reduction() const { return state().reduction; }
const CalibrationTrialCache& CalibrationModel::trial_cache() const { return state().cache; }

namespace {

// A trial's buffers: grown once, then reused by every trial of the copy that owns them.
struct TrialScratch {
  Eigen::VectorXd truth, y;
  RunMeanKernel::Workspace run_means;
  std::vector<double> truths, means;  // a batch's: trial t's at t·layout size, t·runs
};

// The truth actual_errors + draws (the drawn errors of the layout's parameters) into truth.
void truth_of(const CalibrationModel& m, const Eigen::VectorXd& actual_errors, std::span<const double> draws,
              double* truth) {
  std::copy_n(actual_errors.data(), actual_errors.size(), truth);
  for (const auto& [j, p] : m.trial_cache().layout_draws) truth[p] += draws[j];
}

// K̂ − (the reference subtracted later) from the run means y of the truth: the drives' rate noise and the
// measuring chain's inputs added, then K̂ = H⁺ (ȳ − known part).
void terms_from_means(const CalibrationModel& m, std::span<const double> draws, Eigen::VectorXd& y,
                      std::span<double> outputs) {
  const CalibrationTrialCache& cache = m.trial_cache();
  // The drives' rate noise scatters each run's mean (model.md §3.2).
  for (const auto& [j, run] : cache.noise_draws) y[run] += draws[j];
  // The measuring chain's inputs through their columns: linear in the input, exactly so for the offset, the
  // fixed terms and the declared inputs; the gain's, the time base's and g's second-order terms are below
  // 1e-8 of a run mean's change at any plausible bound (1e-4).
  for (const std::size_t j : cache.chain_draws) y += cache.chain_columns.col(Eigen::Index(j)) * draws[j];
  // K̂ = H⁺ (ȳ − known part): only the truth is reduced per trial.
  y -= cache.known_part;
  for (std::size_t o = 0; o < outputs.size(); ++o) outputs[o] = cache.design_pinv.row(Eigen::Index(o)).dot(y);
}

// K̂ − (the reference subtracted later): the free terms identified from the run means of the truth
// actual_errors + draws.
void identified_terms(const CalibrationModel& m, const Eigen::VectorXd& actual_errors,
                      std::span<const double> draws, std::span<double> outputs, TrialScratch& scratch) {
  const CalibrationTrialCache& cache = m.trial_cache();
  const Experiment& ex = m.experiment();
  Eigen::VectorXd& truth = scratch.truth;
  Eigen::VectorXd& y = scratch.y;
  truth.resize(actual_errors.size());
  truth_of(m, actual_errors, draws, truth.data());
  y.resize(Eigen::Index(ex.plan.runs.size()));
  if (cache.run_means) {
    cache.run_means->means(std::span<const double>(truth.data(), std::size_t(truth.size())),
                           std::span<double>(y.data(), std::size_t(y.size())), scratch.run_means);
  } else {
    for (std::size_t j = 0; j < ex.plan.runs.size(); ++j)
      y[Eigen::Index(j)] = m.mode() == ModelMode::exact
                               ? average_run<double>(ex.geometry, ex.layout, truth, ex.site, ex.plan.runs[j],
                                                     &ex.instrument, {}, m.reduction())
                                     .output
                               : detail::paper_average<double>(ex, cache.paper_nodes[j], truth,
                                                               &ex.instrument, {}, m.spec().paper_cross_terms)
                                     .output;
  }
  terms_from_means(m, draws, y, outputs);
}

// The trial function of a model: one trial, or a batch whose truths' run means go through the kernel
// together (RunMeanKernel::means of many trials, each trial's bits those it has alone).
class CalibrationTrial final : public mc_batch::BatchTrial {
 public:
  explicit CalibrationTrial(CalibrationModel model) : model_(std::move(model)) {}
  std::unique_ptr<mc_batch::BatchTrial> fresh_copy() const override {
    return std::make_unique<CalibrationTrial>(model_);
  }
  void one(std::span<const double> draws, std::span<double> outputs) override {
    check_sizes(draws.size(), outputs.size(), 1);
    const Eigen::VectorXd& reference = model_.reference();
    identified_terms(model_, model_.actual_errors(), draws, outputs, scratch_);
    for (std::size_t o = 0; o < outputs.size(); ++o) outputs[o] -= reference[Eigen::Index(o)];
  }
  void many(std::span<const double> draws, std::size_t trials, std::span<double> outputs) override {
    check_sizes(draws.size(), outputs.size(), trials);
    const std::size_t n_sources = model_.parameters().size(), n_out = std::size_t(model_.n_outputs());
    const CalibrationTrialCache& cache = model_.trial_cache();
    if (!cache.run_means) {
      for (std::size_t t = 0; t < trials; ++t)
        one(draws.subspan(t * n_sources, n_sources), outputs.subspan(t * n_out, n_out));
      return;
    }
    const Eigen::VectorXd& actual = model_.actual_errors();
    const auto L = std::size_t(actual.size()), R = model_.experiment().plan.runs.size();
    scratch_.truths.resize(trials * L);
    scratch_.means.resize(trials * R);
    for (std::size_t t = 0; t < trials; ++t)
      truth_of(model_, actual, draws.subspan(t * n_sources, n_sources), scratch_.truths.data() + t * L);
    cache.run_means->means(scratch_.truths, trials, scratch_.means, scratch_.run_means);
    const Eigen::VectorXd& reference = model_.reference();
    for (std::size_t t = 0; t < trials; ++t) {
      scratch_.y = Eigen::Map<const Eigen::VectorXd>(scratch_.means.data() + t * R, Eigen::Index(R));
      const std::span<double> out = outputs.subspan(t * n_out, n_out);
      terms_from_means(model_, draws.subspan(t * n_sources, n_sources), scratch_.y, out);
      for (std::size_t o = 0; o < n_out; ++o) out[o] -= reference[Eigen::Index(o)];
    }
  }

 private:
  // A draw for every source of the model (its tolerances, then each run's rate noise) and an output for every
  // free term, per trial: the sources are read by their index, so a shorter draw vector would be read past
  // its end.
  void check_sizes(std::size_t draws, std::size_t outputs, std::size_t trials) const {
    const std::size_t n_sources = model_.parameters().size(), n_out = std::size_t(model_.n_outputs());
    if (draws != trials * n_sources || outputs != trials * n_out)
      throw std::invalid_argument(fmt::format(
          "calibration trial: {} draws and {} outputs for {} trial(s); the model takes {} draws (one per source) "
          "and gives {} outputs a trial",
          draws, outputs, trials, n_sources, n_out));
  }

  CalibrationModel model_;  // its state shared and only read
  TrialScratch scratch_;    // this copy's own
};

}  // namespace

namespace {

// The model's parameter per source: a layout index, a run's rate noise (negative, rate_noise.hpp) or an input
// of the measuring chain; anything else is refused.
std::vector<int> source_parameters(const std::vector<Tolerance>& sources, int runs, int size) {
  std::vector<int> parameters;
  for (const Tolerance& t : sources) {
    // A negative parameter is a run's rate noise (rate_noise.hpp), added to that run's mean.
    const bool noise = t.parameter < 0 && rate_noise_run(t.parameter) < runs;
    const bool chain = is_chain_parameter(t.parameter);
    if (!noise && !chain && (t.parameter < 0 || t.parameter >= size))
      throw InputError(
          fmt::format("calibration model: source '{}' has parameter index {}, outside the layout "
                      "(0…{})",
                      t.id, t.parameter, size - 1));
    parameters.push_back(t.parameter);
  }
  return parameters;
}

// The trial's run-mean rule: fast nodes enough for the instrument's degree and the layout's harmonics (a kink,
// |a_i| a_i, keeps the default), slow nodes to 5e-6 of the drift.
void trial_quadrature(const Experiment& experiment, QuadratureOptions& quadrature) {
  std::vector<TermSpec> terms = experiment.instrument.terms();
  int degree = 1;
  for (const auto& t : terms) degree = std::max(degree, t.kind == TermKind::power ? t.power : 2);
  const int band = 2 * (degree + experiment.layout.harmonic_order()) + 2;
  bool kink = false;
  for (const auto& t : terms) kink = kink || t.kind == TermKind::abs_square;
  if (!kink) quadrature.fast_nodes = std::max(8, band);  // even; 10 for a cubic with first harmonics
  // drift^Q/Q! ≤ 5e-6 keeps Q = 2 up to |ΔΩ|T ≈ 1.5e-3 (drift = 2|ΔΩ|T for M = 10); the bound overstates
  // the error relative to the swing (tests/reduction/run_average_test.cpp: below 1e-12 of the swing for 3σ draws).
  quadrature.slow_tolerance = 5e-6;
}

// What each source's draw is, sorted once per model: an input of the measuring chain, a run's rate noise (and
// its run) or an error of the layout (and its index).
void sort_draw_roles(const std::vector<int>& parameters, CalibrationTrialCache& cache) {
  for (std::size_t j = 0; j < parameters.size(); ++j) {
    const int p = parameters[j];
    if (is_chain_parameter(p))
      cache.chain_draws.push_back(j);
    else if (p < 0)
      cache.noise_draws.emplace_back(j, Eigen::Index(rate_noise_run(p)));
    else
      cache.layout_draws.emplace_back(j, Eigen::Index(p));
  }
}

// The measuring chain's inputs' columns of the run means (runs × sources, zero for every other source).
void chain_columns_of(const Experiment& experiment, const IdentificationSpec& spec,
                      const std::vector<int>& parameters, const Eigen::VectorXd& actual_errors, ModelMode mode,
                      const ReductionOptions& reduction, CalibrationTrialCache& cache) {
  std::vector<int> chain_parameters;
  for (int p : parameters)
    if (is_chain_parameter(p)) chain_parameters.push_back(p);
  if (chain_parameters.empty()) return;
  const Eigen::MatrixXd columns =
      chain_output_columns(experiment, spec, chain_parameters, actual_errors, mode, reduction);
  cache.chain_columns =
      Eigen::MatrixXd::Zero(Eigen::Index(experiment.plan.runs.size()), Eigen::Index(parameters.size()));
  for (std::size_t s = 0, c = 0; s < parameters.size(); ++s)
    if (is_chain_parameter(parameters[s])) cache.chain_columns.col(Eigen::Index(s)) = columns.col(Eigen::Index(c++));
  cache.any_chain = true;
}

}  // namespace

CalibrationModel calibration_model(const Experiment& experiment, const IdentificationSpec& spec,
                                   const std::vector<Tolerance>& sources,
                                   const Eigen::VectorXd& actual_errors, ModelMode mode) {
  const int size = experiment.layout.size();
  if (actual_errors.size() != size)
    throw InputError(fmt::format("calibration model: {} actual errors for a layout of {} parameters",
                                 actual_errors.size(), size));
  auto state = std::make_shared<CalibrationModel::State>();
  CalibrationModel::State& m = *state;
  m.experiment = experiment;
  m.spec = spec;
  m.actual_errors = actual_errors;
  m.mode = mode;
  m.parameters = source_parameters(sources, int(experiment.plan.runs.size()), size);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(size);
  trial_quadrature(experiment, m.reduction.quadrature);
  CalibrationTrialCache& cache = m.cache;
  sort_draw_roles(m.parameters, cache);
  if (mode == ModelMode::exact && !m.reduction.chain.frozen_platform)
    cache.run_means =
        std::make_shared<const RunMeanKernel>(experiment.geometry, experiment.layout, experiment.site,
                                              experiment.plan.runs, experiment.instrument, m.reduction);
  if (mode == ModelMode::paper)
    for (const Run& run : experiment.plan.runs)
      cache.paper_nodes.push_back(detail::paper_run_nodes(experiment, run, {}));
  chain_columns_of(experiment, spec, m.parameters, actual_errors, mode, m.reduction, cache);
  const Eigen::VectorXd known = spec.compensate ? actual_errors : zero;
  const Observations<double> model = observe<double>(experiment, zero, known, spec, mode, m.reduction);
  const auto nfree = Eigen::Index(spec.free_terms.size());
  const Eigen::MatrixXd H = model.regressors.leftCols(nfree);
  cache.design_pinv.resize(nfree, H.rows());
  for (Eigen::Index j = 0; j < H.rows(); ++j)
    cache.design_pinv.col(j) = solve_least_squares<double>(H, Eigen::VectorXd::Unit(H.rows(), j));
  cache.known_part = model.known_rate;
  Eigen::Index column = nfree;
  for (const auto& [id, value] : spec.fixed_terms) {
    (void)id;
    cache.known_part += model.regressors.col(column++) * value;
  }
  // The reference goes through the very arithmetic of a trial, so that zero draws on zero errors give
  // exactly zero deviations.
  CalibrationModel result;
  result.state_ = state;
  m.reference = Eigen::VectorXd::Zero(nfree);
  const std::vector<double> no_draws(m.parameters.size(), 0.0);
  TrialScratch scratch;
  identified_terms(result, zero, no_draws, std::span<double>(m.reference.data(), std::size_t(nfree)), scratch);
  return result;
}

TrialFunction calibration_trial(const CalibrationModel& model) {
  if (model.empty())
    throw std::invalid_argument(
        "calibration_trial: the model was not built by calibration_model (no trial cache)");
  // The model's state is shared and only read; the scratch is the copy's own (copied empty per thread).
  return mc_batch::BatchCallable(std::make_unique<CalibrationTrial>(model));
}

}  // namespace ccal
