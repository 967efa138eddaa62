#pragma once
// The command line's flags of a verb, declared from the verb's options table (core/options.hpp): one flag per
// row, named after the field (option_flag, core/options.hpp), bound to the verb's options struct, whose values are the defaults
// the help shows. Numbers are read by the library's parsers, so that 1e5 is a whole number and an error
// echoes what was typed; the range is checked by the verb itself, so the command line refuses what Python and
// the library refuse, in the same words but for the option's name.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/core/options.hpp"

namespace ccal::cli {

// The flag a field of the command `command` was declared with (add_option_flags), for the message of an
// OptionError; option_flag(field) (core/options.hpp) when the command did not declare it.
std::string declared_flag(const CLI::App* command, std::string_view field);

// "unknown command 'X'; accepted: a, b, c", with "did you mean 'b'?" when nearest_name (the library's
// did-you-mean, io/config_file.hpp) finds one; of a command's subcommands (parent "history"): "unknown
// command 'ccal history X'; …". typed empty: none was given.
std::string unknown_command_message(std::string_view typed, const std::vector<std::string>& names,
                                    std::string_view parent = {});

// A parse error's message as the program words it, for the command being parsed: an option given more often
// than it is taken ("--x: At Most 1 required but received 2", the parser's) is "--x: given 2 times; accepted:
// once"; an option without its value ("--x: 1 required N missing") and a missing argument ("SERIAL is
// required") say so with how the option is written and its help; any other as the parser says.
std::string parse_error_message(const CLI::ParseError& error, const CLI::App& command);

// The subcommand being run: the deepest parsed one below `app` (`ccal history show`: show), else app itself.
const CLI::App& deepest_command(const CLI::App& app);
// "; run 'ccal history show --help'": the help of the command being parsed below `chosen`, the command the
// first word named (none: the program's help).
std::string help_hint(const CLI::App& app, const CLI::App* chosen);

// Declares a flag for every row of `table` on `command`, bound to `options` (which must outlive the parse),
// except the fields named in `skip` (bound by hand by the command).
template <class Options>
void add_option_flags(CLI::App& command, Options& options, OptionTable<Options> table,
                      std::initializer_list<std::string_view> skip = {}, std::string_view prefix = "");

// The values a choice option accepts (an enumeration row's names, --format's formats), recorded when the
// option is declared, for the help (help_format.hpp) and the shell completions (shell_docs.hpp); empty for an
// option that is not a choice.
void remember_choices(const CLI::Option* option, std::vector<std::string> choices);
const std::vector<std::string>& choices_of(const CLI::Option* option);

namespace detail {
void remember_flag(const CLI::App* command, std::string_view field, const std::string& flag);
CLI::Option* add_text_flag(CLI::App& command, const std::string& flag, std::string_view help,
                           std::function<void(const std::string&)> set);

// "0.5,0.75,1" (repeated flags too) into `value`: split here rather than by CLI11, which drops empty items,
// so that "1,,2", a typing error, is refused.
inline void parse_number_list(std::vector<double>& value, const std::string& field,
                              const std::vector<std::string>& texts) {
  value.clear();
  for (const std::string& t : texts)
    for (std::size_t begin = 0;;) {
      const std::size_t end = std::min(t.find(',', begin), t.size());
      const std::string item = t.substr(begin, end - begin);
      if (item.empty())
        throw OptionError(field, t,
                          "has an empty item; accepted: numbers separated by single commas, e.g. 0.5,0.75,1");
      try {
        value.push_back(parse_real_option(field, item));
      } catch (const OptionError&) {
        throw OptionError(field, "'" + item + "'", "is not a finite number; accepted: numbers separated by single commas, e.g. "
                                       "0.5,0.75,1");
      }
      if (end == t.size()) break;
      begin = end + 1;
    }
}

// An enumeration row: its names are the choices, the current one the default.
template <class Options>
CLI::Option* add_choice_flag(CLI::App& command, Options& options, const OptionSpec<Options>& row,
                             const OptionEnum<Options> e, const std::string& flag, const std::string& help) {
  const std::string field(row.field);
  CLI::Option* option = add_text_flag(command, flag, help, [&options, e, field](const std::string& text) {
    e.set(options, parse_choice_option(field, text, e.names));
  });
  if (const auto index = e.get(options)) option->default_str(std::string(e.names[*index]));
  option->type_name(std::string(row.value_name));
  remember_choices(option, std::vector<std::string>(e.names.begin(), e.names.end()));
  return option;
}

// A number, or an optional one (Field: a number or std::optional of one), read by the library's parsers
// (integers within the row's range), its default shown when it has one.
template <class Field, class Range>
CLI::Option* add_number_flag(CLI::App& command, Field& value, const std::string& field, Range range,
                             const std::string& flag, const std::string& help) {
  using Number = std::remove_cvref_t<decltype([] {
    if constexpr (requires { typename Field::value_type; })
      return typename Field::value_type{};
    else
      return Field{};
  }())>;
  CLI::Option* option = add_text_flag(command, flag, help, [&value, field, range](const std::string& text) {
    if constexpr (std::is_floating_point_v<Number>)
      value = parse_real_option(field, text, range);
    else if constexpr (std::is_unsigned_v<Number>)
      value = Number(parse_unsigned_option(field, text, range));
    else
      value = Number(parse_integer_option(field, text, std::numeric_limits<Number>::min(),
                                          std::numeric_limits<Number>::max(), range));
  });
  if constexpr (requires { typename Field::value_type; }) {
    if (value)
      option->default_str(option_value_text(*value));
    else if (!range.unset_text.empty())
      option->default_str(std::string(range.unset_text));  // what unset stands for
  } else {
    option->default_str(option_value_text(value));
  }
  return option;
}

template <class Options, class Member>
void add_one_flag(CLI::App& command, Options& options, const OptionSpec<Options>& row, Member member,
                  const std::string& flag) {
  const std::string field(row.field);
  const std::string help = option_help(row.help, row.range);
  if constexpr (std::is_same_v<Member, OptionEnum<Options>>) {
    add_choice_flag(command, options, row, member, flag, help);
  } else {
    using Field = typename Member::type;
    Field& value = member.of(options);
    CLI::Option* option = nullptr;
    if constexpr (std::is_same_v<Field, bool>) {
      option = command.add_flag(flag, value, help);
    } else if constexpr (std::is_same_v<Field, std::string>) {
      option = command.add_option(flag, value, help);
      if (!value.empty()) option->default_str(value);
    } else if constexpr (std::is_same_v<Field, std::vector<std::string>>) {
      option = command.add_option(flag, value, help)->allow_extra_args(false);
      if (row.required) option->required();
    } else if constexpr (std::is_same_v<Field, std::optional<std::vector<std::string>>>) {
      // Set only when given (unset: the verb's default, e.g. the file's terms); comma-separated or repeated.
      // Split here rather than by CLI11, which drops empty items: "K0,,K2" is a typing error.
      option = command
                   .add_option_function<std::vector<std::string>>(
                       flag,
                       [&value, field](const std::vector<std::string>& texts) {
                         std::vector<std::string> items;
                         for (const std::string& text : texts)
                           for (std::string& item : split_option_list(field, text)) items.push_back(std::move(item));
                         value = std::move(items);
                       },
                       help)
                   ->allow_extra_args(false);
    } else if constexpr (std::is_same_v<Field, std::vector<double>>) {
      option = command.add_option_function<std::vector<std::string>>(
          flag,
          [&value, field](const std::vector<std::string>& texts) { parse_number_list(value, field, texts); },
          help);
    } else {
      option = add_number_flag(command, value, field, row.range, flag, help);
    }
    if (!row.value_name.empty() && !std::is_same_v<Field, bool>)
      option->type_name(std::string(row.value_name));
  }
  remember_flag(&command, row.field, flag);
}
}  // namespace detail

template <class Options>
void add_option_flags(CLI::App& command, Options& options, OptionTable<Options> table,
                      std::initializer_list<std::string_view> skip, std::string_view prefix) {
  for (const OptionSpec<Options>& row : table) {
    if (std::find(skip.begin(), skip.end(), row.field) != skip.end()) continue;
    const std::string flag = option_flag(row.field, prefix);
    std::visit([&](auto member) { detail::add_one_flag(command, options, row, member, flag); }, row.member);
  }
}

}  // namespace ccal::cli
