#pragma once
// The program's shell completions for bash, zsh and fish, made from the same declarations as its --help (the
// commands, their flags from the verbs' options tables, the values of every choice option), so that none of
// them can drift from the program:
//   ccal --completion bash|zsh|fish
// After a choice option (--format, --mode, …) each completes its values, after a file's option file names,
// after any other value nothing; elsewhere the command's flags, and file names for a configuration or data
// file. The build writes all three into the build folder and `cmake --install` installs them
// (share/bash-completion/completions/ccal, share/zsh/vendor-completions/_ccal,
// share/fish/vendor_completions.d/ccal.fish).

#include <CLI/CLI.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace ccal::cli {

// The shells a completion is made for.
inline const std::vector<std::string> kCompletionShells = {"bash", "zsh", "fish"};

// The completion script for `shell` (one of kCompletionShells).
std::string completion_script(const CLI::App& app, std::string_view shell);

// The named commands of a command (ccal's, or history's), in the order declared.
std::vector<const CLI::App*> commands_of(const CLI::App& app);
// The options a user can give a command (not the hidden ones, nor --help, nor positionals), in the order
// declared.
std::vector<const CLI::Option*> flags_of(const CLI::App& command);

}  // namespace ccal::cli
