// ccal allocate: the largest centrifuge tolerances for which every target on an identified coefficient holds
// (ccal/uncertainty/allocate.hpp), with a Monte Carlo check of the result.
#include <cstdint>
#include <memory>

#include "ccal/render/allocate.hpp"
#include "ccal/verbs/allocate.hpp"
#include "commands.hpp"
#include "output.hpp"
#include "terminal.hpp"

namespace ccal::cli {
namespace {

struct AllocateCli {
  std::string config;
  std::vector<std::string> targets;
  double coverage_probability = 0.95;
  std::string mode;  // empty: the configuration's
  double max_scale = 10.0;
  std::int64_t verify_trials = 2000;  // signed, so that a negative number is reported rather than wrapped
  std::uint64_t seed = 1;
  int threads = 0;
  WidthOptions width;
  OutputOptions output;
};

render::AllocateTextOptions text_options(const WidthOptions& width, const OutputOptions& output) {
  render::AllocateTextOptions to;
  to.width = text_width(width, output_terminal(output));
  to.wide = width.wide;
  return to;
}

}  // namespace

Command add_allocate(CLI::App& app) {
  auto o = std::make_shared<AllocateCli>();
  CLI::App* cmd = app.add_subcommand(
      "allocate",
      "Tolerance allocation: the largest centrifuge tolerances for which every target on the expanded "
      "uncertainty of an identified coefficient holds, checked by Monte Carlo");
  add_config_argument(*cmd, o->config);
  cmd->add_option("--target", o->targets,
                  "COEFF=U: the allowed expanded uncertainty (half-width of the coverage interval) of a free "
                  "coefficient, in its unit (output unit per g^n) or with a unit, e.g. K3=1e-6 or "
                  "\"K3=1e-6 deg/s/g^3\"; repeat for each coefficient")
      ->required()
      ->allow_extra_args(false)
      ->type_name("COEFF=U");
  cmd->add_option("--coverage-probability", o->coverage_probability,
                  "Coverage probability p of the targets, in (0, 1)")
      ->capture_default_str()
      ->type_name("p");
  add_renamed_option(*cmd, "--coverage",
                     "renamed: give the coverage probability of the targets as --coverage-probability p "
                     "(e.g. 0.95)");
  cmd->add_option("--mode", o->mode,
                  "Kinematics of the sensitivities and the verification: exact or paper; default: the "
                  "config's [identification] mode")
      ->check(mode_names_check());
  cmd->add_option("--max-scale", o->max_scale, "No tolerance is loosened by more than this factor (> 0)")
      ->capture_default_str()
      ->type_name("X");
  cmd->add_option("--verify-trials", o->verify_trials,
                  "Monte Carlo trials of the verification on the allocated tolerances (0: none)")
      ->capture_default_str()
      ->type_name("N");
  cmd->add_option("--seed", o->seed, "Seed of the verification")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber)  // a negative seed would wrap to 2^64 - 1 silently
      ->type_name("S");
  cmd->add_option("--threads", o->threads, "Threads of the verification (0: the OpenMP default)")
      ->capture_default_str()
      ->type_name("K");
  add_width_options(*cmd, o->width, "Uncut source names and the cost column; no width limit");
  add_output_options(*cmd, o->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal allocate --target K2=2e-5 --target K3=2e-3\n"
      "      tolerances of the bundled paper example for U(K2) <= 2e-5 deg/s/g^2 and U(K3) <= 2e-3 "
      "deg/s/g^3\n"
      "  ccal allocate my.toml --target \"K3=1e-6 deg/s/g^3\" --max-scale 3 --verify-trials 10000\n"
      "  ccal allocate --target K0=1e-3 --format json -o allocation.json\n");
  return {cmd, [o] {
            verbs::AllocateOptions ao;
            ao.targets = o->targets;
            ao.coverage_probability = o->coverage_probability;
            if (!o->mode.empty()) ao.mode = parse_mode(o->mode);
            ao.max_scale = o->max_scale;
            ao.verify_trials = o->verify_trials;
            ao.seed = o->seed;
            ao.threads = o->threads;
            ao.progress = true;  // drawn only when standard error is a terminal
            const verbs::AllocateResult r = verbs::allocate(load_config_or_example(o->config), ao);
            const std::string& f = o->output.format;
            write_output(o->output, f == "json"  ? render::json(r)
                                    : f == "csv" ? render::csv(r)
                                                 : render::text(r, text_options(o->width, o->output)));
          }};
}

}  // namespace ccal::cli
