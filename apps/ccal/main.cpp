// ccal command-line tool: parse the command line, call the library, print. Exit codes: 0 success, 2 bad input
// (configuration, units, options), 1 internal error. Errors are one line on standard error.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "ccal/errors.hpp"
#include "ccal/version.hpp"
#include "commands.hpp"

namespace {
constexpr int kBadInput = 2;
constexpr int kInternal = 1;

int report(std::string_view kind, std::string_view message) {
  std::string line(message);
  for (char& c : line)
    if (c == '\n') c = ' ';
  std::cerr << "ccal: " << kind << ": " << line << '\n';
  return kind == "error" ? kBadInput : kInternal;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "ccal: precision-centrifuge calibration of accelerometers (error budget of centrifuge errors on "
      "identified coefficients).",
      "ccal"};
  app.set_version_flag("--version", std::string("ccal ") + ccal::version());
  app.require_subcommand(1);
  app.footer(
      "Examples:\n"
      "  ccal budget                     error budget of the bundled paper example\n"
      "  ccal montecarlo --trials 2000   Monte Carlo (JCGM 101) of the same budget\n"
      "  ccal allocate --target K2=1e-7 --target K3=1e-6   largest tolerances meeting both targets\n"
      "  ccal force                      sensed input, run 1 of the bundled paper example\n"
      "  ccal force examples/wang_ren_2014.toml --run 20g --time \"10 s\" --format json\n"
      "  ccal simulate --observations-out obs.csv   run means of the paper's plan and the identified K0, K2, "
      "K3\n"
      "  ccal identify obs.csv                      least-squares fit of the observations file\n"
      "  ccal reduce my.toml --log 20g=run20.csv …  recorded run logs to run means and coefficients\n"
      "Run 'ccal <command> --help' for the options of a command.\n");

  std::vector<ccal::cli::Command> commands;
  commands.push_back(ccal::cli::add_budget(app));
  commands.push_back(ccal::cli::add_force(app));
  commands.push_back(ccal::cli::add_simulate(app));
  commands.push_back(ccal::cli::add_identify(app));
  commands.push_back(ccal::cli::add_reduce(app));
  commands.push_back(ccal::cli::add_montecarlo(app));
  commands.push_back(ccal::cli::add_allocate(app));

  // A first word that is not an option must name a command; say so plainly rather than "a subcommand is
  // required".
  if (argc > 1 && argv[1][0] != '-') {
    std::string names;
    bool known = false;
    for (const auto& command : commands) {
      known = known || command.app->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + command.app->get_name();
    }
    if (!known) return report("error", std::string("unknown command '") + argv[1] + "'; accepted: " + names);
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    return report("error", std::string(e.what()) + "; run 'ccal --help'");
  }

  try {
    for (const auto& command : commands)
      if (command.app->parsed()) command.run();
    return 0;
  } catch (const ccal::InputError& e) {
    return report("error", e.what());
  } catch (const CLI::Error& e) {
    return report("error", e.what());
  } catch (const std::exception& e) {
    return report("internal error", e.what());
  } catch (...) {
    return report("internal error", "unknown exception");
  }
}
