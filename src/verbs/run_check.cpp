#include "run_check.hpp"

#include <fmt/format.h>

#include <cmath>

#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"
#include "ccal/reduction/observe.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/reduce.hpp"
#include "statement_type_a.hpp"

namespace ccal::verbs {

std::vector<RunCheck> check_runs(const Config& cfg, const LogReduction& logs, ModelMode mode) {
  const double unit = output_unit_si(cfg.instrument.output_unit);
  const std::size_t n = cfg.plan.runs.size();
  std::vector<RunCheck> checks(n);
  std::vector<std::size_t> rows(n);
  std::vector<double> durations(n);
  for (std::size_t j = 0; j < n; ++j) {
    rows[j] = checks[j].index = j;
    durations[j] = cfg.plan.runs[j].duration;
  }
  for (std::size_t k = 0; k < logs.runs.size(); ++k) {
    RunCheck& c = checks[logs.runs[k].index];
    c.logged = true;
    c.mean = logs.observations.output[Eigen::Index(k)] / unit;
    durations[c.index] = logs.runs[k].log.duration;
  }
  // The instrument's nominal reading: the plan's runs through the chain with the known [errors] (those the
  // lab measured are in the machine whether or not the model compensates them).
  const Experiment ex = cfg.experiment();
  const Eigen::VectorXd& errors = cfg.centrifuge.errors;
  const Eigen::VectorXd nominal = observe<double>(ex, errors, errors, cfg.identification, mode).output / unit;
  ccal::BudgetDetail budget;  // empty: the noise alone
  try {
    BudgetOptions bo;
    bo.mode = mode;
    bo.compare_with_paper = false;
    budget = verbs::budget(cfg, bo).budget;
  } catch (const InputError&) {
  }
  const Eigen::VectorXd noise = run_noise(cfg, budget, rows, durations, unit);
  const Eigen::MatrixXd effects = run_effects(cfg, budget, rows, unit);
  for (std::size_t j = 0; j < n; ++j) {
    RunCheck& c = checks[j];
    c.nominal = nominal[Eigen::Index(j)];
    c.u = std::sqrt(noise[Eigen::Index(j)] * noise[Eigen::Index(j)] + effects.row(Eigen::Index(j)).squaredNorm());
    c.beyond = c.logged && c.u > 0 && !(std::abs(c.mean - c.nominal) <= kRunCheckLimit * c.u);
  }
  return checks;
}

std::string run_check_finding(const Config& cfg, const std::vector<RunCheck>& checks, const RunCheck& c) {
  const std::string& unit = cfg.instrument.output_unit;
  std::string other;
  double closest = kRunCheckLimit;
  for (const RunCheck& x : checks)
    if (x.index != c.index && x.u > 0 && std::abs(c.mean - x.nominal) / x.u <= closest) {
      closest = std::abs(c.mean - x.nominal) / x.u;
      other = fmt::format("; it is what run '{}' reads: a log of that run (swapped, or named for the wrong run?)",
                          cfg.plan.runs[x.index].name);
    }
  return fmt::format(
      "run '{}': the log's mean {:.7g} {} is {:.3g} u from the {:.7g} {} the nominal instrument reads at this run "
      "(u = {:.2g} {}: noise and tolerances; within {:g} u expected){}",
      cfg.plan.runs[c.index].name, c.mean, unit, std::abs(c.mean - c.nominal) / c.u, c.nominal, unit, c.u, unit,
      kRunCheckLimit, other.empty() ? "; check that it is this run's log and the [instrument.terms]" : other);
}

}  // namespace ccal::verbs
