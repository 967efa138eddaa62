// ccal budget: the error budget of the configured centrifuge tolerances on the identified coefficients.
#include <cmath>
#include <memory>

#include "ccal/render/budget.hpp"
#include "ccal/verbs/budget.hpp"
#include "commands.hpp"
#include "output.hpp"
#include "terminal.hpp"

namespace ccal::cli {
namespace {

struct BudgetOptionsCli {
  std::string config;
  std::string mode;  // empty: the configuration's
  double coverage_factor = 2.0;
  std::string derivatives = "linearised";
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
  cmd->add_option(
         "--mode", options->mode,
         "Kinematics: exact (full chain) or paper (Wang & Ren first-order rules); default: the config's")
      ->check(mode_names_check());
  cmd->add_option("--coverage-factor", options->coverage_factor,
                  "Coverage factor k >= 1 of the expanded uncertainty U = k u")
      ->check(CLI::Validator(
          [](std::string& text) {
            double k = 0;
            return CLI::detail::lexical_cast(text, k) && std::isfinite(k) && k >= 1
                       ? std::string()
                       : "'" + text +
                             "' is not a coverage factor k >= 1; accepted: e.g. 2 (U = k u); a probability "
                             "such as 0.95 is --coverage-probability of montecarlo and allocate";
          },
          "K >= 1"))
      ->capture_default_str()
      ->type_name("K");
  add_renamed_option(*cmd, "--coverage",
                     "renamed: give the coverage factor k as --coverage-factor K (e.g. 2); a coverage "
                     "probability is --coverage-probability of montecarlo and allocate");
  cmd->add_option(
         "--derivatives", options->derivatives,
         "How the sensitivities are differentiated: linearised (closed-form chain Jacobian at zero "
         "errors, AD elsewhere; fast) or automatic (forward-mode AD through everything); same numbers")
      ->check(CLI::IsMember({"linearised", "automatic"}))
      ->capture_default_str();
  cmd->add_option("--top", options->top,
                  "Sources listed per coefficient, the rest summed in one row (default: what fits the "
                  "screen, at least 5)")
      ->check(CLI::Range(1, 100000))
      ->type_name("N");
  add_width_options(*cmd, options->width,
                    "Everything: every source, uncut names, exact-vs-paper flags, force and rate paths, "
                    "compensation choices, observability; no width limit");
  add_output_options(*cmd, options->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal budget\n"
      "      the budget of the bundled paper example (exact kinematics)\n"
      "  ccal budget examples/wang_ren_2014.toml --mode paper --top 10\n"
      "  ccal budget --wide --coverage-factor 3\n"
      "  ccal budget my.toml --format csv -o budget.csv\n");
  return {cmd, [options] {
            verbs::BudgetOptions bo;
            if (!options->mode.empty()) bo.mode = parse_mode(options->mode);
            bo.coverage_factor = options->coverage_factor;
            bo.derivatives = options->derivatives == "automatic" ? DerivativeMethod::automatic
                                                                 : DerivativeMethod::linearised;
            const verbs::BudgetResult r = verbs::budget(load_config_or_example(options->config), bo);
            print_warnings(r.observability.warnings);
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
