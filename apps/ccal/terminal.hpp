#pragma once
// The terminal a command writes to, for layouts that fit it, and the options that set a text's width.
#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>

#include "output.hpp"

namespace ccal::cli {

struct TerminalSize {
  std::size_t columns = 0, rows = 0;  // 0: not a terminal (or its size is unknown)
};

// The size of standard output's terminal when the text goes there (no -o file), else zeros.
TerminalSize output_terminal(const OutputOptions& output);

// --width N and --wide of a text report.
struct WidthOptions {
  std::size_t width = 0;  // 0: the terminal's width, or 100 off a terminal
  bool wide = false;
};
void add_width_options(CLI::App& command, WidthOptions& options, const std::string& wide_help);
// The width a text gets: --width, else the terminal's, else 100.
std::size_t text_width(const WidthOptions& options, const TerminalSize& terminal);

// A whole count written as a decimal number ("1e3", "100.0") rewritten in digits ("1000"), as the library's own
// counts (--trials 1e4) take it; anything else is left for the option's own check.
CLI::Validator whole_number_in_digits();

// An option that was renamed: giving it fails with a message naming its successor (exit code 2).
void add_renamed_option(CLI::App& command, const std::string& old_name, const std::string& message);

}  // namespace ccal::cli
