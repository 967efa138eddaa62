#pragma once
// The layout of every --help: CLI11's, but with the value of each option named as a user reads it, not as
// the parser types it. A choice option lists its values ("--format {text,json,csv}"), any other option the
// name of its value ("--trials N", "-o FILE"), and the default goes at the end of the help line
// ("(default: text)"); a positional is its value's name (CONFIG, SERIAL), in brackets in the usage line when
// it may be left out. Set on the top-level command before the subcommands are added, which inherit it.

#include <CLI/CLI.hpp>
#include <string>

namespace ccal::cli {

class HelpFormatter : public CLI::Formatter {
 public:
  HelpFormatter();  // "COMMAND" and "Commands" for CLI11's "SUBCOMMAND", "Arguments" for "Positionals"
  std::string make_option_name(const CLI::Option* option, bool is_positional) const override;
  std::string make_option_opts(const CLI::Option* option) const override;
  std::string make_option_desc(const CLI::Option* option) const override;
  std::string make_option_usage(const CLI::Option* option) const override;
};

// The name of an option's value as the help shows it: the declared name without the parser's additions
// (a validator's ":INT in [1 - 100000]"), "{a,b,c}" for a choice; empty for a flag.
std::string value_name(const CLI::Option& option);

// The name a positional goes by in the help and the usage line: its value's name (CONFIG, SERIAL).
std::string positional_name(const CLI::Option& option);

}  // namespace ccal::cli
