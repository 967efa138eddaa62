// ccal budget: the error budget of the configured centrifuge tolerances on the identified coefficients.
#include <cmath>
#include <memory>

#include "ccal/render/budget.hpp"
#include "ccal/verbs/budget.hpp"
#include "commands.hpp"
#include "output.hpp"

namespace ccal::cli {
namespace {

struct BudgetOptionsCli {
  std::string config;
  std::string mode;  // empty: the configuration's
  double coverage = 2.0;
  std::string derivatives = "linearised";
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
      ->check(CLI::IsMember({"exact", "paper"}));
  cmd->add_option("--coverage", options->coverage, "Coverage factor k of the expanded uncertainty U = k u")
      ->check(CLI::Validator(
          [](std::string& text) {
            double k = 0;
            return CLI::detail::lexical_cast(text, k) && std::isfinite(k) && k > 0
                       ? std::string()
                       : "'" + text + "' is not a positive number; accepted: a coverage factor such as 2";
          },
          "K > 0"))
      ->capture_default_str();
  cmd->add_option(
         "--derivatives", options->derivatives,
         "How the sensitivities are differentiated: linearised (closed-form chain Jacobian at zero "
         "errors, AD elsewhere; fast) or automatic (forward-mode AD through everything); same numbers")
      ->check(CLI::IsMember({"linearised", "automatic"}))
      ->capture_default_str();
  add_output_options(*cmd, options->output, {"text", "json", "csv"});
  cmd->footer(
      "Examples:\n"
      "  ccal budget\n"
      "      the budget of the bundled paper example (exact kinematics)\n"
      "  ccal budget examples/wang_ren_2014.toml --mode paper\n"
      "  ccal budget my.toml --format csv -o budget.csv\n");
  return {cmd, [options] {
            verbs::BudgetOptions bo;
            if (!options->mode.empty()) bo.mode = parse_mode(options->mode);
            bo.coverage_factor = options->coverage;
            bo.derivatives = options->derivatives == "automatic" ? DerivativeMethod::automatic
                                                                 : DerivativeMethod::linearised;
            const verbs::BudgetResult r = verbs::budget(load_config_or_example(options->config), bo);
            print_warnings(r.observability.warnings);
            const std::string& f = options->output.format;
            write_output(options->output, f == "json"  ? render::json(r)
                                          : f == "csv" ? render::csv(r)
                                                       : render::text(r));
          }};
}

}  // namespace ccal::cli
