#include "ccal/verbs/instrument_covariance.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "ccal/core/errors.hpp"
#include "ccal/model/error_sources.hpp"
#include "ccal/setup/measuring_chain.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal::verbs {

bool instrument_own_input(int parameter) noexcept {
  if (is_chain_parameter(parameter)) {
    const ChainKind kind = chain_input(parameter).kind;
    return kind == ChainKind::fixed_term || kind == ChainKind::output_gain || kind == ChainKind::output_offset;
  }
  return parameter >= 0 && parameter < kStaticChannelCount && channels()[std::size_t(parameter)].link == Link::instrument;
}

namespace {

// The sources' correlation matrix R of a budget: 1 on the diagonal and within a group, [[correlations]] where
// the budget holds them (input_correlation, groups included).
Eigen::MatrixXd source_correlation(const ccal::BudgetDetail& b) {
  const auto n = Eigen::Index(b.sources.size());
  if (b.input_correlation.rows() == n) return b.input_correlation;
  Eigen::MatrixXd r = Eigen::MatrixXd::Identity(n, n);
  for (Eigen::Index s = 0; s < n; ++s)
    for (Eigen::Index t = 0; t < n; ++t)
      if (s != t && !b.sources[std::size_t(s)].group.empty() &&
          b.sources[std::size_t(s)].group == b.sources[std::size_t(t)].group)
        r(s, t) = 1;
  return r;
}

// E: the sources' signed effects (coefficients × sources) in the display units.
Eigen::MatrixXd display_effects(const ccal::BudgetDetail& b) {
  Eigen::MatrixXd e(Eigen::Index(b.coefficients.size()), Eigen::Index(b.sources.size()));
  for (std::size_t s = 0; s < b.sources.size(); ++s)
    for (std::size_t k = 0; k < b.coefficients.size(); ++k)
      e(Eigen::Index(k), Eigen::Index(s)) = b.sources[s].effect[Eigen::Index(k)] * b.display_scale[k];
  return e;
}

// LPU: the blocks E_a R_ab E_bᵀ of instruments a and b (rows from first_row), with the pairs of two
// instruments' own sources uncorrelated.
Eigen::MatrixXd lpu_covariance(const std::vector<ccal::BudgetDetail>& budgets,
                               const std::vector<Eigen::MatrixXd>& effects,
                               const std::vector<Eigen::Index>& first_row, Eigen::Index rows) {
  const Eigen::MatrixXd r = source_correlation(budgets.front());
  Eigen::MatrixXd lpu = Eigen::MatrixXd::Zero(rows, rows);
  for (std::size_t a = 0; a < budgets.size(); ++a)
    for (std::size_t b = 0; b < budgets.size(); ++b) {
      Eigen::MatrixXd rab = r;
      if (a != b)
        for (Eigen::Index s = 0; s < r.rows(); ++s)
          for (Eigen::Index t = 0; t < r.cols(); ++t)
            if (instrument_own_input(budgets[a].sources[std::size_t(s)].parameter) ||
                instrument_own_input(budgets[b].sources[std::size_t(t)].parameter))
              rab(s, t) = 0;
      lpu.block(first_row[a], first_row[b], effects[a].rows(), effects[b].rows()) =
          effects[a] * rab * effects[b].transpose();
    }
  return lpu;
}

// One instrument's part of the joint trial: its trial function, where its draws are among the joint sources,
// its display scales, its outputs at zero draws, and its scratch.
struct InstrumentPart {
  TrialFunction trial;
  std::vector<std::size_t> index;
  std::vector<double> scale, reference;
  std::vector<double> draws, f;
};

// The Monte Carlo's trial: y = −C (f(e) − f(0)) of every instrument at one draw of the shared sources (each
// part copied into each thread's trial with its scratch).
TrialFunction joint_trial(const std::vector<Config>& each, const JointSources& joint,
                          const std::vector<ccal::BudgetDetail>& budgets, ModelMode mode) {
  std::vector<InstrumentPart> parts;  // copied into each thread's trial with their scratch
  for (std::size_t a = 0; a < each.size(); ++a) {
    const Config& cfg = each[a];
    const CalibrationModel model =
        calibration_model(cfg.experiment(), cfg.identification, cfg.tolerances, cfg.centrifuge.errors, mode);
    InstrumentPart p;
    p.trial = calibration_trial(model);
    p.index = joint.of_instrument[a];
    p.scale = budgets[a].display_scale;
    p.draws.assign(cfg.tolerances.size(), 0.0);
    p.f.assign(std::size_t(model.n_outputs()), 0.0);
    p.reference.assign(p.f.size(), 0.0);
    p.trial(p.draws, p.reference);
    parts.push_back(std::move(p));
  }
  return [parts = std::move(parts)](std::span<const double> draws, std::span<double> outputs) mutable {
    std::size_t row = 0;
    for (InstrumentPart& p : parts) {
      for (std::size_t j = 0; j < p.index.size(); ++j) p.draws[j] = draws[p.index[j]];
      p.trial(p.draws, p.f);
      for (std::size_t k = 0; k < p.f.size(); ++k) outputs[row++] = -p.scale[k] * (p.f[k] - p.reference[k]);
    }
  };
}

}  // namespace

JointSources joint_sources(const std::vector<Config>& each) {
  JointSources j;
  std::map<std::string, std::size_t> shared;
  for (const Tolerance& t : each.front().tolerances)
    if (!instrument_own_input(t.parameter)) {
      shared[t.id] = j.sources.size();
      j.sources.push_back(t);
    }
  for (const Correlation& c : each.front().correlations)
    if (shared.count(c.first) && shared.count(c.second)) j.correlations.push_back(c);
  for (const Config& cfg : each) {
    std::vector<std::size_t> index;
    std::map<std::string, std::string> own_id;
    for (const Tolerance& t : cfg.tolerances) {
      if (!instrument_own_input(t.parameter)) {
        const auto found = shared.find(t.id);
        if (found == shared.end())
          throw InputError(fmt::format("instrument '{}': the tolerance '{}' is not the other instruments'; the "
                                       "machine's tolerances are one for all the instruments of a test",
                                       cfg.instrument_id, t.id));
        index.push_back(found->second);
        continue;
      }
      Tolerance copy = t;
      copy.id = cfg.instrument_id + ":" + t.id;
      if (!copy.group.empty()) copy.group = cfg.instrument_id + ":" + copy.group;
      own_id[t.id] = copy.id;
      index.push_back(j.sources.size());
      j.sources.push_back(std::move(copy));
    }
    for (const Correlation& c : cfg.correlations) {
      const bool first_own = own_id.count(c.first) > 0, second_own = own_id.count(c.second) > 0;
      if (first_own || second_own)
        j.correlations.push_back({first_own ? own_id[c.first] : c.first, second_own ? own_id[c.second] : c.second,
                                  c.r});
    }
    j.of_instrument.push_back(std::move(index));
  }
  return j;
}

InstrumentCovariance instrument_covariance(const std::vector<Config>& each, ModelMode mode, std::uint64_t trials,
                                           std::uint64_t seed, int threads) {
  InstrumentCovariance out;
  if (each.empty()) return out;
  ccal::BudgetOptions bo;
  bo.mode = mode;
  bo.compare_with_paper = false;
  std::vector<ccal::BudgetDetail> budgets;
  std::vector<Eigen::MatrixXd> effects;
  Eigen::Index rows = 0;
  for (const Config& cfg : each) {
    budgets.push_back(ccal::compute_budget(cfg, bo));
    effects.push_back(display_effects(budgets.back()));
    out.instruments.push_back(cfg.instrument_id);
    out.first_row.push_back(rows);
    for (std::size_t k = 0; k < budgets.back().coefficients.size(); ++k) {
      out.names.push_back(cfg.instrument_id + " " + budgets.back().coefficients[k]);
      out.units.push_back(budgets.back().units[k]);
    }
    rows += Eigen::Index(budgets.back().coefficients.size());
  }
  out.lpu = lpu_covariance(budgets, effects, out.first_row, rows);
  if (trials == 0) return out;

  const JointSources joint = joint_sources(each);
  const TrialFunction trial = joint_trial(each, joint, budgets, mode);
  ccal::PropagationOptions mo;
  mo.trials = trials;
  mo.seed = seed;
  mo.threads = threads;
  const ccal::MonteCarloDetail mc = ccal::run_monte_carlo(joint.sources, joint.correlations, int(rows), out.names, trial, mo);
  out.monte_carlo = mc.covariance;
  out.trials = mc.trials;
  out.seed = mc.seed;
  return out;
}

}  // namespace ccal::verbs
