#include "terminal.hpp"

#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <string_view>

namespace ccal::cli {

TerminalSize output_terminal(const OutputOptions& output) {
  if (!output.path.empty() && output.path != "-") return {};
  if (isatty(STDOUT_FILENO) == 0) return {};
  winsize size{};
  if (ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) != 0) return {};
  return {size.ws_col, size.ws_row};
}

void add_width_options(CLI::App& command, WidthOptions& options, const std::string& wide_help) {
  command
      .add_option("--width", options.width,
                  "Columns of the text (default: the terminal's width, or 100 when not a terminal)")
      ->transform(whole_number_in_digits())
      ->check(CLI::Range(40, 10000))
      ->type_name("N");
  command.add_flag("--wide", options.wide, wide_help);
}

std::size_t text_width(const WidthOptions& options, const TerminalSize& terminal) {
  if (options.width > 0) return options.width;
  return terminal.columns >= 40 ? terminal.columns : 100;
}

CLI::Validator whole_number_in_digits() {
  return CLI::Validator(
      [](std::string& text) {
        double value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        // 2^53: the largest range in which every whole double is written exactly.
        if (error == std::errc() && end == text.data() + text.size() && std::isfinite(value) && value >= 0 &&
            value <= 9007199254740992.0 && std::floor(value) == value)
          text = std::to_string(static_cast<long long>(value));
        // The parser would read 0x10 as hexadecimal, 0b11 as binary: a count is written in decimal.
        if (text.size() > 2 && text[0] == '0' && std::string_view("xXbBoO").find(text[1]) != std::string_view::npos)
          return fmt::format("'{}' is not a decimal number; accepted: a whole number in decimal digits", text);
        return std::string();
      },
      "");
}

void add_renamed_option(CLI::App& command, const std::string& old_name, const std::string& message) {
  // Listed in --help under "Renamed" (a hidden option would have no name in the error message).
  command.add_option(old_name, message)
      ->group("Renamed")
      ->type_name("")
      ->check(CLI::Validator([message](std::string&) { return message; }, ""));
}

}  // namespace ccal::cli
