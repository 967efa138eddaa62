#include "output.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "ccal/errors.hpp"

namespace ccal::cli {

void add_output_options(CLI::App& command, OutputOptions& options, const std::vector<std::string>& formats) {
  options.format = formats.front();
  command.add_option("--format", options.format, "Output format")
      ->check(CLI::IsMember(formats))
      ->capture_default_str();
  command.add_option("-o,--output", options.path, "Write the output to FILE instead of standard output")
      ->type_name("FILE");
}

void write_output(const OutputOptions& options, std::string_view text) {
  if (options.path.empty()) {
    std::cout << text << std::flush;
    return;
  }
  namespace fs = std::filesystem;
  const fs::path target(options.path);
  fs::path temporary = target;
  temporary += fmt::format(".tmp{}", static_cast<long>(::getpid()));
  auto fail = [&](std::string_view why) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw InputError(fmt::format("-o: cannot write '{}': {}; give a writable file path", options.path, why));
  };
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) fail("cannot create a file there");
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) fail("write failed");
  }
  std::error_code ec;
  fs::rename(temporary, target, ec);
  if (ec) fail(ec.message());
}

Config load_config_or_example(const std::string& path) {
  return path.empty() ? bundled_example() : load_config(path);
}

std::string number(double v, int digits) {
  if (v == 0.0) return "0";
  return fmt::format("{:.{}g}", v, digits);
}

std::string Table::render(std::string_view indent) const {
  std::vector<std::size_t> width(header_.size(), 0);
  auto measure = [&](const std::vector<std::string>& row) {
    for (std::size_t c = 0; c < row.size() && c < width.size(); ++c)
      width[c] = std::max(width[c], row[c].size());
  };
  measure(header_);
  for (const auto& row : rows_) measure(row);
  std::size_t total = 0;
  for (std::size_t w : width) total += w;
  total += 3 * (width.size() - 1);

  std::string out;
  auto line = [&](const std::vector<std::string>& row) {
    std::string text(indent);
    for (std::size_t c = 0; c < width.size(); ++c) {
      const std::string cell = c < row.size() ? row[c] : "";
      if (c > 0) text += "   ";
      text += c == 0 ? fmt::format("{:<{}}", cell, width[c]) : fmt::format("{:>{}}", cell, width[c]);
    }
    while (!text.empty() && text.back() == ' ') text.pop_back();
    out += text + '\n';
  };
  line(header_);
  out += std::string(indent) + std::string(total, '-') + '\n';
  for (const auto& row : rows_) {
    if (row.empty())
      out += std::string(indent) + std::string(total, '-') + '\n';
    else
      line(row);
  }
  return out;
}

}  // namespace ccal::cli
