// ccal force: specific force and angular rate at the instrument at one instant of a run, exact and as a sum
// of first-order contributions of the configured centrifuge errors (docs/cli.md).
#include <memory>

#include "ccal/core/units.hpp"
#include "ccal/render/force.hpp"
#include "ccal/verbs/force.hpp"
#include "commands.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct ForceCli {
  std::string config;
  std::string run = "1";
  std::string time = "0";
  std::string mode{mode_name(verbs::ForceOptions{}.mode)};  // the library's default
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
  cmd->add_option("--run", options->run, "Run name or 1-based index")->capture_default_str()->type_name("J");
  cmd->add_option("--time", options->time, "Time into the run, e.g. \"10 s\" or 10 (seconds), within [0, T]")
      ->capture_default_str()
      ->type_name("T");
  cmd->add_option("--mode", options->mode,
                  "First-order model: exact (linearised exact chain) or paper (Wang & Ren Eq.14 form)")
      ->check(mode_names_check())
      ->capture_default_str();
  add_output_options(*cmd, options->output, {"text", "json"});
  cmd->footer(
      "Examples:\n"
      "  ccal force\n"
      "      run 1 of the bundled paper example at t = 0\n"
      "  ccal force examples/wang_ren_2014.toml --run 20g --time \"10 s\" --mode paper\n"
      "  ccal force my.toml --run 3 --time 120 --format json -o force.json\n");

  return {cmd, [options] {
            verbs::ForceOptions fo;
            fo.run = options->run;
            fo.time = parse_as(options->time, kind::time, "--time", true);
            fo.mode = *parse_mode(options->mode);
            const verbs::ForceResult r = verbs::force(load_config_or_example(options->config), fo);
            write_output(options->output,
                         options->output.format == "json" ? render::json(r) : render::text(r));
          }};
}

}  // namespace ccal::cli
