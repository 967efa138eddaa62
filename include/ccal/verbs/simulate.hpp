#pragma once
// `ccal simulate` as a library call: the run means a test plan produces (truth: the exact chain with the
// configured [errors], plus the instrument's noise), the regressors the analyst computes (with zero errors,
// or the [errors] values when compensating), as an observations file, and their identification exactly as
// `ccal identify` gives it for that file (docs/model.md §8–9).

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/intake/log_manifest.hpp"
#include "ccal/intake/run_log_writer.hpp"
#include "ccal/io/truth_file.hpp"
#include "ccal/reduction/observe.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/verbs/identification.hpp"
#include "ccal/uncertainty/option_rows.hpp"

namespace ccal::verbs {

struct SimulateOptions {
  std::optional<ModelMode> mode;  // reduction of a run; unset: the configuration's [identification] mode
  std::uint64_t seed = 1;         // of the output noise (used only if the instrument has noise)
  // The machine's errors are the configuration's [errors] plus one draw of every [tolerances] input from its
  // distribution (groups and [[correlations]] as the Monte Carlo draws them, uncertainty/montecarlo.hpp's
  // draw_sources with `seed`): a machine drawn from the lab's stated knowledge (the coverage study). Its drives
  // also have their stated rate noise: each run mean moves by a normal draw of the budget's σ_j.
  bool draw_truth = false;
  // What the simulated machine really has (io/truth_file.hpp); unset: the configuration's [errors]. Not a row
  // of the table: each front end reads the file (the command line: --truth FILE).
  std::optional<SimulationTruth> truth;
};

// The options' table (core/options.hpp): names, ranges and help of the fields a front end sets.
OptionTable<SimulateOptions> options_of(std::type_identity<SimulateOptions>);

struct SimulateResult {
  Config config;
  ModelMode mode = ModelMode::exact;
  std::uint64_t seed = 1;
  Observations<double> observations;  // run means (output SI, regressors in their term units)
  double output_unit_si = 1;          // SI size of one output unit
  bool noisy = false;                 // the instrument's noise or quantum was applied
  int error_count = 0;                // non-zero errors of the simulated machine (the truth's, or [errors])
  std::optional<SimulationTruth> truth;  // the truth file, when one was given
  Eigen::VectorXd machine_errors;        // the errors the simulated machine has (SI, by the layout)
  std::vector<double> drawn;             // draw_truth: the draw of each [tolerances] input (SI, their order)
  std::vector<std::size_t> order;     // regressor columns in canonical term order, as in the file
  std::string observations_csv;       // the observations file (the input of `ccal identify`)
  Identification identification;      // of that file
  // A test of several instruments ([[instruments]]): each one's simulation, in the configuration's order, on one
  // machine (the shared errors one draw for all, the drives' rate noise too; each one's own inputs and output
  // noise its own); the fields above are then the first's, config the whole test's. Empty for one instrument.
  std::vector<SimulateResult> instruments;
};

// Throws InputError for a plan the mode cannot reduce (paper mode off the paper's mounting), an ill-posed or
// unobservable identification.
SimulateResult simulate(const Config& config, const SimulateOptions& options = {});

// The run logs of a simulated test as `ccal simulate --logs-out DIR` writes them: one file per run in the layout's
// format (intake/run_log_writer.hpp), then the folder's manifest (kLogManifestName), which `ccal reduce --logs DIR`
// reads. step: the sampling interval [s] (default_log_step when unset). For a test of several instruments every
// instrument's output is a column of each file, named by the layout's [instruments] when it maps them, else
// "pulses_<id>" (or "output_<id>" for an instrument without a quantum), and the manifest's [instruments] names
// them. InputError for a layout whose [instruments] misses an instrument or states its output wrongly.
std::vector<RunLogFile> simulation_logs(const SimulateResult& simulation, LogLayout layout,
                                        std::optional<double> step = std::nullopt);

// Unit of a regressor column: gⁿ, or rad/s for K_w.
std::string regressor_unit(const std::string& term_id);

}  // namespace ccal::verbs
