#include "output.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "atomic_file.hpp"
#include "option_flags.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/render/statement.hpp"
#include "ccal/setup/config.hpp"

namespace ccal::cli {

void add_output_options(CLI::App& command, OutputOptions& options, const std::vector<std::string>& formats,
                        bool long_output) {
  options.format = formats.front();
  options.formats = formats;
  CLI::Option* format = command.add_option("--format", options.format, "Output format")
                            ->check(CLI::IsMember(formats))
                            ->capture_default_str()
                            ->type_name("FORMAT");
  remember_choices(format, formats);
  refuse_empty_output(
      *command
           .add_option(long_output ? "-o,--output" : "-o", options.path,
                       "Write the output to FILE instead of standard output ('-': standard output)")
           ->type_name("FILE"));
}

void refuse_empty_output(CLI::Option& option) {
  // A parse error of its own rather than the validator's message: CLI11 would name the option by its long
  // name, while every message of the output files names it -o.
  option.each([](const std::string& path) {
    if (path.empty())
      throw CLI::ParseError("-o: the path is empty; accepted: a file path or '-' for standard output",
                            CLI::ExitCodes::ValidationError);
  });
}

CLI::Option* refuse_empty_path(CLI::Option* option, const std::string& name, const std::string& accepted) {
  option->each([name, accepted](const std::string& path) {
    if (path.empty())
      throw CLI::ParseError(fmt::format("{}: the path is empty; accepted: {}", name, accepted),
                            CLI::ExitCodes::ValidationError);
  });
  return option;
}

void refuse_empty_input_paths(CLI::App& app) {
  // Each input path option by the name the parser gives it, and what it accepts.
  static const std::pair<std::string_view, std::string_view> kInputs[] = {
      {"config", "a configuration file (TOML), or no CONFIG at all for the bundled example"},
      {"--config", "a configuration file (TOML)"},
      {"file", "a CSV file"},
      {"--truth", "a truth file (TOML with an [errors] table), or no --truth"},
      {"--log-layout", "a layout file (TOML), or no --log-layout"},
      {"--logs", "a folder of logs with its manifest.toml"},
      {"--observations", "an observations file (CSV), or no --observations"},
      {"--history-db", "a history store's path, or no --history-db"},
      {"--db", "a history store's path, or no --db for the default store"},
      {"STATEMENT", "a calibration statement's JSON file"},
      {"FILE", "a file of `ccal history export`"}};
  for (CLI::Option* option : app.get_options()) {
    for (const auto& [name, accepted] : kInputs) {
      if (option->get_name() != name) continue;
      // Positional arguments by their type name (CONFIG, FILE.csv), options by their flag.
      const std::string shown = option->nonpositional() ? std::string(name) : option->get_type_name();
      option->each([shown, accepted = std::string(accepted)](const std::string& path) {
        if (path.empty())
          throw CLI::ParseError(
              fmt::format("{}: the path is empty (an unset shell variable?); accepted: {}", shown, accepted),
              CLI::ExitCodes::ValidationError);
      });
    }
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) refuse_empty_input_paths(*sub);
}

void write_output(const OutputOptions& options, std::string_view text) { write_outputs(options, text, {}); }

void add_observations_out_option(CLI::App& command, std::string& path) {
  refuse_empty_path(command.add_option("--observations-out", path,
                                       "Also write the observations CSV (the input of 'ccal identify') to FILE"),
                    "--observations-out", "a file path, e.g. obs.csv")
      ->type_name("FILE.csv");
}

void check_observations_out(const std::string& path, const OutputOptions& output) {
  if (!path.empty() && same_file(path, output.path.empty() ? "-" : output.path))
    throw InputError(
        fmt::format("--observations-out: '{}' is also the -o file; accepted: two different files", path));
}

void add_statement_out_option(CLI::App& command, std::string& path) {
  refuse_empty_path(
      command.add_option(
          "--statement-out", path,
          "With --statement, also write the calibration statement alone to FILE: JSON for FILE.json, CSV "
          "(one row per coefficient with its covariance row) for FILE.csv"),
      "--statement-out", "a file path, FILE.json or FILE.csv")
      ->type_name("FILE.json|FILE.csv");
}

namespace {

// The format a file's name says by its extension (in any case), among those ccal reads or writes; "" for none.
std::string_view format_named(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  static constexpr std::pair<std::string_view, std::string_view> kNamed[] = {
      {".json", "JSON"}, {".csv", "CSV"}, {".html", "HTML"}, {".htm", "HTML"},
      {".pdf", "PDF"},   {".toml", "TOML"}, {".npy", "NumPy"}};
  for (const auto& [ext, format] : kNamed)
    if (extension == ext) return format;
  return {};
}

}  // namespace

void check_statement_out(const std::string& path, bool statement, const OutputOptions& output) {
  if (path.empty()) return;
  if (!statement)
    throw InputError(
        fmt::format("--statement-out: '{}' asks for the statement's file without --statement; "
                    "accepted: --statement --statement-out FILE",
                    path));
  const std::string_view named = format_named(path);  // the extension in any case, as every output's name
  if (named != "JSON" && named != "CSV")
    throw InputError(
        fmt::format("--statement-out: '{}' has no .json or .csv extension, which sets the format; "
                    "accepted: FILE.json or FILE.csv",
                    path));
  if (same_file(path, output.path.empty() ? "-" : output.path))
    throw InputError(
        fmt::format("--statement-out: '{}' is also the -o file; accepted: two different files", path));
}

void add_statement_out_file(std::vector<ExtraFile>& extra, const std::string& path,
                            const std::optional<verbs::CalibrationStatement>& statement) {
  if (path.empty() || !statement) return;
  const bool json = format_named(path) == "JSON";
  extra.push_back({"--statement-out", path, json ? render::json(*statement) : render::csv(*statement)});
}

void note_input(const std::string& path) { note_input_file(path); }

void print_warnings(const std::vector<std::string>& warnings) {
  for (const auto& w : warnings) std::cerr << "ccal: warning: " << w << '\n';
}

namespace {

// What a file holds, as format_named says it: -o by --format (the report's page is HTML), the others by their
// option; "" where the name sets the format itself (--statement-out) or is made by the command (--logs-out).
std::string_view format_written(const std::string& option, const OutputOptions& options, const std::string& path) {
  if (option == "-o") {
    static constexpr std::pair<std::string_view, std::string_view> kFormats[] = {
        {"text", "text"}, {"json", "JSON"}, {"csv", "CSV"}, {"html", "HTML"}};
    for (const auto& [name, format] : kFormats)
      if (options.format == name) return format;
    return {};
  }
  if (option == "--observations-out") return "CSV";
  if (option == "--plan-out") return "TOML";
  if (option == "--pdf") return "PDF";
  if (option == "--samples-out") return format_named(path) == "NumPy" ? "NumPy" : "CSV";
  return {};
}

// A file whose name says another format than it would hold (budget -o b.json of text, --observations-out o.json
// of CSV, report -o r.pdf of the HTML page): refused, naming the option and what would be accepted. Standard
// output, a device or a FIFO has no format to say.
void check_named_formats(const OutputOptions& options, const std::vector<FileToWrite>& files) {
  for (const FileToWrite& f : files) {
    std::error_code ec;
    const auto status = std::filesystem::status(f.path, ec);
    if (f.path == "-" || (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)))
      continue;
    const std::string_view named = format_named(f.path), written = format_written(f.option, options, f.path);
    if (named.empty() || written.empty() || named == written) continue;
    static constexpr std::pair<std::string_view, std::string_view> kNames[] = {
        {"text", "a name that says no other format, e.g. FILE.txt"}, {"JSON", "FILE.json"}, {"CSV", "FILE.csv"},
        {"HTML", "FILE.html"}, {"PDF", "FILE.pdf"}, {"TOML", "FILE.toml"}, {"NumPy", "FILE.npy"}};
    std::string accepted;
    for (const auto& [format, name] : kNames)
      if (format == written) accepted = name;
    if (f.option == "--samples-out") accepted = "FILE.csv or FILE.npy";
    const std::string flag_value = named == "JSON" ? "json" : named == "CSV" ? "csv" : "";
    if (f.option == "-o" && std::find(options.formats.begin(), options.formats.end(), flag_value) !=
                                options.formats.end())
      accepted += fmt::format(", or --format {} for {}", flag_value, named);
    if (f.option == "-o" && named == "PDF" && written == "HTML")
      accepted += ", or --pdf FILE.pdf for the page printed as PDF";
    throw InputError(fmt::format("{}: '{}' names {} {} file, and {} writes {}; accepted: {}", f.option, f.path,
                                 named == "HTML" ? "an" : "a", named, f.option, written, accepted));
  }
}

std::vector<FileToWrite> files_of(const OutputOptions& options, std::string_view text,
                                  const std::vector<ExtraFile>& extra) {
  std::vector<FileToWrite> files;
  files.push_back({"-o", options.path.empty() ? "-" : options.path, std::string(text), {}});
  for (const auto& f : extra) files.push_back({f.option, f.path, f.text, f.produce});
  return files;
}

}  // namespace

void write_outputs(const OutputOptions& options, std::string_view text, const std::vector<ExtraFile>& extra) {
  const std::vector<FileToWrite> files = files_of(options, text, extra);
  check_files(files);  // first what each file is (an input, a folder), then what its name says
  check_named_formats(options, files);
  write_files(files);
}

void check_outputs(const OutputOptions& options, const std::vector<ExtraFile>& extra) {
  const std::vector<FileToWrite> files = files_of(options, {}, extra);
  check_files(files);
  check_named_formats(options, files);
}

Config load_config_or_example(const ConfigChoice& config) {
  if (config.path.empty()) return select_instrument(bundled_example(), config.instrument);
  note_input(config.path);
  return select_instrument(load_config(config.path), config.instrument);
}

void add_instrument_option(CLI::App& command, ConfigChoice& config) {
  command
      .add_option("--instrument", config.instrument,
                  "ID: in a test of several instruments ([[instruments]]), the one to answer for (its id); "
                  "default: every instrument, where the command handles several")
      ->type_name("ID")
      ->each([](const std::string& id) {
        if (id.empty())  // an unset shell variable would otherwise mean every instrument silently
          throw CLI::ParseError("--instrument: " + std::string(kEmptyInstrumentId), CLI::ExitCodes::ValidationError);
      });
}

void add_config_argument(CLI::App& command, ConfigChoice& config) {
  command
      .add_option("config", config.path,
                  "Configuration file (TOML, docs/config.md); default: the bundled paper example")
      ->type_name("CONFIG");
  add_instrument_option(command, config);
}

std::string config_file_text(const std::string& path) {
  if (path.empty()) return std::string(bundled_example_text());
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError(fmt::format("{}: cannot read the file again", path));
  return text.str();
}

}  // namespace ccal::cli
