// ccal force: specific force and angular rate at the instrument at one instant of a run, exact and as a sum
// of first-order contributions of the configured centrifuge errors (docs/cli.md).
#include <memory>

#include "ccal/core/units.hpp"
#include "ccal/render/force.hpp"
#include "ccal/verbs/force.hpp"
#include "commands.hpp"
#include "option_flags.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct ForceCli {
  ConfigChoice config;
  verbs::ForceOptions options;  // its table's flags are bound to it, but --time
  std::string time = "0";       // a time with its unit, or seconds
  OutputOptions output;
};

}  // namespace

Command add_force(CLI::App& app) {
  auto options = std::make_shared<ForceCli>();
  CLI::App* cmd = app.add_subcommand(
      "force",
      "Specific force and angular rate at the instrument at one instant of a run, exact and as "
      "first-order contributions of the configured [errors].");
  add_config_argument(*cmd, options->config);
  add_option_flags(*cmd, options->options, option_table<verbs::ForceOptions>(), {"time"});
  cmd->add_option("--time", options->time, "Time into the run, e.g. \"10 s\" or 10 (seconds), within [0, T]")
      ->capture_default_str()
      ->type_name("T");
  add_output_options(*cmd, options->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal force\n"
      "      run 1 of the bundled paper example at t = 0\n"
      "  ccal force examples/wang_ren_2014.toml --run 20g --time \"10 s\" --mode paper\n"
      "  ccal force my.toml --run 3 --time 120 --format json -o force.json\n");

  return {cmd, [options] {
            verbs::ForceOptions fo = options->options;
            fo.time = parse_as(options->time, kind::time, "--time", true);
            const verbs::ForceResult r = verbs::force(load_config_or_example(options->config), fo);
            const std::string& f = options->output.format;
            write_output(options->output, f == "json"  ? render::json(r)
                                          : f == "csv" ? render::csv(r)
                                                       : render::text(r));
          }};
}

}  // namespace ccal::cli
