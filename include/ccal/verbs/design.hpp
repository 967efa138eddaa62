#pragma once
// `ccal design` as a library call: the test plan, within the configuration's design space ([design]), under
// which the centrifuge's tolerances, the drives' rate noise and the instrument's noise cost the chosen
// coefficients least (docs/model.md §15). The designed plan is re-scored by the full budget (verbs::budget)
// before it is returned, and optionally checked by Monte Carlo.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ccal/uncertainty/candidate_cache.hpp"
#include "ccal/model/run_sheet.hpp"
#include "ccal/verbs/statement.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/uncertainty/design_candidates.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/montecarlo.hpp"

namespace ccal::verbs {

struct DesignOptions {
  std::optional<DesignObjective> objective;  // unset: [design] objective
  // Targets "<coefficient>=<U> [unit]" as for `ccal allocate --target`; they replace [design] targets (of every
  // instrument of a test of several).
  std::vector<std::string> targets;
  std::optional<int> starts;                // random starts; unset: [design] starts (default 6)
  std::optional<std::uint64_t> seed;        // unset: [design] seed (default 1)
  // The coverage of every U (targets, budgets, verification), as in `ccal budget` (uncertainty/coverage.hpp).
  std::optional<double> coverage_probability;  // unset: kDefaultCoverageProbability
  std::optional<double> coverage_factor;
  int threads = 0;                          // 0: all cores
  std::int64_t verify_trials = 0;           // Monte Carlo check of the designed plan; 0: none
  // Trade-off curve: the design repeated with the total time scaled by each factor (e.g. 0.5, 0.75, 1).
  std::vector<double> tradeoff;
  // A progress line on standard error, only when it is a terminal: the candidate runs cached, the search's
  // starts, the refinement, each with its estimate of the time left.
  bool progress = false;
  // The candidate runs' rows are read from the cache when it holds them for this configuration, and written
  // to it otherwise (uncertainty/candidate_cache.hpp, in cache_folder); true: computed anew (and written all the
  // same).
  bool fresh_candidates = false;
  std::filesystem::path cache_folder = default_cache_folder();  // empty: no cache
};

// The options' table (core/options.hpp): names, ranges and help of the fields a front end sets.
OptionTable<DesignOptions> options_of(std::type_identity<DesignOptions>);

// The objective's per-coefficient data, in the order of the free terms.
struct DesignTarget {
  std::string coefficient;
  double weight = 0;      // w_k (0: not counted)
  double reference = 0;   // R_k [SI]: the target, or the configured plan's value
  bool is_target = false;  // R_k is a user's target (else the configured plan's U_k)
};

struct TradeoffPoint {
  double total_time = 0;       // [s], the budget of the search
  double used_time = 0;        // Σ T_j of its plan [s]
  Eigen::VectorXd expanded;    // U_k of every free term, full budget of its plan (SI)
  double objective = 0;
};

struct DesignResult {
  Config config;    // as configured
  Config designed;  // the same with the designed [plan], rounded to what the machine sets ([design]
                    // *_resolution)
  RunSheet sheet;   // the designed plan as its operator runs it; `after` is its U if run as written
  ResolvedDesignSpace space;
  std::size_t candidates = 0;  // candidate runs cached
  DesignObjective objective = DesignObjective::uncertainty;
  std::vector<DesignTarget> targets;
  DesignSearchResult search;
  double configured_objective = 0;  // of the configured plan, by the cached rows
  double designed_objective = 0;
  BudgetResult before, after;  // the full budgets of the configured and the designed plan
  // The calibration statement each plan is expected to give if run as written, by the statement's own method
  // (expected_statement: the noise model's Type A part, the inputs the declared encoders will measure
  // credited); unset with a stated coverage factor, which the statement does not take.
  std::optional<CalibrationStatement> expected_before, expected_after;
  // Tolerances only (the LPU, without the drives' noise): U_k of every free term before and after (SI).
  Eigen::VectorXd tolerance_before, tolerance_after;
  std::string mechanism;  // in words: what changed, how much from a stronger signal, how much from cancelling
  std::optional<MonteCarloResult> verification;
  std::vector<TradeoffPoint> tradeoff;
  double cache_seconds = 0, search_seconds = 0;
  bool candidates_from_cache = false;  // the candidate runs' rows were read from the cache file
  // A test of several instruments (two or more [[instruments]]): one plan for all, run with every instrument at
  // once (docs/model.md §15.4). config, designed (its plan, and each instrument's, the designed one), sheet, space,
  // candidates, objective, search and the objectives (the joint one: the largest of the instruments' normalised
  // objectives, the sum for d_optimal) are the whole test's; each instrument's result is here, in the file's
  // order, with its targets, its budgets before and after, its expected statements, its mechanism and its Monte
  // Carlo check (its objectives its own). The fields of one instrument's result are then empty. Empty for one.
  std::vector<DesignResult> instruments;
};

// Throws InputError for an empty or contradictory design space, one with no plan that fits and identifies the
// free terms, bad options (naming --target, --starts, --verify, --tradeoff, --threads), and whatever
// verbs::budget refuses; for a test of several instruments, --tradeoff, and what it refuses of one instrument
// (naming it). The targets apply to every instrument of a test of several.
DesignResult design(const Config& config, const DesignOptions& options = {});

}  // namespace ccal::verbs
