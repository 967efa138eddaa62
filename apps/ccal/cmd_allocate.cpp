// ccal allocate: the largest centrifuge tolerances for which every target on an identified coefficient holds
// (ccal/uncertainty/allocate.hpp), with a Monte Carlo check of the result.
#include <memory>

#include "ccal/render/allocate.hpp"
#include "ccal/verbs/allocate.hpp"
#include "commands.hpp"
#include "option_flags.hpp"
#include "output.hpp"
#include "terminal.hpp"

namespace ccal::cli {
namespace {

struct AllocateCli {
  ConfigChoice config;
  AllocateOptions options;  // its table's flags are bound to it
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
  add_option_flags(*cmd, o->options, option_table<AllocateOptions>());
  add_renamed_option(*cmd, "--coverage",
                     "renamed: give the coverage probability of the targets as --coverage-probability p "
                     "(e.g. 0.95)");
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
            AllocateOptions ao = o->options;
            ao.progress = true;  // drawn only when standard error is a terminal
            const verbs::AllocateResult r = verbs::allocate(load_config_or_example(o->config), ao);
            const std::string& f = o->output.format;
            write_output(o->output, f == "json"  ? render::json(r)
                                    : f == "csv" ? render::csv(r)
                                                 : render::text(r, text_options(o->width, o->output)));
          }};
}

}  // namespace ccal::cli
