#include "option_flags.hpp"

#include <fmt/format.h>

#include <algorithm>
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
std::string parse_error_message(const CLI::ParseError& error) {
  const std::string what = error.what();
  static const std::regex at_most(R"(^(.*): At Most (\d+) required but received (\d+)$)");
  std::smatch m;
  if (!std::regex_match(what, m, at_most)) return what;
  const std::string once = m[2] == "1" ? "once (the last of several is not taken silently)" : m[2].str() + " times";
  return fmt::format("{}: given {} times; accepted: {}", m[1].str(), m[3].str(), once);
}

}  // namespace ccal::cli
