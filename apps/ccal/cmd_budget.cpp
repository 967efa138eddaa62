// ccal budget: the error budget of the configured centrifuge tolerances on the identified coefficients.
#include <memory>

#include "ccal/render/budget.hpp"
#include "ccal/verbs/budget.hpp"
#include "commands.hpp"
#include "option_flags.hpp"
#include "output.hpp"
#include "terminal.hpp"

namespace ccal::cli {
namespace {

struct BudgetOptionsCli {
  ConfigChoice config;
  BudgetOptions options;  // its table's flags are bound to it
  std::size_t top = 0;  // 0: what fits the screen
  WidthOptions width;
  OutputOptions output;
};

}  // namespace

Command add_budget(CLI::App& app) {
  auto options = std::make_shared<BudgetOptionsCli>();
  CLI::App* cmd = app.add_subcommand(
      "budget", "Error budget: what each centrifuge tolerance costs every identified coefficient");
  add_config_argument(*cmd, options->config);
  add_option_flags(*cmd, options->options, option_table<BudgetOptions>());
  add_renamed_option(*cmd, "--coverage",
                     "renamed: give the coverage probability as --coverage-probability p (e.g. 0.95), as in "
                     "every command, or a stated factor k as --coverage-factor K (e.g. 2)");
  cmd->add_option("--top", options->top,
                  "Sources listed per coefficient, the rest summed in one row (default: what fits the "
                  "screen, at least 5)")
      ->transform(whole_number_in_digits())
      ->check(CLI::Range(1, 100000))
      ->type_name("N");
  add_width_options(*cmd, options->width,
                    "Everything: every source, uncut names, all of EA-4/02's columns (type, x_i, nu_i, unit "
                    "of c_i), exact-vs-paper flags, force and rate paths, compensation choices, "
                    "observability; no width limit");
  add_output_options(*cmd, options->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal budget\n"
      "      the budget of the bundled paper example (exact kinematics)\n"
      "  ccal budget examples/wang_ren_2014.toml --mode paper --top 10\n"
      "  ccal budget --wide --coverage-probability 0.99\n"
      "      every source, U at p = 99 % (k = 2.58); --coverage-factor 2 states k instead\n"
      "  ccal budget my.toml --format csv -o budget.csv\n"
      "  ccal budget examples/two_instruments.toml\n"
      "      a test of several instruments: each one's budget, then the correlation of their coefficients\n");
  return {cmd, [options] {
            const verbs::BudgetResult r =
                verbs::budget(load_config_or_example(options->config), options->options);
            print_warnings(r.observability.warnings);
            for (const verbs::BudgetResult& one : r.instruments) {  // a test of several: each one's, by its id
              std::vector<std::string> warnings;
              for (const std::string& w : one.observability.warnings)
                warnings.push_back("instrument " + one.config.instrument_id + ": " + w);
              print_warnings(warnings);
            }
            const std::string& f = options->output.format;
            const TerminalSize terminal = output_terminal(options->output);
            render::BudgetTextOptions to;
            to.width = text_width(options->width, terminal);
            to.wide = options->width.wide;
            to.top = options->top;
            if (terminal.rows > 0) to.screen_rows = terminal.rows;
            write_output(options->output, f == "json"  ? render::json(r)
                                          : f == "csv" ? render::csv(r)
                                                       : render::text(r, to));
          }};
}

}  // namespace ccal::cli
