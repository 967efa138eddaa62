#include "shell_docs.hpp"

#include <fmt/format.h>

#include <vector>

namespace ccal::cli {

namespace {

// roff text: a backslash doubled, a leading dot or quote escaped, so that no line of help is a request.
std::string roff(std::string_view text) {
  std::string out;
  for (char c : text) out += c == '\\' ? std::string("\\e") : c == '-' ? std::string("\\-") : std::string(1, c);
  if (!out.empty() && (out.front() == '.' || out.front() == '\'')) out = "\\&" + out;
  return out;
}

std::vector<const CLI::App*> commands_of(const CLI::App& app) {
  return app.get_subcommands([](const CLI::App* c) { return !c->get_name().empty(); });
}

// The options a user can give a command (not the hidden ones, nor --help), in the order declared.
std::vector<const CLI::Option*> flags_of(const CLI::App& command) {
  return command.get_options([](const CLI::Option* o) {
    return !o->get_lnames().empty() && !o->get_group().empty() && o->get_lnames().front() != "help";
  });
}

std::string option_names(const CLI::Option& o) {
  std::string names;
  for (const auto& s : o.get_snames()) names += fmt::format("{}-{}", names.empty() ? "" : ", ", s);
  for (const auto& l : o.get_lnames()) names += fmt::format("{}--{}", names.empty() ? "" : ", ", l);
  return names;
}

std::string man_options(const CLI::App& command) {
  std::string out;
  for (const CLI::Option* o : command.get_options([](const CLI::Option* p) { return p->get_positional(); }))
    out += fmt::format(".TP\n\\fI{}\\fR\n{}\n", roff(o->get_type_name()), roff(o->get_description()));
  for (const CLI::Option* o : flags_of(command)) {
    const std::string type = o->get_expected_max() == 0 ? "" : " \\fI" + roff(o->get_type_name()) + "\\fR";
    std::string text = o->get_description();
    if (!o->get_default_str().empty()) text += " (default: " + o->get_default_str() + ")";
    if (o->get_group() == "Renamed") text = "renamed: " + o->get_description();
    out += fmt::format(".TP\n\\fB{}\\fR{}\n{}\n", roff(option_names(*o)), type, roff(text));
  }
  return out;
}

}  // namespace

std::string man_page(const CLI::App& app, std::string_view version) {
  std::string out = fmt::format(".TH CCAL 1 \"\" \"ccal {}\" \"User Commands\"\n", roff(version));
  out += ".SH NAME\nccal \\- " + roff(app.get_description()) + "\n";
  out += ".SH SYNOPSIS\n\\fBccal\\fR [\\fB\\-\\-help\\fR] [\\fB\\-\\-version\\fR] \\fIcommand\\fR [\\fIoptions\\fR]\n";
  out += ".br\n\\fBccal \\-\\-man\\-page\\fR | \\fBccal \\-\\-completion bash\\fR\n";
  out += ".SH DESCRIPTION\nEvery command has \\fB\\-\\-help\\fR, which ends with examples. Configuration files, "
         "the model and the Python module are described in the documentation (docs/cli.md, docs/config.md, "
         "docs/model.md).\n";
  out += ".SH COMMANDS\n";
  for (const CLI::App* c : commands_of(app)) {
    out += fmt::format(".SS \"ccal {}\"\n{}\n", roff(c->get_name()), roff(c->get_description()));
    out += man_options(*c);
    for (const CLI::App* sub : commands_of(*c)) {  // a command of commands (ccal history add, show)
      out += fmt::format(".SS \"ccal {} {}\"\n{}\n", roff(c->get_name()), roff(sub->get_name()),
                         roff(sub->get_description()));
      out += man_options(*sub);
    }
  }
  out += ".SH EXIT STATUS\n.TP\n0\nsuccess\n.TP\n2\nbad input (configuration, data files, options): one line "
         "on standard error naming the place and what would be accepted; no output file is written or changed\n"
         ".TP\n1\ninternal error\n";
  return out;
}

std::string bash_completion(const CLI::App& app) {
  std::string commands, cases;
  for (const CLI::App* c : commands_of(app)) {
    commands += fmt::format("{}{}", commands.empty() ? "" : " ", c->get_name());
    std::string flags, valued;
    std::vector<const CLI::Option*> options = flags_of(*c);
    for (const CLI::App* sub : commands_of(*c)) {  // a command of commands: its commands' names and flags
      flags += " " + sub->get_name();
      for (const CLI::Option* o : flags_of(*sub)) options.push_back(o);
    }
    for (const CLI::Option* o : options) {
      std::vector<std::string> names;
      for (const auto& l : o->get_lnames()) names.push_back(fmt::format("--{}", l));
      for (const auto& s : o->get_snames()) names.push_back(fmt::format("-{}", s));
      for (const std::string& name : names) {
        flags += fmt::format(" {}", name);
        if (o->get_expected_max() != 0) valued += fmt::format("{}{}", valued.empty() ? "" : "|", name);
      }
    }
    // After a flag that takes a value: file names (most values are files or free text); else the flags.
    cases += fmt::format("    {})\n      case \"$prev\" in\n        {}) COMPREPLY=($(compgen -f -- \"$cur\")) ;;\n"
                         "        *) COMPREPLY=($(compgen -W \"{}\" -- \"$cur\")) ;;\n      esac\n"
                         "      [[ $cur != -* && ${{#COMPREPLY[@]}} -eq 0 ]] && COMPREPLY=($(compgen -f -- \"$cur\"))\n"
                         "      ;;\n",
                         c->get_name(), valued.empty() ? "--no-value" : valued, flags.substr(1));
  }
  return fmt::format(
      "# bash completion for ccal (made by `ccal --completion bash`, from the program's own options)\n"
      "_ccal() {{\n"
      "  local cur=${{COMP_WORDS[COMP_CWORD]}} prev=${{COMP_WORDS[COMP_CWORD-1]}}\n"
      "  if [[ $COMP_CWORD -eq 1 ]]; then\n"
      "    COMPREPLY=($(compgen -W \"{} --help --version --man-page --completion\" -- \"$cur\"))\n"
      "    return\n"
      "  fi\n"
      "  case ${{COMP_WORDS[1]}} in\n{}  esac\n"
      "}}\n"
      "complete -F _ccal ccal\n",
      commands, cases);
}

}  // namespace ccal::cli
