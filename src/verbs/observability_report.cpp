#include "ccal/verbs/observability_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "ccal/core/errors.hpp"
#include "ccal/core/format.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/reduction/fit.hpp"
#include "ccal/uncertainty/budget.hpp"

namespace ccal::verbs {
namespace {

using Index = Eigen::Index;

// Raises the refusal of the first unobservable term and collects the warnings of the weak ones.
void judge(ObservabilityReport& report, std::string_view source) {
  if (const TermObservability* t = report.result.first(TermStatus::unobservable))
    throw InputError(fmt::format("{}: {}", source, unobservable_message(*t)));
  for (std::size_t k = 0; k < report.result.terms.size(); ++k) {
    const TermObservability& t = report.result.terms[k];
    if (t.status != TermStatus::weak) continue;
    report.warnings.push_back(fmt::format(
        "{} is weak: the smallest change the plan can detect is {} {} ({:g} sigma), more than the "
        "coefficient; "
        "{}",
        t.term, number(t.min_detectable, 3), report.units[k], report.result.detection_factor, t.fix));
  }
}

}  // namespace

DataResolution run_resolution(const std::vector<Run>& runs, const std::vector<double>& rates,
                              const Observations<double>& obs, const IdentificationSpec& spec,
                              const InstrumentModel& instrument) {
  const double unit = output_unit_si(instrument.output_unit);
  const ObservabilityProblem p = observability_problem(obs, spec, instrument, runs, rates);
  DataResolution d;
  d.noise_density = p.noise_density / unit;
  d.quantum = p.quantum / unit;
  d.runs = p.runs;
  for (auto& r : d.runs) r.output_magnitude /= unit;
  return d;
}

ObservabilityReport assess_fit(const FitProblem& problem, const FitResult& fit,
                               const std::vector<std::string>& units, const DataResolution* resolution,
                               std::string_view source) {
  ObservabilityProblem p;
  p.terms = fit.names;
  const Index rows = problem.H.rows();
  p.H.resize(rows, static_cast<Index>(fit.names.size()));
  Eigen::VectorXd known = problem.y;  // what the run means were, for their floating-point resolution
  for (std::size_t k = 0, free = 0; k < problem.term_names.size(); ++k) {
    const auto col = static_cast<Index>(k);
    const auto fixed = problem.fixed.find(problem.term_names[k]);
    if (fixed == problem.fixed.end()) {
      p.H.col(static_cast<Index>(free++)) = problem.H.col(col);
    } else {
      p.other_terms.push_back(problem.term_names[k]);
      p.others.conservativeResize(rows, p.others.cols() + 1);
      p.others.col(p.others.cols() - 1) = problem.H.col(col);
    }
  }
  p.reference = fit.value;
  ObservabilityReport report;
  report.units = units;
  if (resolution) {
    p.runs = resolution->runs;
    p.noise_density = resolution->noise_density;
    p.quantum = resolution->quantum;
    report.basis = "instrument noise and quantum over each run's duration, floating point";
  } else {
    const bool weighted = problem.weights.size() != 0;
    for (Index j = 0; j < rows; ++j) {
      RunResolutionInfo info;
      // |y| plus every fitted and fixed contribution: the values the run mean was made of.
      double m = std::abs(known(j));
      for (std::size_t k = 0; k < problem.term_names.size(); ++k) {
        const auto fixed = problem.fixed.find(problem.term_names[k]);
        double value = 0;
        if (fixed != problem.fixed.end()) {
          value = fixed->second;
        } else {
          for (std::size_t f = 0; f < fit.names.size(); ++f)
            if (fit.names[f] == problem.term_names[k]) value = fit.value[static_cast<Index>(f)];
        }
        m += std::abs(value * problem.H(j, static_cast<Index>(k)));
      }
      info.output_magnitude = m;
      info.extra_sigma = weighted ? 1.0 / std::sqrt(problem.weights(j)) : fit.residual_std;
      p.runs.push_back(info);
    }
    report.basis = weighted ? "the sigma column, floating point"
                            : "the fit's residual standard deviation, floating point";
  }
  report.result = assess_observability(p);
  if (!resolution)  // a table: neither runs nor an instrument to improve
    for (auto& t : report.result.terms)
      if (t.status == TermStatus::weak)
        t.fix = "more rows, a wider spread of the input or less scattered data";
  judge(report, source);
  return report;
}

ObservabilityReport assess_plan(const Config& config, ModelMode mode) {
  const Experiment ex = config.experiment();
  const IdentificationSpec& spec = config.identification;
  const Eigen::VectorXd& at = config.centrifuge.errors;
  const Eigen::VectorXd known = spec.compensate ? at : Eigen::VectorXd::Zero(at.size());
  const Observations<double> obs = observe<double>(ex, at, known, spec, mode);
  const FitProblem problem = fit_problem(obs, spec);
  try {
    static_cast<void>(fit(problem));  // dependent or nearly dependent terms: the fit's own message
  } catch (const IllPosedFit& e) {
    throw plan_cannot_identify(e);
  }
  const double unit = output_unit_si(config.instrument.output_unit);
  std::vector<double> rates;
  for (const Run& run : config.plan.runs) rates.push_back(nominal_rate(run, ex.geometry, ex.site));
  // In the output unit, as the other commands' tables.
  ObservabilityProblem p = observability_problem(obs, spec, ex.instrument, config.plan.runs, rates);
  p.noise_density /= unit;
  p.quantum /= unit;
  for (auto& r : p.runs) r.output_magnitude /= unit;
  const auto nfree = static_cast<Index>(spec.free_terms.size());
  p.reference = Eigen::VectorXd::Zero(nfree);
  for (Index k = 0; k < nfree; ++k)
    p.reference(k) =
        config.instrument.coefficient(spec.free_terms[static_cast<std::size_t>(k)]).value_or(0.0) / unit;
  ObservabilityReport report;
  for (const auto& id : spec.free_terms)
    report.units.push_back(coefficient_unit(config.instrument.output_unit, id, config.instrument.g_symbol));
  report.basis = "instrument noise and quantum over each run's duration, floating point";
  report.result = assess_observability(p);
  judge(report, config.source);
  return report;
}

}  // namespace ccal::verbs
