#pragma once
// The ccal subcommands. Each add_* function registers one subcommand with its options and returns the
// action to run when that subcommand is chosen; main() parses the command line, runs the chosen action and
// maps exceptions to exit codes. A new subcommand is one more cmd_<name>.cpp and one line in main.cpp.

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace ccal::cli {

struct Command {
  CLI::App* app = nullptr;    // the subcommand
  std::function<void()> run;  // runs it with the parsed options; throws on failure
};

Command add_force(CLI::App& app);
Command add_budget(CLI::App& app);
Command add_simulate(CLI::App& app);
Command add_identify(CLI::App& app);
Command add_montecarlo(CLI::App& app);
Command add_allocate(CLI::App& app);
Command add_reduce(CLI::App& app);
Command add_design(CLI::App& app);
Command add_report(CLI::App& app);
Command add_history(CLI::App& app);

// The command line as typed (arguments with spaces or shell characters in single quotes), for reports.
void set_command_line(int argc, char** argv);
std::string command_line_text();

}  // namespace ccal::cli
