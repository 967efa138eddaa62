#include "shell_docs.hpp"

#include <fmt/format.h>

#include <vector>

#include "completion.hpp"
#include "help_format.hpp"

namespace ccal::cli {

namespace {

// roff text: a backslash doubled, a leading dot or quote escaped, so that no line of help is a request.
std::string roff(std::string_view text) {
  std::string out;
  for (char c : text) out += c == '\\' ? std::string("\\e") : c == '-' ? std::string("\\-") : std::string(1, c);
  if (!out.empty() && (out.front() == '.' || out.front() == '\'')) out = "\\&" + out;
  return out;
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
    out += fmt::format(".TP\n\\fI{}\\fR\n{}\n", roff(positional_name(*o)), roff(o->get_description()));
  for (const CLI::Option* o : flags_of(command)) {
    const std::string type = o->get_expected_max() == 0 ? "" : " \\fI" + roff(value_name(*o)) + "\\fR";
    std::string text = o->get_description();
    if (!o->get_default_str().empty()) text += " (default: " + o->get_default_str() + ")";
    if (o->get_group() == "Renamed") text = "renamed: " + o->get_description();
    out += fmt::format(".TP\n\\fB{}\\fR{}\n{}\n", roff(option_names(*o)), type, roff(text));
  }
  return out;
}

}  // namespace

std::string man_page(const CLI::App& app, std::string_view summary, std::string_view version) {
  std::string out = fmt::format(".TH CCAL 1 \"\" \"ccal {}\" \"User Commands\"\n", roff(version));
  out += ".SH NAME\nccal \\- " + roff(summary) + "\n";
  out += ".SH SYNOPSIS\n\\fBccal\\fR [\\fB\\-\\-help\\fR] [\\fB\\-V\\fR|\\fB\\-\\-version\\fR] \\fIcommand\\fR "
         "[\\fIoptions\\fR]\n";
  out += ".br\n\\fBccal \\-\\-man\\-page\\fR | \\fBccal \\-\\-completion\\fR "
         "\\fBbash\\fR|\\fBzsh\\fR|\\fBfish\\fR\n";
  out += ".SH DESCRIPTION\n" + roff(app.get_description()) +
         "\n.PP\nEvery command has \\fB\\-\\-help\\fR, which ends with its examples. Configuration files, "
         "the commands' outputs, the model and the Python module are described in the documentation installed "
         "with ccal, in \\fIshare/doc/ccal/docs\\fR under its prefix (e.g. /usr/local/share/doc/ccal/docs): "
         "cli.md (the commands, their options and outputs), config.md, model.md, python.md, tutorial.md (docs/ "
         "in the sources).\n";
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

}  // namespace ccal::cli
