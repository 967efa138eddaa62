#include "completion.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "help_format.hpp"
#include "option_flags.hpp"

namespace ccal::cli {

namespace {

// What follows an option (or stands for a positional) on the command line.
enum class ValueKind { none, choice, file, folder, other };

// An option or positional as every shell's completion needs it.
struct Word {
  std::vector<std::string> names;  // --format, -o (empty for a positional)
  ValueKind kind = ValueKind::none;
  std::vector<std::string> choices;
  std::string value;  // FORMAT, FILE, N
  std::string help;   // its first clause
  bool repeated = false;
  bool required = false;
};

struct Node {
  std::string path;  // "budget", "history show"
  std::string help;
  std::vector<Word> options, positionals;
  std::vector<Node> commands;
};

// The help's first clause, short enough for a completion menu.
std::string short_help(std::string text) {
  std::size_t cut = text.size();
  for (const std::string_view end : {". ", "; "})
    for (std::size_t at = text.find(end); at != std::string::npos; at = text.find(end, at + 1)) {
      const bool abbreviation = end == ". " && (text.substr(0, at).ends_with("e.g") ||
                                                 text.substr(0, at).ends_with("i.e"));
      if (at > 10 && !abbreviation) {
        cut = std::min(cut, at);
        break;
      }
    }
  text = text.substr(0, cut);
  if (!text.empty() && text.back() == '.') text.pop_back();
  if (text.size() > 90) text = text.substr(0, 87) + "...";
  return text;
}

Word word_of(const CLI::Option& o) {
  Word w;
  for (const auto& l : o.get_lnames()) w.names.push_back("--" + l);
  for (const auto& s : o.get_snames()) w.names.push_back("-" + s);
  w.help = short_help(o.get_description());
  w.required = o.get_required();
  w.repeated = o.get_expected_max() > 1 || o.get_multi_option_policy() == CLI::MultiOptionPolicy::TakeAll;
  if (o.get_expected_max() == 0) return w;
  w.value = o.get_positional() ? positional_name(o) : value_name(o);
  w.choices = choices_of(&o);
  if (!w.choices.empty()) w.value = o.get_type_name().substr(0, o.get_type_name().find(':'));  // FORMAT, MODE
  const std::string& v = w.value;
  w.kind = !w.choices.empty()                                                              ? ValueKind::choice
           : v == "DIR"                                                                    ? ValueKind::folder
           : v.starts_with("FILE") || v == "CONFIG" || v.find(".csv") != std::string::npos ? ValueKind::file
                                                                                           : ValueKind::other;
  return w;
}

Node node_of(const CLI::App& command, const std::string& path) {
  Node n{path, short_help(command.get_description()), {}, {}, {}};
  for (const CLI::Option* o : flags_of(command))
    if (o->get_group() != "Renamed") n.options.push_back(word_of(*o));
  for (const CLI::Option* o : command.get_options([](const CLI::Option* p) { return p->get_positional(); }))
    n.positionals.push_back(word_of(*o));
  for (const CLI::App* sub : commands_of(command))
    n.commands.push_back(node_of(*sub, path + " " + sub->get_name()));
  return n;
}

// The program's own top-level words.
Node program(const CLI::App& app) {
  Node n{"", "", {}, {}, {}};
  n.options.push_back({{"--help", "-h"}, ValueKind::none, {}, "", "Print the help and exit", false, false});
  n.options.push_back(
      {{"--version", "-V"}, ValueKind::none, {}, "", "Print the version and exit", false, false});
  n.options.push_back(
      {{"--man-page"}, ValueKind::none, {}, "", "Write the manual page (roff)", false, false});
  n.options.push_back({{"--completion"},
                       ValueKind::choice,
                       kCompletionShells,
                       "SHELL",
                       "Write the completion script of a shell",
                       false,
                       false});
  for (const CLI::App* c : commands_of(app)) n.commands.push_back(node_of(*c, c->get_name()));
  return n;
}

std::string join(const std::vector<std::string>& words, std::string_view separator = " ") {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : std::string(separator)) + w;
  return out;
}

// A text in single quotes for any of the three shells (fish reads \' inside them, bash and zsh '\'').
std::string single_quoted(std::string_view text, bool fish = false) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'')
      out += fish ? "\\'" : "'\\''";
    else if (c == '\\' && fish)
      out += "\\\\";
    else
      out += c;
  }
  return out + "'";
}

// ---- bash: one function; the case of a command (and of history's commands) lists its flags, the values of
// its choice options and which of its flags take a file, a folder or another value.
std::string bash_case(const Node& n) {
  std::string values, flags, files, folders, others;
  for (const Word& w : n.options)
    for (const std::string& name : w.names) {
      flags += " " + name;
      if (w.kind == ValueKind::choice)
        values += fmt::format("        {}) COMPREPLY=($(compgen -W \"{}\" -- \"$cur\")); return ;;\n", name,
                              join(w.choices));
      else if (w.kind != ValueKind::none)
        (w.kind == ValueKind::file ? files : w.kind == ValueKind::folder ? folders : others) += "|" + name;
    }
  for (const Node& sub : n.commands) flags += " " + sub.path.substr(sub.path.rfind(' ') + 1);
  bool file_argument = false;  // a positional that is a file: file names besides the flags
  for (const Word& w : n.positionals) file_argument = file_argument || w.kind == ValueKind::file;
  if (!files.empty())
    values += fmt::format("        {}) COMPREPLY=($(compgen -f -- \"$cur\")); return ;;\n", files.substr(1));
  if (!folders.empty())
    values +=
        fmt::format("        {}) COMPREPLY=($(compgen -d -- \"$cur\")); return ;;\n", folders.substr(1));
  if (!others.empty()) values += fmt::format("        {}) COMPREPLY=(); return ;;\n", others.substr(1));
  return fmt::format("    {})\n      case $prev in\n{}      esac\n      words=\"{}\" files={} ;;\n",
                     single_quoted(n.path), values, flags.empty() ? "" : flags.substr(1),
                     file_argument ? "yes" : "no");
}

std::string bash_script(const Node& top) {
  std::string cases = bash_case(top);
  std::string nested;  // the commands that have commands (history): their command is the second word too
  for (const Node& c : top.commands) {
    cases += bash_case(c);
    for (const Node& sub : c.commands) cases += bash_case(sub);
    if (!c.commands.empty()) nested += (nested.empty() ? "" : "|") + c.path;
  }
  return fmt::format(
      "# bash completion for ccal (made by `ccal --completion bash` from the program's own options)\n"
      "_ccal() {{\n"
      "  local cur=${{COMP_WORDS[COMP_CWORD]}} prev=${{COMP_WORDS[COMP_CWORD-1]}} command='' words='' "
      "files=no\n"
      "  # The command: ccal's first word, and the second too for a command of commands.\n"
      "  if ((COMP_CWORD > 1)) && [[ ${{COMP_WORDS[1]}} != -* ]]; then command=${{COMP_WORDS[1]}}; fi\n"
      "  case $command in\n    {}) ((COMP_CWORD > 2)) && command=\"$command ${{COMP_WORDS[2]}}\" ;;\n  esac\n"
      "  case $command in\n{}    *) return ;;\n  esac\n"
      "  COMPREPLY=($(compgen -W \"$words\" -- \"$cur\"))\n"
      "  # A word that is not a flag, where the command takes a file (a configuration, observations, a\n"
      "  # statement): file names too.\n"
      "  [[ $cur != -* && $files == yes ]] && COMPREPLY+=($(compgen -f -- \"$cur\"))\n"
      "  return 0\n"
      "}}\n"
      "complete -o filenames -F _ccal ccal\n",
      nested.empty() ? "''" : nested, cases);
}

// ---- zsh: an _arguments call per command, after the words before it are shifted away.
// A text inside an _arguments or _describe spec: brackets and backslashes escaped, and colons where they
// would end the field (a message, a command's name).
std::string zsh_escape(std::string_view text, bool colon = true) {
  std::string out;
  for (char c : text) {
    if (c == '[' || c == ']' || c == '\\' || (colon && c == ':')) out += '\\';
    out += c;
  }
  return out;
}

std::string zsh_action(const Word& w) {
  switch (w.kind) {
    case ValueKind::choice:
      return ":" + zsh_escape(w.value) + ":(" + join(w.choices) + ")";
    case ValueKind::file:
      return ":" + zsh_escape(w.value) + ":_files";
    case ValueKind::folder:
      return ":" + zsh_escape(w.value) + ":_files -/";
    case ValueKind::other:
      return ":" + zsh_escape(w.value) + ": ";
    case ValueKind::none:
      break;
  }
  return "";
}

std::string zsh_arguments(const Node& n) {
  std::string specs;
  for (const Word& w : n.options) {
    const std::string names = w.names.size() == 1 ? w.names.front() : "{" + join(w.names, ",") + "}";
    const std::string exclusive = w.names.size() == 1 || w.repeated ? "" : "(" + join(w.names) + ")";
    specs += fmt::format(" \\\n        {}{}{}", (w.repeated || !exclusive.empty() ? single_quoted((w.repeated ? "*" : "") + exclusive) : ""), names,
                         single_quoted("[" + zsh_escape(w.help, false) + "]" + zsh_action(w)));
  }
  int k = 0;
  for (const Word& w : n.positionals)
    specs += " \\\n        " +
             single_quoted(fmt::format("{}:{}", ++k, w.required ? "" : ":") + zsh_escape(w.value) + ":" +
                           (w.kind == ValueKind::other ? " " : "_files"));
  return "_arguments -s" + specs;
}

std::string zsh_describe(const Node& n, std::string_view what) {
  std::string items;
  for (const Node& c : n.commands)
    items += " " + single_quoted(zsh_escape(c.path.substr(c.path.rfind(' ') + 1)) + ":" +
                                 zsh_escape(c.help, false));
  return fmt::format("local -a commands=({})\n      _describe -t commands {} commands", items.substr(1),
                     single_quoted(what));
}

std::string zsh_script(const Node& top) {
  std::string cases;
  for (const Node& c : top.commands) {
    if (c.commands.empty()) {
      cases += fmt::format("    {}) {} ;;\n", single_quoted(c.path), zsh_arguments(c));
      continue;
    }
    cases += fmt::format(
        "    {})\n      if ((CURRENT == 2)); then\n        {}\n        return\n      fi\n"
        "      local sub=${{words[2]}}\n      shift words; ((CURRENT--))\n      case $sub in\n",
        single_quoted(c.path), zsh_describe(c, "ccal " + c.path + " command"));
    for (const Node& sub : c.commands)
      cases += fmt::format("        {}) {} ;;\n", single_quoted(sub.path.substr(sub.path.rfind(' ') + 1)),
                           zsh_arguments(sub));
    cases += "      esac ;;\n";
  }
  return fmt::format(
      "#compdef ccal\n"
      "# zsh completion for ccal (made by `ccal --completion zsh` from the program's own options)\n"
      "_ccal() {{\n"
      "  if ((CURRENT == 2)); then\n"
      "    if [[ $PREFIX == -* ]]; then\n      {}\n    else\n      {}\n    fi\n"
      "    return\n"
      "  fi\n"
      "  local command=${{words[2]}}\n"
      "  shift words; ((CURRENT--))\n"
      "  case $command in\n"
      "    --completion) ((CURRENT == 2)) && _values shell {} ;;\n"
      "{}  esac\n"
      "}}\n"
      "if [[ $zsh_eval_context[-1] == loadautofunc ]]; then _ccal \"$@\"; else compdef _ccal ccal; fi\n",
      zsh_arguments(top), zsh_describe(top, "ccal command"), join(kCompletionShells), cases);
}

// ---- fish: one `complete` line per command, option and command of commands, each under its condition.
std::string fish_option(const Word& w, const std::string& condition) {
  std::string line = "complete -c ccal -n " + single_quoted(condition, true);
  for (const std::string& name : w.names)
    line += name.starts_with("--") ? " -l " + name.substr(2) : " -s " + name.substr(1);
  if (w.kind == ValueKind::choice) line += " -x -a " + single_quoted(join(w.choices), true);
  if (w.kind == ValueKind::file) line += " -r -F";
  if (w.kind == ValueKind::folder) line += " -x -a '(__fish_complete_directories)'";
  if (w.kind == ValueKind::other) line += " -x";
  return line + " -d " + single_quoted(w.help, true) + "\n";
}

std::string fish_node(const Node& n, const std::string& condition) {
  std::string out;
  for (const Word& w : n.options) out += fish_option(w, condition);
  for (const Word& w : n.positionals)
    if (w.kind == ValueKind::file || w.kind == ValueKind::folder)
      out += "complete -c ccal -n " + single_quoted(condition, true) + " -F\n";
  std::vector<std::string> names;
  for (const Node& c : n.commands) names.push_back(c.path.substr(c.path.rfind(' ') + 1));
  for (const Node& c : n.commands) {
    const std::string name = c.path.substr(c.path.rfind(' ') + 1);
    out +=
        fmt::format("complete -c ccal -n {} -a {} -d {}\n",
                    single_quoted(condition + "; and not __fish_seen_subcommand_from " + join(names), true),
                    name, single_quoted(c.help, true));
    out += fish_node(c, (n.path.empty() ? "" : condition + "; and ") + "__fish_seen_subcommand_from " + name);
  }
  return out;
}

std::string fish_script(const Node& top) {
  std::string out =
      "# fish completion for ccal (made by `ccal --completion fish` from the program's own options)\n"
      "complete -c ccal -f\n";
  Node first = top;
  first.commands.clear();
  out += fish_node(first, "__fish_use_subcommand");
  std::vector<std::string> names;
  for (const Node& c : top.commands) names.push_back(c.path);
  for (const Node& c : top.commands) {
    out += fmt::format("complete -c ccal -n __fish_use_subcommand -a {} -d {}\n", c.path,
                       single_quoted(c.help, true));
    out += fish_node(c, "__fish_seen_subcommand_from " + c.path);
  }
  return out;
}

}  // namespace

std::vector<const CLI::App*> commands_of(const CLI::App& app) {
  return app.get_subcommands([](const CLI::App* c) { return !c->get_name().empty(); });
}

std::vector<const CLI::Option*> flags_of(const CLI::App& command) {
  return command.get_options([](const CLI::Option* o) {
    return !o->get_lnames().empty() && !o->get_group().empty() && o->get_lnames().front() != "help";
  });
}

std::string completion_script(const CLI::App& app, std::string_view shell) {
  const Node top = program(app);
  if (shell == "zsh") return zsh_script(top);
  if (shell == "fish") return fish_script(top);
  return bash_script(top);
}

}  // namespace ccal::cli
