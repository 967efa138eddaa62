// ccal montecarlo: propagation of the configured tolerances to the identified coefficients by the Monte Carlo
// method of JCGM 101 (the engine of ccal/uncertainty/montecarlo.hpp), with the LPU of `ccal budget` for its
// validation.
#include <cstdint>
#include <memory>

#include "ccal/render/montecarlo.hpp"
#include "ccal/verbs/montecarlo.hpp"
#include "commands.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct MonteCarloCli {
  std::string config;
  std::int64_t trials = 10000;  // signed, so that a negative number is reported rather than wrapped
  std::uint64_t seed = 1;
  int threads = 0;
  int digits = 0;
  std::int64_t max_trials = 1000000;
  double coverage = 0.95;
  std::string mode;  // empty: the configuration's
  OutputOptions output;
};

}  // namespace

Command add_montecarlo(CLI::App& app) {
  auto o = std::make_shared<MonteCarloCli>();
  CLI::App* cmd = app.add_subcommand(
      "montecarlo",
      "Monte Carlo propagation (JCGM 101) of the configured tolerances to the identified coefficients, with "
      "the validation of the LPU");
  add_config_argument(*cmd, o->config);
  cmd->add_option("--trials", o->trials,
                  "Number of trials M (≥ 2); with --digits, the stage size (at least 10000)")
      ->capture_default_str()
      ->type_name("N");
  cmd->add_option("--seed", o->seed, "Seed of the random numbers (same seed, same results)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)  // a negative seed would wrap to 2^64 - 1 silently
      ->type_name("S");
  cmd->add_option("--threads", o->threads, "Threads (0: the OpenMP default); the results do not depend on it")
      ->capture_default_str()
      ->type_name("K");
  cmd->add_option("--digits", o->digits,
                  "0: fixed M; n in 1..6: adaptive M (JCGM 101 §7.9) until n significant digits of u(y) "
                  "are stable")
      ->capture_default_str()
      ->type_name("n");
  cmd->add_option("--max-trials", o->max_trials, "Adaptive procedure: no stage beyond this many trials")
      ->capture_default_str()
      ->type_name("N");
  cmd->add_option("--coverage", o->coverage, "Coverage probability p of the intervals, in (0, 1)")
      ->capture_default_str()
      ->type_name("p");
  cmd->add_option("--mode", o->mode,
                  "Kinematics: exact (full chain) or paper (Wang & Ren first-order rules); default: the "
                  "configuration's [identification] mode")
      ->check(CLI::IsMember({"exact", "paper"}));
  add_output_options(*cmd, o->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal montecarlo --trials 2000\n"
      "      2000 trials of the bundled paper example\n"
      "  ccal montecarlo my.toml --trials 100000 --seed 7 --threads 2 --format json -o mc.json\n"
      "  ccal montecarlo --digits 2\n"
      "      the adaptive procedure: stages of 10000 trials until u(y) is stable to 2 digits\n");
  return {cmd, [o] {
            verbs::MonteCarloOptions mo;
            if (!o->mode.empty()) mo.mode = parse_mode(o->mode);
            mo.trials = o->trials;
            mo.seed = o->seed;
            mo.threads = o->threads;
            mo.digits = o->digits;
            mo.max_trials = o->max_trials;
            mo.coverage = o->coverage;
            mo.progress = true;  // drawn only when standard error is a terminal
            const verbs::MonteCarloResult r = verbs::monte_carlo(load_config_or_example(o->config), mo);
            const std::string& f = o->output.format;
            write_output(o->output, f == "json"  ? render::json(r)
                                    : f == "csv" ? render::csv(r)
                                                 : render::text(r));
          }};
}

}  // namespace ccal::cli
