#pragma once
// The program's manual page, made from the same declarations as its --help (the subcommands and their flags,
// which come from the verbs' options tables), so it cannot drift from it (the shell completions: completion.hpp).
//   ccal --man-page              roff for man(1): `ccal --man-page > ccal.1; man -l ccal.1`
// The build writes it into the build folder and `cmake --install` installs it (share/man/man1/ccal.1), with the
// documentation it names (share/doc/ccal).

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>

namespace ccal::cli {

// summary: the NAME line's text after "ccal - ".
std::string man_page(const CLI::App& app, std::string_view summary, std::string_view version);

}  // namespace ccal::cli
