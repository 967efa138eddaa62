#pragma once
// Simulation of a test plan and its reduction to observation equations (docs/model.md §8–9):
//   truth:  ᾱ_j = ⟨instrument output⟩ over run j, through the exact chain with the *true* centrifuge errors;
//   model:  the regressors Z_kj = ⟨term_k⟩ and the known rate term ⟨s_ω ω_IA⟩_j, through the exact chain with
//   the
//           errors the analyst *knows* (zero: uncompensated; measured values: compensated, the paper's
//           conclusion 3).
// Identification then solves ᾱ_j − ⟨s_ω ω_IA⟩_j − Σ_fixed K Z = Σ_free K Z in the least-squares sense.

#include <Eigen/Core>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/model/centrifuge.hpp"
#include "ccal/model/instrument.hpp"
#include "ccal/model/plan.hpp"
#include "ccal/model/site.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/reduction/run_average.hpp"
#include "ccal/setup/experiment.hpp"

namespace ccal {

// The paper's reduction of one run (docs/model.md §5.1, §7.1): the first-order form with the frozen-γ rules,
// phases on the nominal rate, Δω in the amplitude of every power term, pose errors and the constant Coriolis
// term in the K1 term only unless `cross_terms` (then the whole a_i in every term). Instantiated for double
// and Dual.
template <class S>
RunAverage<S> paper_average(const Experiment& ex, const VecX<S>& e, const ccal::Run& run,
                            const InstrumentModel* instrument, const std::vector<TermSpec>& terms,
                            bool cross_terms);

// Observations of every run, with the truth reduced through `ex` and the analyst's model through `model`
// (the same experiment, except perhaps for what the model compensates, e.g. its Site's Earth-rotation
// switches, or for what the simulated machine's measuring chain changes: its gravity, its runs' g-levels and
// durations, chain_inputs.hpp); run j of each is its own plan's run j. `truth` and `known` are error vectors indexed by ex.layout (SI).
template <class S>
Observations<S> observe(const Experiment& ex, const Experiment& model, const VecX<S>& truth,
                        const VecX<S>& known, const IdentificationSpec& spec,
                        ModelMode mode = ModelMode::exact, const ReductionOptions& options = {}) {
  Observations<S> obs;
  obs.columns = observation_columns(spec);
  std::vector<TermSpec> terms;
  for (const auto& id : obs.columns) terms.push_back(parse_term(id).value());
  const auto n = Eigen::Index(ex.plan.runs.size());
  obs.regressors.resize(n, Eigen::Index(terms.size()));
  obs.output.resize(n);
  obs.known_rate.resize(n);
  obs.input.resize(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const ccal::Run& run = ex.plan.runs[std::size_t(j)];
    const ccal::Run& model_run = model.plan.runs[std::size_t(j)];  // as the lab planned it (a truth's may differ)
    obs.runs.push_back(run.name);
    RunAverage<S> truth_avg, model_avg;
    if (mode == ModelMode::exact) {
      truth_avg = average_run<S>(ex.geometry, ex.layout, truth, ex.site, run, &ex.instrument, {}, options);
      model_avg = average_run<S>(model.geometry, model.layout, known, model.site, model_run, nullptr, terms,
                                 options);
    } else {
      truth_avg = paper_average<S>(ex, truth, run, &ex.instrument, {}, spec.paper_cross_terms);
      model_avg = paper_average<S>(model, known, model_run, nullptr, terms, spec.paper_cross_terms);
    }
    obs.output[j] = truth_avg.output;
    obs.regressors.row(j) = model_avg.regressors.transpose();
    obs.known_rate[j] = S(ex.instrument.rate_gain) * model_avg.rate_ia;
    obs.input[j] = model_avg.input[0];
  }
  return obs;
}

template <class S>
Observations<S> observe(const Experiment& ex, const VecX<S>& truth, const VecX<S>& known,
                        const IdentificationSpec& spec, ModelMode mode = ModelMode::exact,
                        const ReductionOptions& options = {}) {
  return observe<S>(ex, ex, truth, known, spec, mode, options);
}

// Adds measurement noise to simulated run means: white noise of density N gives a mean with σ = N/√T; a
// quantised integrated output (step q, e.g. a PIGA pulse weight) counts whole steps, so the mean is off by a
// uniform error of width q/T. Seeded: the same seed gives the same noise.
void add_output_noise(Observations<double>& obs, const Experiment& ex, std::uint64_t seed);

// The least-squares problem of a set of observations (output SI, regressors) under a spec.
FitProblem fit_problem(const Observations<double>& obs, const IdentificationSpec& spec);

// Identified free coefficients as a differentiable function of the observations: the design from the model
// means is treated as data (QR of the column-scaled design), the outputs may carry derivatives.
template <class S>
VecX<S> identify_coefficients(const Observations<S>& obs, const IdentificationSpec& spec) {
  const Eigen::Index n = obs.output.size();
  const auto nfree = Eigen::Index(spec.free_terms.size());
  Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic> H = obs.regressors.leftCols(nfree);
  VecX<S> y = obs.output - obs.known_rate;
  Eigen::Index k = nfree;
  for (const auto& [id, value] : spec.fixed_terms) {
    (void)id;
    y -= obs.regressors.col(k++) * S(value);
  }
  (void)n;
  return solve_least_squares<S>(H, y);
}

}  // namespace ccal
