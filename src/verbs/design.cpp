#include "ccal/verbs/design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "../uncertainty/progress_bar.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/intake/measured_inputs.hpp"
#include "ccal/uncertainty/allocate.hpp"
#include "ccal/uncertainty/coverage.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "design_mechanism.hpp"

namespace ccal::verbs {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

constexpr OptionSpec<DesignOptions> kDesignRows[] = {
    {"objective", enum_member<&DesignOptions::objective>(kDesignObjectiveNames), "NAME",
     "uncertainty (U of the chosen coefficients from tolerances and noise), d_optimal or a_optimal (the "
     "instrument's noise alone); default: [design] objective"},
    {"targets", &DesignOptions::targets, "COEFF=U",
     "COEFF=U: the objective counts U(COEFF)/U against this target instead of the configured plan's U, e.g. "
     "K3=1e-4 or \"K3=1e-4 deg/s/g^3\"; one per coefficient; in a test of several instruments, every "
     "instrument's"},
    {"starts", &DesignOptions::starts, "N",
     "Random starts of the search (besides the configured plan); default: [design] starts",
     OptionRange::between(0, 1000)},
    {"seed", &DesignOptions::seed, "S", "Seed of the random starts; default: [design] seed"},
    rows::coverage_probability(&DesignOptions::coverage_probability,
                               "Coverage probability p of the expanded uncertainties (the targets, the "
                               "budgets and the verification), in {range}"),
    rows::coverage_factor(&DesignOptions::coverage_factor),
    rows::threads(&DesignOptions::threads, "Threads (0: the OpenMP default)"),
    rows::verify_trials(&DesignOptions::verify_trials,
                        "Monte Carlo trials checking the designed plan's budget (0: none)"),
    {"tradeoff", &DesignOptions::tradeoff, "F,...",
     "Factors of the total test time for a trade-off curve (total time against U), e.g. 0.5,0.75,1",
     OptionRange::between(0, 10).open_low().e_g("0.5,0.75,1")},
    {"fresh_candidates", &DesignOptions::fresh_candidates, "",
     "Compute the candidate runs' rows anew instead of reading them from the cache ($XDG_CACHE_HOME/ccal, "
     "else ~/.cache/ccal), which keeps them per configuration file and build of ccal"},
};

// The objective's weights and references (references of the configured plan filled in later).
std::vector<DesignTarget> design_targets(const Config& config, const DesignOptions& o,
                                         const ccal::BudgetDetail& before) {
  std::map<std::string, double> targets = config.design.targets;
  if (!o.targets.empty()) {
    targets.clear();
    for (const std::string& t : o.targets) {
      const AllocationTarget a = parse_allocation_target(t, before.coefficients, before.units);
      // A second target on one coefficient replaced the first in silence.
      if (!targets.emplace(a.coefficient, a.expanded).second)
        throw OptionError(a.field, a.coefficient, "has two targets; accepted: one target per coefficient");
    }
  }
  std::vector<std::string> chosen = config.design.coefficients;
  if (chosen.empty())
    for (const auto& [id, value] : targets) chosen.push_back(id);
  if (chosen.empty()) chosen = before.coefficients;
  std::vector<DesignTarget> out;
  for (const std::string& id : before.coefficients) {
    DesignTarget t;
    t.coefficient = id;
    if (std::find(chosen.begin(), chosen.end(), id) != chosen.end()) {
      const auto w = config.design.weights.find(id);
      t.weight = w == config.design.weights.end() ? 1.0 : w->second;
    }
    if (const auto it = targets.find(id); it != targets.end()) {
      t.reference = it->second;
      t.is_target = true;
      if (t.weight == 0) t.weight = 1.0;
    }
    out.push_back(t);
  }
  return out;
}

// The configured runs as candidates, if every one lies in the design space (then the configured plan is a
// start, and the design can only improve on it).
bool configured_in_space(const Config& config, const ResolvedDesignSpace& s) {
  if (int(config.plan.runs.size()) != s.runs) return false;
  double total = 0;
  for (const Run& r : config.plan.runs) {
    total += r.duration;
    const bool g_ok = s.refinement.g_step > 0
                          ? r.g_level >= s.refinement.g_low && r.g_level <= s.refinement.g_high
                          : std::find(s.g_levels.begin(), s.g_levels.end(), r.g_level) != s.g_levels.end();
    if (!g_ok || r.g_level > s.max_g) return false;
    if (std::find(s.mountings.begin(), s.mountings.end(), r.mounting) == s.mountings.end()) return false;
    if (std::find(s.platforms.begin(), s.platforms.end(), r.mode) == s.platforms.end()) return false;
  }
  return total <= s.total_time * (1 + 1e-12);
}

// The designed plan as the operator runs it: each run rounded to what the machine can set, in g-level order,
// named after its g-level ("29.47g"; "30g", "30g-2", … where several share one), so that a log's name says
// its g-level.
Config with_plan(const Config& config, const std::vector<DesignRun>& runs, const ResolvedDesignSpace& space) {
  std::vector<DesignRun> sorted = runs;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const DesignRun& a, const DesignRun& b) { return a.g_level < b.g_level; });
  Config c = config;
  clear_fingerprints(c);  // another plan: no longer the file's configuration
  c.plan.runs.clear();
  const SettingResolution resolution = setting_resolution(config.design);
  std::map<std::string, int> count;
  for (const DesignRun& run : sorted) {
    Run planned = rounded_run(plan_run(run, ""), resolution, space.max_g);
    const std::string level = fmt::format("{:.12g}g", planned.g_level);
    const int n = ++count[level];
    planned.name = n == 1 ? level : fmt::format("{}-{}", level, n);
    c.plan.runs.push_back(planned);
  }
  // Rounding lowers durations and keeps g-levels within max_g (resolve_design_space refuses steps coarser
  // than the space), so the rounded plan stays in it; were it not, no plan is better than a wrong one.
  double total = 0;
  for (const Run& run : c.plan.runs) total += run.duration;
  if (total > space.total_time * (1 + 1e-12))
    throw InputError(
        fmt::format("{}: the designed plan rounded to design.duration_resolution lasts {:g} s, more "
                    "than total_time = {:g} s; accepted: a finer duration_resolution",
                    config.source, total, space.total_time));
  return c;
}

// The budget options of a design: its coverage.
BudgetOptions budget_options(const DesignOptions& o) {
  BudgetOptions b;
  b.coverage_probability = o.coverage_probability;
  b.coverage_factor = o.coverage_factor;
  return b;
}

BudgetResult rescore(const Config& designed, const DesignOptions& options) {
  try {
    return budget(designed, budget_options(options));
  } catch (const IllPosedFit& e) {
    throw InputError(std::string("the designed plan does not identify the free terms by the full budget: ") +
                     e.what());
  }
}

// The design problem's candidates: every run of the design space, then the configured runs when they all lie
// in it (their plan is then the search's initial plan, so that the design can only improve on it), with the
// rows of every candidate computed once.
DesignProblem candidate_problem(const Config& config, const ResolvedDesignSpace& space,
                                const DesignOptions& options, progress_bar::Progress& progress,
                                bool& from_cache) {
  std::vector<DesignRun> candidates = candidate_runs(space, config);
  std::vector<std::vector<int>> initial;
  if (configured_in_space(config, space)) {
    std::vector<int> plan;
    for (const Run& run : config.plan.runs) {
      plan.push_back(int(candidates.size()));
      candidates.push_back(design_run(run));
    }
    initial.push_back(plan);
  }
  DesignProblem problem;
  problem.runs = space.runs;
  problem.min_g_levels = space.min_g_levels;
  problem.g_resolution = setting_resolution(config.design).g;
  problem.total_time = space.total_time;
  // The rows from the cache file of this configuration and these candidates, else computed and stored there.
  const std::string key = candidate_cache_key(config, candidates);
  const auto terms = Eigen::Index(config.identification.free_terms.size());
  std::optional<CandidateRows> cached;
  if (!options.fresh_candidates)
    cached = read_candidate_cache(options.cache_folder, key, Eigen::Index(candidates.size()), terms);
  from_cache = cached.has_value();
  if (cached) {
    problem.rows = std::move(*cached);
  } else {
    progress.restart(candidates.size(), "design: candidate runs ", "runs");
    problem.rows = candidate_rows(config, candidates, options.threads, [&progress] { progress.tick(); });
    write_candidate_cache(options.cache_folder, key, problem.rows);
  }
  problem.candidates = std::move(candidates);
  problem.initial_plans = initial;
  return problem;
}

// The criterion's weights and references. A reference is the target, else the configured plan's own value of
// the criterion (U_k or σ_k by the cached rows), else the budget's U_k; a coefficient no tolerance reaches
// cannot be improved (weight 0). Also the configured plan's objective, when it is a start.
void set_criterion(const Config& config, DesignResult& r, DesignProblem& problem) {
  const auto nk = Eigen::Index(r.targets.size());
  DesignCriterion& c = problem.criterion;
  c.objective = r.objective;
  c.coverage_factor = r.before.budget.coverage.factor;
  c.weight = Eigen::VectorXd::Zero(nk);
  c.reference = Eigen::VectorXd::Ones(nk);
  for (Eigen::Index k = 0; k < nk; ++k) c.weight[k] = r.targets[std::size_t(k)].weight;
  const std::vector<std::vector<int>>& initial = problem.initial_plans;
  if (!initial.empty()) {
    const PlanScore configured = score_plan(problem.rows.select(initial.front()), c);
    for (Eigen::Index k = 0; k < nk; ++k) {
      DesignTarget& t = r.targets[std::size_t(k)];
      if (!t.is_target && configured.well_posed)
        t.reference = r.objective == DesignObjective::uncertainty ? configured.expanded[k]
                                                                  : std::sqrt(configured.covariance(k, k));
    }
  }
  for (Eigen::Index k = 0; k < nk; ++k) {
    DesignTarget& t = r.targets[std::size_t(k)];
    if (!(t.reference > 0)) t.reference = r.before.budget.expanded_uncertainty[k];
    if (!(t.reference > 0)) t.weight = 0;  // a coefficient no tolerance reaches cannot be improved
    c.reference[k] = t.reference > 0 ? t.reference : 1.0;
  }
  if (!(c.weight.maxCoeff() > 0) && r.objective != DesignObjective::d_optimal)
    throw InputError(config.source + ": design: no chosen coefficient has an uncertainty to reduce");
  if (!initial.empty())
    r.configured_objective = score_plan(problem.rows.select(initial.front()), c).objective;
}

// One point of the trade-off curve: the same design with the total time (and the default nominal duration)
// scaled by `factor`, neither verified nor traded off again.
TradeoffPoint tradeoff_point(const Config& config, const DesignOptions& options,
                             const ResolvedDesignSpace& space, double factor) {
  Config scaled = config;
  scaled.design.total_time = space.total_time * factor;
  if (config.design.durations.empty()) scaled.design.durations = {space.durations.front() * factor};
  DesignOptions o = options;
  o.tradeoff.clear();
  o.verify_trials = 0;
  // The scaled design's refusal names [design] keys the user did not write: said of the factor instead.
  const DesignResult d = [&] {
    try {
      return design(scaled, o);
    } catch (const OptionError&) {
      throw;
    } catch (const InputError& e) {
      throw OptionError(
          "tradeoff", option_number_text(factor),
          fmt::format("scales the total time to {:g} s, for which the design fails ({}); accepted: "
                      "factors for which the design space still holds a plan",
                      *scaled.design.total_time, e.what()));
    }
  }();
  TradeoffPoint point;
  point.total_time = d.space.total_time;
  point.used_time = d.search.rows.duration.sum();
  point.expanded = d.after.budget.expanded_uncertainty;
  point.objective = d.designed_objective;
  return point;
}

}  // namespace

OptionTable<DesignOptions> options_of(std::type_identity<DesignOptions>) { return kDesignRows; }

namespace {

// One instrument's part of a design: its configuration as its statement will charge it (the inputs the declared
// encoders will measure at that measurement's uncertainty, docs/model.md §13.3, the others at their tolerances),
// its result so far (the configured plan's budget, the targets, the criterion) and its problem (its rows of the
// candidates).
struct Prepared {
  Config config;
  DesignResult r;
  DesignProblem problem;
};

Prepared prepare(const Config& configured, const DesignOptions& options, const ResolvedDesignSpace* space,
                 progress_bar::Progress& progress) {
  Prepared p;
  p.config = with_measured_inputs(configured, expected_measured_inputs(configured));
  const Config& config = p.config;
  if (config.tolerances.empty())
    throw InputError(config.source + ": [tolerances] is empty; the design needs the tolerances it weighs");
  DesignResult& r = p.r;
  r.config = configured;
  r.space = space ? *space : resolve_design_space(config);
  r.objective = options.objective.value_or(config.design.objective);
  r.before = budget(config, budget_options(options));
  r.targets = design_targets(config, options, r.before.budget);
  const auto t0 = std::chrono::steady_clock::now();
  p.problem = candidate_problem(config, r.space, options, progress, r.candidates_from_cache);
  r.candidates = p.problem.candidates.size();
  r.cache_seconds = seconds_since(t0);
  set_criterion(config, r, p.problem);
  p.problem.refinement = r.space.refinement;
  p.problem.evaluate = [config, threads = options.threads](const std::vector<DesignRun>& runs) {
    return candidate_rows(config, runs, threads);
  };
  return p;
}

// The search, its progress shown; its time in `seconds`.
DesignSearchResult run_search(const DesignProblem& problem, const Config& config, const DesignOptions& options,
                              progress_bar::Progress& progress, double& seconds) {
  const auto t1 = std::chrono::steady_clock::now();
  DesignSearchOptions so;
  so.starts = options.starts.value_or(config.design.starts.value_or(6));
  so.seed = options.seed.value_or(config.design.seed.value_or(1));
  if (progress.on()) {
    std::string stage;
    so.on_progress = [&progress, &stage](std::string_view now, int done, int total) {
      if (now != stage) {
        stage = now;
        progress.restart(std::uint64_t(total), fmt::format("design: {} ", now),
                         now == "search" ? "starts" : "halvings");
      }
      progress.set_done(std::uint64_t(done));
    };
  }
  DesignSearchResult search = search_design(problem, so);
  seconds = seconds_since(t1);
  progress.finish();
  return search;
}

// An instrument's result of the designed plan: its full budget, the tolerances' part, the mechanism, the
// expected statements and the Monte Carlo check.
void finish(Prepared& p, DesignSearchResult search, const DesignOptions& options) {
  DesignResult& r = p.r;
  r.search = std::move(search);
  r.designed_objective = r.search.score.objective;
  r.designed = with_plan(p.config, r.search.runs, r.space);
  r.sheet = run_sheet(r.designed.plan, r.designed.centrifuge.geometry, r.designed.site);
  r.after = rescore(r.designed, options);
  r.tolerance_before = tolerance_expanded(r.before.budget);
  r.tolerance_after = tolerance_expanded(r.after.budget);
  r.mechanism = mechanism_text(r);
  if (!options.coverage_factor) {
    const double p_cov = r.after.budget.coverage.probability;
    r.expected_before = expected_statement(p.config, p_cov);
    r.expected_after = expected_statement(r.designed, p_cov);
  }
  if (options.verify_trials > 0) {
    MonteCarloOptions mo;
    mo.propagation.trials = options.verify_trials;
    mo.propagation.seed = options.seed.value_or(p.config.design.seed.value_or(1));
    mo.propagation.threads = options.threads;
    mo.propagation.coverage_probability = r.after.budget.coverage.probability;  // a stated k's normal p
    r.verification = monte_carlo(r.designed, mo);
  }
}

// A test of several instruments: one plan for all (docs/model.md §15.4), each instrument's rows of the same
// candidates, the plan scored by the joint objective; each instrument's result as design() of it alone reports it.
DesignResult design_of_instruments(const Config& configured, const DesignOptions& options) {
  if (!options.tradeoff.empty())
    throw OptionError("tradeoff", option_number_text(options.tradeoff.front()),
                      fmt::format("is not taken for a test of {} instruments ({}); accepted: {} with a "
                                  "configuration of one instrument (one of the test's chosen)",
                                  configured.instruments.size(), configured.source, OptionError::name("tradeoff")));
  progress_bar::Progress progress(options.progress);
  std::vector<Prepared> each;
  for (const Config& one : configured.instruments) {
    try {
      each.push_back(prepare(one, options, each.empty() ? nullptr : &each.front().r.space, progress));
    } catch (const OptionError&) {
      throw;
    } catch (const InputError& e) {
      throw InputError(fmt::format("instrument '{}': {}", one.instrument_id, e.what()));
    }
  }
  DesignProblem problem = each.front().problem;
  std::vector<double> configured_objectives;
  for (std::size_t i = 0; i < each.size(); ++i) {
    if (i > 0)
      problem.others.push_back({each[i].problem.rows, each[i].problem.criterion, each[i].problem.evaluate});
    configured_objectives.push_back(each[i].r.configured_objective);
  }
  DesignResult r;
  r.config = configured;
  r.space = each.front().r.space;
  r.objective = each.front().r.objective;
  r.candidates = each.front().r.candidates;
  r.candidates_from_cache = true;
  for (const Prepared& p : each) {
    r.cache_seconds += p.r.cache_seconds;
    r.candidates_from_cache = r.candidates_from_cache && p.r.candidates_from_cache;
  }
  if (!problem.initial_plans.empty()) r.configured_objective = joint_objective(problem, configured_objectives);
  r.search = run_search(problem, each.front().config, options, progress, r.search_seconds);
  r.designed_objective = r.search.score.objective;
  for (std::size_t i = 0; i < each.size(); ++i) {
    DesignSearchResult own = r.search;
    own.score = r.search.scores[i];
    if (i > 0) own.rows = r.search.other_rows[i - 1];
    own.scores.clear();
    own.other_rows.clear();
    finish(each[i], std::move(own), options);
    each[i].r.search_seconds = r.search_seconds;
  }
  r.designed = with_plan(configured, r.search.runs, r.space);
  for (Config& one : r.designed.instruments) {
    one.plan = r.designed.plan;
    clear_fingerprints(one);
  }
  r.sheet = run_sheet(r.designed.plan, r.designed.centrifuge.geometry, r.designed.site);
  for (Prepared& p : each) r.instruments.push_back(std::move(p.r));
  return r;
}

}  // namespace

namespace {

// Before the search, and named as this verb's options (the verification's Monte Carlo would say "trials", and
// "coverage_probability" for the p of a stated coverage factor the user did not give).
void check_verification_trials(const DesignOptions& o) {
  const double p = o.coverage_factor ? normal_coverage_probability(*o.coverage_factor)
                                     : o.coverage_probability.value_or(kDefaultCoverageProbability);
  try {
    check_coverage_interval(o.verify_trials, p, "verify_trials");
  } catch (const OptionError&) {
    if (!o.coverage_factor) throw;
    throw OptionError("verify_trials", std::to_string(o.verify_trials),
                      fmt::format("are too few for the coverage interval of the stated coverage factor {} (p = {:.6g} "
                                  "of a normal quantity): its ends do not exist (JCGM 101 §7.7.2); accepted: {} at "
                                  "least {}, or 0 (none)",
                                  *o.coverage_factor, p, OptionError::name("verify_trials"),
                                  least_trials_for_coverage(p)));
  }
}

}  // namespace

DesignResult design(const Config& configured, const DesignOptions& options) {
  check_options(options, option_table<DesignOptions>());
  rows::check_coverage_choice(options.coverage_probability, options.coverage_factor);
  if (options.verify_trials > 0) check_verification_trials(options);
  if (configured.instruments.size() > 1) return design_of_instruments(configured, options);
  progress_bar::Progress progress(options.progress);
  Prepared p = prepare(configured, options, nullptr, progress);
  DesignResult& r = p.r;
  DesignSearchResult search = run_search(p.problem, p.config, options, progress, r.search_seconds);
  finish(p, std::move(search), options);
  for (double factor : options.tradeoff)
    r.tradeoff.push_back(tradeoff_point(p.config, options, r.space, factor));
  return std::move(p.r);
}

}  // namespace ccal::verbs
