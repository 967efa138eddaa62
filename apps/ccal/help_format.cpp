#include "help_format.hpp"

#include <cctype>

#include "option_flags.hpp"

namespace ccal::cli {

std::string value_name(const CLI::Option& option) {
  if (option.get_expected_max() == 0) return "";
  if (const auto& choices = choices_of(&option); !choices.empty()) {
    std::string list;
    for (const std::string& c : choices) list += (list.empty() ? "" : ",") + c;
    return "{" + list + "}";
  }
  // CLI11 appends each validator's description after a ':' (N:INT in [1 - 100000]); the parser's own type
  // names for numbers (INT, UINT, FLOAT) read as N and X, as the options' rows name them.
  std::string name = option.get_type_name();
  name = name.substr(0, name.find(':'));
  if (name.empty()) return "";  // declared without one (a renamed option)
  if (name == "INT" || name == "UINT") return "N";
  if (name == "FLOAT") return "X";
  return name;
}

HelpFormatter::HelpFormatter() {
  label("SUBCOMMAND", "COMMAND");
  label("SUBCOMMANDS", "COMMAND");
  label("Subcommands", "Commands");
  label("Positionals", "Arguments");
}

std::string positional_name(const CLI::Option& option) {
  std::string name = value_name(option);
  if (name.empty() || name == "TEXT") {
    name = option.get_name(true, false);
    for (char& c : name) c = char(std::toupper(static_cast<unsigned char>(c)));
  }
  return name;
}

std::string HelpFormatter::make_option_name(const CLI::Option* option, bool is_positional) const {
  return is_positional ? positional_name(*option) : option->get_name(false, true);
}

std::string HelpFormatter::make_option_opts(const CLI::Option* option) const {
  if (option->get_positional()) return "";
  const std::string value = value_name(*option);
  return value.empty() ? "" : " " + value;
}

std::string HelpFormatter::make_option_desc(const CLI::Option* option) const {
  std::string text = option->get_description();
  const std::string& default_text = option->get_default_str();
  if (!default_text.empty() && option->get_expected_max() != 0 && text.find("default") == std::string::npos)
    text += " (default: " + default_text + ")";
  return text;
}

std::string HelpFormatter::make_option_usage(const CLI::Option* option) const {
  std::string name = positional_name(*option);
  if (option->get_expected_max() >= CLI::detail::expected_max_vector_size) name += "...";
  return option->get_required() ? name : "[" + name + "]";
}

}  // namespace ccal::cli
