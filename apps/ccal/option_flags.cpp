#include "option_flags.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <regex>
#include <string>
#include <utility>

#include "ccal/io/config_file.hpp"  // nearest_name: the did-you-mean of every mistyped name

namespace ccal::cli {

namespace {

std::map<std::pair<const CLI::App*, std::string>, std::string>& declared() {
  static std::map<std::pair<const CLI::App*, std::string>, std::string> flags;
  return flags;
}

std::map<const CLI::Option*, std::vector<std::string>>& choices() {
  static std::map<const CLI::Option*, std::vector<std::string>> values;
  return values;
}

}  // namespace

void remember_choices(const CLI::Option* option, std::vector<std::string> values) {
  choices()[option] = std::move(values);
}

const std::vector<std::string>& choices_of(const CLI::Option* option) {
  static const std::vector<std::string> none;
  const auto found = choices().find(option);
  return found != choices().end() ? found->second : none;
}

std::string declared_flag(const CLI::App* command, std::string_view field) {
  const auto found = declared().find({command, std::string(field)});
  return found != declared().end() ? found->second : option_flag(field);
}

std::string unknown_command_message(std::string_view typed, const std::vector<std::string>& names,
                                    std::string_view parent) {
  std::string accepted;
  for (const std::string& name : names) accepted += (accepted.empty() ? "" : ", ") + name;
  const std::string prefix = parent.empty() ? "" : "ccal " + std::string(parent) + " ";
  if (typed.empty())
    return "'" + (prefix.empty() ? std::string("ccal ") : prefix) + "…' needs a command; accepted: " + accepted;
  const std::optional<std::string> nearest = nearest_name(typed, names);
  return "unknown command '" + prefix + std::string(typed) + "'" +
         (nearest ? "; did you mean '" + prefix + *nearest + "'?" : ";") + " accepted: " + accepted;
}

namespace detail {

void remember_flag(const CLI::App* command, std::string_view field, const std::string& flag) {
  declared().emplace(std::make_pair(command, std::string(field)), flag);
}

CLI::Option* add_text_flag(CLI::App& command, const std::string& flag, std::string_view help,
                           std::function<void(const std::string&)> set) {
  return command.add_option_function<std::string>(flag, std::move(set), std::string(help));
}

}  // namespace detail
const CLI::App& deepest_command(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands())
    if (sub->parsed()) return deepest_command(*sub);
  return app;
}

std::string help_hint(const CLI::App& app, const CLI::App* chosen) {
  if (!chosen) return "; run 'ccal --help'";
  std::string path;
  for (const CLI::App* c = &deepest_command(*chosen); c != nullptr && c != &app; c = c->get_parent())
    path = " " + c->get_name() + path;
  return "; run 'ccal" + path + " --help'";
}

namespace {

// An option or argument of the command by the name the parser gives it ("--trials", "SERIAL").
const CLI::Option* option_named(const CLI::App& command, const std::string& name) {
  for (const CLI::Option* option : command.get_options())
    if (option->get_name() == name || option->check_name(name)) return option;
  return nullptr;
}

// "--trials N (Number of trials M (default 1000000); …)": how the option is written, and its help.
std::string accepted_form(const CLI::App& command, const std::string& name) {
  const CLI::Option* option = option_named(command, name);
  if (option == nullptr) return "a value";
  const std::string type = option->get_type_name();
  const std::string form = option->nonpositional() ? name + (type.empty() ? "" : " " + type) : type;
  const std::string help = option->get_description();
  return help.empty() ? form : fmt::format("{} ({})", form, help);
}

// The words a command did not take, as the parser lists them ("X --instrument"): the first that looks like an
// option (a dash and a letter) is one the command does not have, said so with the nearest of its options; ""
// when none looks like one.
std::string unknown_option_message(const std::string& words, const CLI::App& command) {
  static const std::regex option_like(R"((?:^|\s)(--?[A-Za-z][^\s=]*))");
  std::smatch m;
  if (!std::regex_search(words, m, option_like)) return {};
  const std::string typed = m[1].str();
  std::vector<std::string> names;
  std::string accepted;
  for (const CLI::Option* option : command.get_options()) {
    // Hidden or renamed options are refused with a message of their own: not offered.
    if (!option->nonpositional() || option->get_group().empty() || option->get_group() == "Renamed") continue;
    for (const std::string& name : option->get_lnames()) names.push_back("--" + name);
    const std::string shown = option->get_lnames().empty() ? "-" + option->get_snames().front()
                                                           : "--" + option->get_lnames().front();
    accepted += (accepted.empty() ? "" : ", ") + shown;
  }
  const std::optional<std::string> nearest = nearest_name(typed, names);
  return fmt::format("{}: no such option;{} accepted: {}", typed,
                     nearest ? " did you mean '" + *nearest + "'?" : "", accepted);
}

}  // namespace

std::string parse_error_message(const CLI::ParseError& error, const CLI::App& command) {
  const std::string what = error.what();
  static const std::regex at_most(R"(^(.*): At Most (\d+) required but received (\d+)$)");
  // "--x: 1 required N missing": the option given last, without its value.
  static const std::regex value_missing(R"(^(\S+): \d+ required .* missing$)");
  // "--width: Value 5 not in range 40 to 10000": the parser's range check.
  static const std::regex out_of_range(R"(^(\S+): Value (.*) not in range (.*) to (.*)$)");
  // "The following argument was not expected: b": a word no argument or option of the command takes.
  static const std::regex extra(R"(^The following arguments? (?:was|were) not expected: (.*)$)");
  // "SERIAL is required": an argument the command needs, not given.
  static const std::regex argument_missing(R"(^(\S+) is required$)");
  // "--format: yaml not in {text,json,csv}": the parser's check of a choice.
  static const std::regex not_a_choice(R"(^(\S+): (.*) not in \{(.*)\}$)");
  std::smatch m;
  if (std::regex_match(what, m, at_most)) {
    const std::string once =
        m[2] == "1" ? "once (the last of several is not taken silently)" : m[2].str() + " times";
    return fmt::format("{}: given {} times; accepted: {}", m[1].str(), m[3].str(), once);
  }
  if (std::regex_match(what, m, value_missing))
    return fmt::format(
        "{}: its value is missing (nothing follows it, or the next word is an option); accepted: {}",
        m[1].str(), accepted_form(command, m[1].str()));
  if (std::regex_match(what, m, out_of_range)) {
    static const std::regex number(R"(^[-+]?[0-9.]+([eE][-+]?[0-9]+)?$)");
    // A count's ranges are whole: a fraction within them is not out of range but no count.
    static const std::regex whole(R"(^[-+]?[0-9]+$)");
    const bool is_number = std::regex_match(m[2].str(), number);
    const bool counts = std::regex_match(m[3].str(), whole) && std::regex_match(m[4].str(), whole);
    // Beyond the range (1e400, which no double holds, too) is out of range; a fraction within it no count.
    const double value = is_number ? std::strtod(m[2].str().c_str(), nullptr) : 0.0;
    const bool beyond = !std::isfinite(value) || value < std::strtod(m[3].str().c_str(), nullptr) ||
                        value > std::strtod(m[4].str().c_str(), nullptr);
    return fmt::format("{}: {} {}; accepted: a {} from {} to {}", m[1].str(), m[2].str(),
                       !is_number ? "is not a number" : counts && !beyond && !std::regex_match(m[2].str(), whole)
                                                            ? "is not a whole number"
                                                            : "is out of range",
                       counts ? "whole number" : "number", m[3].str(), m[4].str());
  }
  if (std::regex_match(what, m, not_a_choice)) {
    std::string names = m[3].str();
    for (std::size_t at = names.find(','); at != std::string::npos; at = names.find(',', at + 2))
      names.replace(at, 1, ", ");
    return fmt::format("{}: '{}' is not accepted; accepted: {}", m[1].str(), m[2].str(), names);
  }
  if (std::regex_match(what, m, extra)) {
    if (const std::string unknown = unknown_option_message(m[1].str(), command); !unknown.empty()) return unknown;
    std::string arguments;
    for (const CLI::Option* option : command.get_options())
      if (option->get_positional()) arguments += (arguments.empty() ? "" : ", ") + option->get_type_name();
    return fmt::format(
        "'{}': {}; accepted: {}, each option with its value (a path with spaces in quotes)", m[1].str(),
        "not expected (a word too many)",
        arguments.empty() ? std::string("no argument besides the options") : "one " + arguments);
  }
  if (std::regex_match(what, m, argument_missing))
    return fmt::format("{}: missing; accepted: {}", m[1].str(), accepted_form(command, m[1].str()));
  return what;
}

}  // namespace ccal::cli
