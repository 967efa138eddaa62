// ccal command-line tool: parse the command line, call the library, print. Exit codes: 0 success, 2 bad input
// (configuration, units, options), 1 internal error. Errors are one line on standard error.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <exception>
#include <memory>
#include <optional>
#include <iostream>
#include <string>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/version.hpp"
#include "commands.hpp"
#include "completion.hpp"
#include "help_format.hpp"
#include "option_flags.hpp"
#include "output.hpp"
#include "shell_docs.hpp"

namespace {
constexpr int kBadInput = 2;
constexpr int kInternal = 1;

// The message as one printable line: control characters (a newline, a terminal escape sequence echoed from
// an input file) shown as \xNN, and a huge message (a whole CSV cell echoed back) shortened in the middle, so
// that its start (the place) and its end (what would be accepted) both remain. UTF-8 text passes unchanged.
std::string printable_line(std::string_view message) {
  constexpr std::size_t kHead = 400, kTail = 300;
  std::string line;
  for (unsigned char c : message) {
    if (c == '\n' || c == '\t')
      line += ' ';
    else if (c < 0x20 || c == 0x7f)
      line += fmt::format("\\x{:02x}", c);
    else
      line += char(c);
  }
  if (line.size() <= kHead + kTail + 40) return line;
  auto boundary = [&](std::size_t k) {  // back to the start of a UTF-8 character
    while (k > 0 && (static_cast<unsigned char>(line[k]) & 0xc0) == 0x80) --k;
    return k;
  };
  const std::size_t head = boundary(kHead), tail = boundary(line.size() - kTail);
  return line.substr(0, head) + fmt::format(" […{} bytes left out…] ", tail - head) + line.substr(tail);
}

int report(std::string_view kind, std::string_view message) {
  std::cerr << "ccal: " << kind << ": " << printable_line(message) << '\n';
  return kind == "error" ? kBadInput : kInternal;
}

// ccal --man-page and ccal --completion SHELL, from the declarations of `app` (shell_docs.hpp, completion.hpp):
// the exit code when the command line asks for one of them, else nothing.
std::optional<int> write_shell_docs(const CLI::App& app, std::string_view summary, int argc, char** argv) {
  if (argc > 1 && std::string_view(argv[1]) == "--man-page") {
    if (argc > 2)
      return report("error", fmt::format("--man-page: takes no argument, got '{}'; accepted: ccal --man-page alone "
                                         "(e.g. ccal --man-page > ccal.1)",
                                         argv[2]));
    std::cout << ccal::cli::man_page(app, summary, ccal::version());
    return 0;
  }
  if (argc > 1 && std::string_view(argv[1]) == "--completion") {
    const auto& shells = ccal::cli::kCompletionShells;
    const bool known = argc > 2 && std::find(shells.begin(), shells.end(), argv[2]) != shells.end();
    if (argc != 3 || !known) {
      // What is wrong: no shell, a shell ccal does not complete, or a word after a known shell.
      const std::string wrong = argc == 2 ? std::string("needs the shell's name; ")
                                : !known  ? fmt::format("'{}' is not a shell ccal completes; ", argv[2])
                                          : fmt::format("takes one shell, and '{}' is a word too many; ", argv[3]);
      return report("error", fmt::format("--completion: {}accepted: bash, zsh or fish (e.g. source <(ccal "
                                         "--completion bash))",
                                         wrong));
    }
    std::cout << ccal::cli::completion_script(app, argv[2]);
    return 0;
  }
  return std::nullopt;
}
}  // namespace

namespace ccal::cli {
namespace {
std::string& stored_command_line() {
  static std::string text;
  return text;
}
}  // namespace

void set_command_line(int argc, char** argv) {
  std::string& text = stored_command_line();
  text.clear();
  for (int k = 0; k < argc; ++k) {
    const std::string_view a = k == 0 ? std::string_view("ccal") : std::string_view(argv[k]);
    const bool plain = !a.empty() && a.find_first_not_of(
                                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                         "0123456789-_=.,/:+@%") == std::string_view::npos;
    std::string quoted;
    if (!plain) {
      quoted = "'";
      for (char c : a) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
      quoted += "'";
    }
    text += (k ? " " : "") + (plain ? std::string(a) : quoted);
  }
}

std::string command_line_text() { return stored_command_line(); }
// The same check for the command of a command that has them (ccal history show): its word, or its lack, as
// the top-level command's; "" when there is no problem.
std::string subcommand_problem(const std::vector<Command>& commands, int argc, char** argv) {
  for (const Command& command : commands) {
    if (argc < 2 || command.app->get_name() != argv[1] || command.app->get_require_subcommand_min() == 0) continue;
    std::vector<std::string> names;
    for (const CLI::App* sub : command.app->get_subcommands([](const CLI::App*) { return true; }))
      names.push_back(sub->get_name());
    const std::string_view next = argc > 2 ? argv[2] : "";
    if (next == "-h" || next == "--help") return "";
    if (next.empty() || next[0] == '-') return unknown_command_message("", names, argv[1]);
    if (std::find(names.begin(), names.end(), next) == names.end())
      return unknown_command_message(next, names, argv[1]);
  }
  return "";
}

}  // namespace ccal::cli

namespace {

// The program's own help: its layout (help_format.hpp; before the commands are added, which inherit it), -V
// and the examples.
void describe_program(CLI::App& app) {
  app.formatter(std::make_shared<ccal::cli::HelpFormatter>());
  app.set_version_flag("-V,--version", ccal::version_line());
  app.require_subcommand(1);
  app.footer(
      "Examples:\n"
      "  ccal budget                     error budget of the bundled paper example\n"
      "  ccal montecarlo --trials 2000   Monte Carlo (JCGM 101) of the same budget\n"
      "  ccal allocate --target K2=2e-5 --target K3=2e-3   largest tolerances meeting both targets\n"
      "  ccal design --plan-out designed.toml   the test plan under which the tolerances cost least\n"
      "  ccal force                      sensed input, run 1 of the bundled paper example\n"
      "  ccal force examples/wang_ren_2014.toml --run 20g --time \"10 s\" --format json\n"
      "  ccal simulate --observations-out obs.csv   run means of the paper's plan and the identified K0, K2, "
      "K3\n"
      "  ccal identify obs.csv                      least-squares fit of the observations file\n"
      "  ccal reduce my.toml --log 20g=run20.csv …  recorded run logs to run means and coefficients\n"
      "  ccal report -o report.html                 the HTML report (budget, Monte Carlo, charts)\n"
      "  ccal report lab.toml --observations obs.csv --pdf certificate.pdf   the calibration certificate\n"
      "Run 'ccal <command> --help' for the options of a command; 'ccal --man-page' writes the manual page,\n"
      "'ccal --completion bash' (or zsh, fish) the shell's completion.\n");
}

// The commands, listed under "Commands:" (history's under its own).
std::vector<ccal::cli::Command> add_commands(CLI::App& app) {
  std::vector<ccal::cli::Command> commands;
  commands.push_back(ccal::cli::add_budget(app));
  commands.push_back(ccal::cli::add_force(app));
  commands.push_back(ccal::cli::add_simulate(app));
  commands.push_back(ccal::cli::add_identify(app));
  commands.push_back(ccal::cli::add_reduce(app));
  commands.push_back(ccal::cli::add_montecarlo(app));
  commands.push_back(ccal::cli::add_allocate(app));
  commands.push_back(ccal::cli::add_design(app));
  commands.push_back(ccal::cli::add_report(app));
  commands.push_back(ccal::cli::add_history(app));
  for (const auto& command : commands) {
    command.app->group("Commands");
    for (CLI::App* sub : command.app->get_subcommands([](CLI::App*) { return true; })) sub->group("Commands");
  }
  return commands;
}

// A first word that is not an option must name a command; say so plainly rather than "a subcommand is
// required", with the nearest command's name. No command at all, or an option the program does not take
// before one, gets the commands too. "" when the words can be parsed.
std::string first_word_problem(const std::vector<ccal::cli::Command>& commands, int argc, char** argv) {
  std::vector<std::string> names;
  for (const auto& command : commands) names.push_back(command.app->get_name());
  if (argc > 1 && argv[1][0] != '-' && std::find(names.begin(), names.end(), argv[1]) == names.end())
    return ccal::cli::unknown_command_message(argv[1], names);
  const std::string_view first = argc > 1 ? argv[1] : "";
  if (first.empty() || (first[0] == '-' && first != "-h" && first != "--help" && first != "-V" &&
                        first != "--version"))
    return (first.empty()
                ? std::string()
                : fmt::format("unknown option '{}' before a command (accepted there: -h, --help, -V, "
                              "--version, --man-page, --completion); ",
                              first)) +
           ccal::cli::unknown_command_message("", names) + "; run 'ccal --help'";
  return ccal::cli::subcommand_problem(commands, argc, argv);
}

// Parses the words and runs the chosen command; every error is reported with exit code 2 (an internal one
// named as such), never a crash.
int parse_and_run(CLI::App& app, const std::vector<ccal::cli::Command>& commands, int argc, char** argv) {
  // The chosen command (for its --help in a hint and the flags of its options), once parsed.
  const CLI::App* chosen = nullptr;
  // The help of the command being parsed: `ccal history show --help` for an error of history show.
  auto help_hint = [&] { return ccal::cli::help_hint(app, chosen); };
  try {
    try {
      if (argc > 1)
        for (const auto& command : commands)
          if (command.app->get_name() == argv[1]) chosen = command.app;
      app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
      if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
      return report("error",
                    ccal::cli::parse_error_message(e, chosen ? ccal::cli::deepest_command(*chosen) : app) +
                        help_hint());
    }
    for (const auto& command : commands)
      if (command.app->parsed()) command.run();
    return 0;
  } catch (const ccal::OptionError& e) {
    // Worded with the flag the command declared for the field (the library names the field).
    return report("error",
                  e.worded([&](std::string_view field) { return ccal::cli::declared_flag(chosen, field); }));
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

}  // namespace

int main(int argc, char** argv) {
  // The program in one line: the manual page's NAME, and the start of the help.
  constexpr std::string_view kSummary = "precision-centrifuge calibration of accelerometers";
  CLI::App app{fmt::format("ccal: {} (error budget of centrifuge errors on identified coefficients, test "
                           "plans, run logs to a calibration statement and certificate).",
                           kSummary),
               "ccal"};
  describe_program(app);
  const std::vector<ccal::cli::Command> commands = add_commands(app);
  ccal::cli::refuse_empty_input_paths(app);
  ccal::cli::set_command_line(argc, argv);
  if (const std::optional<int> code = write_shell_docs(app, kSummary, argc, argv)) return *code;
  if (const std::string problem = first_word_problem(commands, argc, argv); !problem.empty())
    return report("error", problem);
  return parse_and_run(app, commands, argc, argv);
}
