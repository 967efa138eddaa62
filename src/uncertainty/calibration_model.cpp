// The calibration experiment as a Monte Carlo model: draws of the tolerances → deviations of the identified
// coefficients (docs/model.md §10.2).
#include <fmt/format.h>

#include <stdexcept>

#include "calibration_cache.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal {

CalibrationModel calibration_model(const Experiment& experiment, const IdentificationSpec& spec,
                                   const std::vector<Tolerance>& sources,
                                   const Eigen::VectorXd& actual_errors, ModelMode mode) {
  const int size = experiment.layout.size();
  if (actual_errors.size() != size)
    throw InputError(fmt::format("calibration model: {} actual errors for a layout of {} parameters",
                                 actual_errors.size(), size));
  CalibrationModel m;
  m.experiment = experiment;
  m.spec = spec;
  m.actual_errors = actual_errors;
  m.mode = mode;
  const int runs = int(experiment.plan.runs.size());
  for (const Tolerance& t : sources) {
    // A negative parameter is a run's rate noise (rate_noise.hpp), added to that run's mean.
    const bool noise = t.parameter < 0 && rate_noise_run(t.parameter) < runs;
    if (!noise && (t.parameter < 0 || t.parameter >= size))
      throw InputError(
          fmt::format("calibration model: source '{}' has parameter index {}, outside the layout "
                      "(0…{})",
                      t.id, t.parameter, size - 1));
    m.parameters.push_back(t.parameter);
  }
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(size);
  {
    std::vector<TermSpec> terms = experiment.instrument.terms();
    int degree = 1;
    for (const auto& t : terms) degree = std::max(degree, t.kind == TermKind::power ? t.power : 2);
    const int band = 2 * (degree + experiment.layout.harmonic_order()) + 2;
    bool kink = false;
    for (const auto& t : terms) kink = kink || t.kind == TermKind::abs_square;
    if (!kink)
      m.reduction.quadrature.fast_nodes = std::max(8, band);  // even; 10 for a cubic with first harmonics
    // drift^Q/Q! ≤ 5e-6 keeps Q = 2 up to |ΔΩ|T ≈ 1.5e-3 (drift = 2|ΔΩ|T for M = 10); the bound overstates
    // the error relative to the swing (tests/reduction/run_average_test.cpp: below 1e-12 of the swing for 3σ draws).
    m.reduction.quadrature.slow_tolerance = 5e-6;
  }
  auto cache = std::make_shared<CalibrationTrialCache>();
  if (mode == ModelMode::exact && !m.reduction.chain.frozen_platform)
    cache->run_means =
        std::make_shared<const RunMeanKernel>(experiment.geometry, experiment.layout, experiment.site,
                                              experiment.plan.runs, experiment.instrument, m.reduction);
  if (mode == ModelMode::paper)
    for (const Run& run : experiment.plan.runs)
      cache->paper_nodes.push_back(detail::paper_run_nodes(experiment, run, {}));
  const Eigen::VectorXd known = spec.compensate ? actual_errors : zero;
  const Observations<double> model = observe<double>(experiment, zero, known, spec, mode, m.reduction);
  const auto nfree = Eigen::Index(spec.free_terms.size());
  const Eigen::MatrixXd H = model.regressors.leftCols(nfree);
  cache->design_pinv.resize(nfree, H.rows());
  for (Eigen::Index j = 0; j < H.rows(); ++j)
    cache->design_pinv.col(j) = solve_least_squares<double>(H, Eigen::VectorXd::Unit(H.rows(), j));
  cache->known_part = model.known_rate;
  Eigen::Index column = nfree;
  for (const auto& [id, value] : spec.fixed_terms) {
    (void)id;
    cache->known_part += model.regressors.col(column++) * value;
  }
  m.cache = std::move(cache);
  // The reference goes through the very arithmetic of a trial, so that zero draws on zero errors give
  // exactly zero deviations.
  m.reference = Eigen::VectorXd::Zero(nfree);
  std::vector<double> no_draws(m.parameters.size(), 0.0), out(std::size_t(nfree), 0.0);
  Eigen::VectorXd saved = m.actual_errors;
  m.actual_errors = zero;
  calibration_trial(m)(no_draws, out);
  m.actual_errors = saved;
  for (Eigen::Index k = 0; k < nfree; ++k) m.reference[k] = out[std::size_t(k)];
  return m;
}

TrialFunction calibration_trial(const CalibrationModel& model) {
  if (!model.cache)
    throw std::invalid_argument(
        "calibration_trial: the model was not built by calibration_model (no trial cache)");
  auto data = std::make_shared<const CalibrationModel>(model);
  return [data](std::span<const double> draws, std::span<double> outputs) {
    const CalibrationModel& m = *data;
    const CalibrationTrialCache& cache = *m.cache;
    const Experiment& ex = m.experiment;
    // Per-thread buffers: a trial allocates nothing once they have grown.
    thread_local Eigen::VectorXd truth, y;
    truth = m.actual_errors;
    bool noise = false;
    for (std::size_t j = 0; j < draws.size(); ++j) {
      if (m.parameters[j] < 0)
        noise = true;
      else
        truth[m.parameters[j]] += draws[j];
    }
    y.resize(Eigen::Index(ex.plan.runs.size()));
    if (cache.run_means) {
      cache.run_means->means(std::span<const double>(truth.data(), std::size_t(truth.size())),
                             std::span<double>(y.data(), std::size_t(y.size())));
    } else {
      for (std::size_t j = 0; j < ex.plan.runs.size(); ++j)
        y[Eigen::Index(j)] = m.mode == ModelMode::exact
                                 ? average_run<double>(ex.geometry, ex.layout, truth, ex.site,
                                                       ex.plan.runs[j], &ex.instrument, {}, m.reduction)
                                       .output
                                 : detail::paper_average<double>(ex, cache.paper_nodes[j], truth,
                                                                 &ex.instrument, {}, m.spec.paper_cross_terms)
                                       .output;
    }
    // The drives' rate noise scatters each run's mean (model.md §3.2).
    if (noise)
      for (std::size_t j = 0; j < draws.size(); ++j)
        if (m.parameters[j] < 0) y[rate_noise_run(m.parameters[j])] += draws[j];
    // K̂ = H⁺ (ȳ − known part): only the truth is reduced per trial.
    y -= cache.known_part;
    for (std::size_t o = 0; o < outputs.size(); ++o)
      outputs[o] = cache.design_pinv.row(Eigen::Index(o)).dot(y) - m.reference[Eigen::Index(o)];
  };
}

}  // namespace ccal
