#pragma once
// The program's manual page and shell completion, made from the same declarations as its --help (the
// subcommands and their flags, which come from the verbs' options tables), so they cannot drift from it.
//   ccal --man-page              roff for man(1): `ccal --man-page > ccal.1; man -l ccal.1`
//   ccal --completion bash       a bash completion script: `source <(ccal --completion bash)`
// The build writes both into the build folder and `cmake --install` installs them (share/man/man1/ccal.1,
// share/bash-completion/completions/ccal).

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>

namespace ccal::cli {

std::string man_page(const CLI::App& app, std::string_view version);
std::string bash_completion(const CLI::App& app);

}  // namespace ccal::cli
