#pragma once
// `ccal report` as a library call: everything the HTML report of a configuration shows, computed by the
// other verbs with the same options (so that every number equals that verb's output): the budget (exact mode
// with the paper's first-order effect of each source beside it), the Monte Carlo propagation with its kept
// distribution, and the sensed input along the instrument's axes over part of one run; optionally a tolerance
// allocation (`ccal allocate`), a test-plan design (`ccal design`), each before and after, and the
// calibration statement of an observations file (`ccal identify OBS.csv --statement --config CONFIG`).

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/verbs/allocate.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/design.hpp"
#include "ccal/verbs/force.hpp"
#include "ccal/verbs/history.hpp"
#include "ccal/verbs/identify.hpp"
#include "ccal/verbs/montecarlo.hpp"

namespace ccal::verbs {

struct ReportOptions {
  std::optional<ModelMode> mode;  // kinematics of budget and Monte Carlo; unset: the configuration's
  // Every U of the report is at the Monte Carlo's coverage probability (monte_carlo.coverage_probability);
  // a stated k, when given, replaces the normal k of the budget's and the design's LPU (as `ccal budget`).
  std::optional<double> coverage_factor;
  PropagationOptions monte_carlo;  // as `ccal montecarlo` in the report's mode
  std::string run;                // the run whose sensed input is drawn; empty: the one of highest g-level
  int input_points = 241;         // instants of the sensed-input curve, 2…100000
  // The allocation section: as `ccal allocate` with these options (its mode set from `mode` when unset).
  std::optional<AllocateOptions> allocate;
  // The design section: as `ccal design` with these options (the design uses the configuration's mode).
  std::optional<DesignOptions> design;
  // The statement section: this observations file (as `ccal simulate --observations-out` writes it),
  // identified as `ccal identify OBS.csv --statement --config CONFIG` with the report's mode and the Monte Carlo's
  // coverage probability, seed and threads.
  std::optional<CsvTable> observations;
  // The statement's Monte Carlo check; 0: none; unset: kDefaultStatementTrials (optional: one given without
  // observations is refused, at its default value too).
  std::optional<std::int64_t> statement_trials;
  // The history section: this store's calibrations of the [certificate]'s serial number (`ccal history
  // show`), when it has any; "": none.
  std::string history_db;
  // With observations and a [certificate] table the page is the calibration certificate; this gives the
  // engineering report instead (the statement first, then the budget, its Monte Carlo, the paper comparison,
  // the sensed input and the provenance), which states the same result.
  bool engineering = false;
};

// The options' table (core/options.hpp): the report's own fields (those of its sections are in their verbs'
// tables).
OptionTable<ReportOptions> options_of(std::type_identity<ReportOptions>);

// The specific force the instrument senses over a window of one run, exact (verbs::force at each instant).
struct SensedInputSeries {
  std::size_t run_index = 0;
  std::string run_name;
  double g_level = 0;              // g
  double duration = 0;             // s, the run's
  double window = 0;               // s, the part drawn: the whole run, or its first 3 platform revolutions
  double platform_rate = 0;        // rad/s (0 for a fixed platform)
  std::vector<double> time;        // s
  std::vector<double> ia, pa, oa;  // exact specific force along IA, PA, OA [g]
  std::vector<double> ia_first_order;  // the first-order model's IA value (nominal + contributions) [g]
  std::vector<ForceResult> instants;   // the window's start, middle and end, in full (`ccal force`)
};

struct ReportResult {
  Config config;
  // The page is the calibration certificate (gives_certificate): it shows the statement and the budget, so the
  // tolerance budget's Monte Carlo and the sensed input, which only the engineering report shows, are left
  // empty.
  bool certificate = false;
  BudgetResult budget;           // verbs::budget(config, {mode, coverage probability, coverage_factor})
  MonteCarloResult monte_carlo;  // verbs::monte_carlo(config, options.monte_carlo), samples kept
  SensedInputSeries sensed_input;
  std::optional<AllocateResult> allocation;  // verbs::allocate(config, *options.allocate)
  std::optional<DesignResult> design;        // verbs::design(config, *options.design)
  // With the design: each configured run at its start (`ccal force --run k --time 0`), whose plan is shown
  // beside the designed one.
  std::vector<ForceResult> configured_runs;
  // With observations: their identification with its calibration statement (verbs::identify with the
  // configuration as budget); `statement` is always set.
  std::optional<IdentifyResult> observed;
  // With observations: each row's mean output as the file has it (its output column), in the output unit.
  std::vector<double> observed_means;
  // With options.history_db: the serial's calibrations, when the store has any (verbs::history_show).
  std::optional<HistoryShowResult> history;
  // A certificate's traceability: every input of the statement's budget on the standard it rests on
  // (traceability_lines), and a warning for the laboratory when some rest on none.
  std::vector<TraceabilityLine> traceability;
  std::vector<std::string> warnings;
};

// The options of each section as the report computes it: what `ccal budget`, `ccal montecarlo`, `ccal
// allocate`, `ccal design` and `ccal identify OBS --statement --config CONFIG` are given for the same numbers.
// report() runs these, and the page shows them as its "same as" command lines (render/report.cpp), every option
// that is not the default named.
struct ReportSections {
  BudgetOptions budget;          // the report's mode, the Monte Carlo's p and the stated k
  MonteCarloOptions monte_carlo;  // options.monte_carlo in the report's mode, no samples kept
  std::optional<AllocateOptions> allocate;  // options.allocate, its mode the report's when unset
  std::optional<DesignOptions> design;      // options.design
  // The observations' statement: its options those of the Monte Carlo (p, seed, threads), the stated k, the
  // report's mode and statement_trials.
  IdentifyOptions identify;
};
ReportSections report_sections(const ReportOptions& options);

// Whether a report of these options is the calibration certificate: observations, a [certificate] table and not
// the engineering report.
bool gives_certificate(const Config& config, const ReportOptions& options);

// Throws InputError as the verbs it calls do, for an unknown --run or input_points out of range, and for a
// bad allocation or design target before anything is computed (naming --allocate-target or --design-target),
// and for observations that cannot be identified or whose terms are not the configuration's (naming
// --observations), also before the long computations.
ReportResult report(const Config& config, const ReportOptions& options = {});

// The allocation section as every front end asks for it: `ccal allocate` for these targets with the report's
// coverage probability, seed and threads (its mode, left unset, is the report's).
AllocateOptions report_allocation(std::vector<std::string> targets, const ReportOptions& options);
// The design section: `ccal design` for these targets (none: the [design] table's) with the report's
// coverage and threads.
DesignOptions report_design(std::vector<std::string> targets, const ReportOptions& options);

}  // namespace ccal::verbs
