#pragma once
// Shared pieces of the ccal commands: the --format / -o options, writing the result atomically, aligned text
// tables and number formatting. Every command builds its whole output in memory first and writes it once at
// the end, so a failing command writes nothing.

#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/io/config_file.hpp"
#include "ccal/render/table.hpp"
#include "ccal/verbs/statement.hpp"

namespace ccal::cli {

// --format and -o of a command.
struct OutputOptions {
  std::string format = "text";
  std::string path;                  // empty: standard output
  std::vector<std::string> formats;  // what --format takes (add_output_options); empty: no --format
};

// Adds --format (one of `formats`, the first is the default) and -o/--output to a command (-o alone when
// long_output is false, for a command whose --output means something else). An empty -o value is refused
// (refuse_empty_output).
void add_output_options(CLI::App& command, OutputOptions& options, const std::vector<std::string>& formats,
                        bool long_output = true);

// Refuses an explicitly given empty path for an output option (-o ""), which would otherwise mean standard
// output silently: a parse error "-o: the path is empty; accepted: a file path or '-' for standard output".
void refuse_empty_output(CLI::Option& option);
// The same for a further output option (--pdf, --statement-out, --plan-out, --samples-out, --logs-out,
// --observations-out), named in the message; it has no standard output: "accepted: a file path".
CLI::Option* refuse_empty_path(CLI::Option* option, const std::string& name, const std::string& accepted);
// The same for every input path of the commands below `app` (CONFIG, --config, --truth, --logs, --db, …),
// which an empty value would otherwise turn into the default (the bundled example, the default history store)
// or into "none": "--db: the path is empty (an unset shell variable?); accepted: …".
void refuse_empty_input_paths(CLI::App& app);

// Writes text to standard output (also for the path "-"), or to options.path. A regular file (or a new one)
// is replaced atomically: the text goes to a temporary created exclusively (O_EXCL | O_NOFOLLOW, random
// name) in the target's folder with the target's permissions, then renamed over it; a symbolic link is
// followed and the file it names replaced. A device or FIFO is written through, never replaced. A path that
// is one of the command's inputs (note_input) is refused. Throws InputError if the file cannot be written or
// standard output reports a write error.
void write_output(const OutputOptions& options, std::string_view text);

// Records a file the command reads (configuration, CSV, log, the history store, also one it is about to
// make), so that no output replaces it.
void note_input(const std::string& path);

// A further file a command writes besides its output, e.g. --observations-out.
struct ExtraFile {
  std::string option;  // the option that named it, for messages
  std::string path;
  std::string text;
  // When set, the content instead of text, written block by block (a file too large to build in memory):
  // produce(write) calls write(block) for each block and returns false when a write failed.
  std::function<bool(const std::function<bool(std::string_view)>& write)> produce = {};
};

// As write_output, with further files: every file is first written to a temporary file and renamed only when
// all of them were written, so a failure leaves none of them (and no temporary file) behind. SIGINT and
// SIGTERM remove the temporaries before the process ends.
void write_outputs(const OutputOptions& options, std::string_view text, const std::vector<ExtraFile>& extra);

// Checks, writing nothing, that write_outputs(options, …, extra) can write its files as far as can be known
// beforehand (atomic_file.hpp check_files); InputError as write_outputs. For a command that changes something
// besides its outputs (history add), before it does.
void check_outputs(const OutputOptions& options, const std::vector<ExtraFile>& extra = {});

// --observations-out FILE (the observations CSV, the input of `ccal identify`, besides the output), and the
// check that it is not also the -o file (InputError).
void add_observations_out_option(CLI::App& command, std::string& path);
void check_observations_out(const std::string& path, const OutputOptions& output);

// --statement-out FILE of `reduce` and `identify`: the calibration statement alone (render/statement.hpp),
// JSON or CSV by the file's extension.
void add_statement_out_option(CLI::App& command, std::string& path);
// Before the work: refused without --statement, with another extension than .json or .csv, or naming the -o
// file (InputError naming --statement-out).
void check_statement_out(const std::string& path, bool statement, const OutputOptions& output);
// The file for the extra outputs, if --statement-out named one.
void add_statement_out_file(std::vector<ExtraFile>& extra, const std::string& path,
                            const std::optional<verbs::CalibrationStatement>& statement);

// The configuration's bytes exactly as read (the bundled example's text for an empty path), for a report's
// hash or a --plan-out file built from it. InputError if the file cannot be read again.
std::string config_file_text(const std::string& path);

// A configuration as the command line names it: its file ("": the bundled example) and, for a test of several
// instruments, the one chosen (--instrument ID; "": all, or the only one).
struct ConfigChoice {
  std::string path;
  std::string instrument;
};

// The optional CONFIG argument every configuration-driven command takes, and its --instrument option.
void add_config_argument(CLI::App& command, ConfigChoice& config);
// --instrument ID alone (for a command whose configuration is an option, e.g. identify's --config).
void add_instrument_option(CLI::App& command, ConfigChoice& config);

// The configuration named on the command line, or the bundled paper example if none is; the instrument chosen,
// when one is (select_instrument).
Config load_config_or_example(const ConfigChoice& config);

// Prints each warning of a result to standard error as "ccal: warning: <text>".
void print_warnings(const std::vector<std::string>& warnings);

using render::number;
using render::Table;

}  // namespace ccal::cli
