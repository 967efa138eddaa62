#pragma once
// A folder of run logs and its manifest (docs/cli.md, "A folder of logs"): `manifest.toml` in the folder says
// which file holds which run of the plan and how the files' columns read, so that `ccal reduce CONFIG --logs DIR`
// takes the folder as a data-acquisition system wrote it, and `ccal simulate --logs-out DIR` writes one.
//
//     # manifest.toml
//     [format]                        # all optional: how the DAQ writes its files (default: ccal's CSV)
//     delimiter = "semicolon"         # comma, semicolon, tab or whitespace
//     decimal = "comma"               # point or comma (comma with another delimiter than comma)
//     comment = "//"                  # lines beginning with it are skipped (default "#"; "" none)
//     skip_lines = 3                  # lines at the top skipped whatever they hold (a preamble), or
//     header_line = 4                 #   the header's line (the lines before it skipped)
//     units_row = true                # a line of the columns' units under the header
//     max_gap = "10 s"                # the longest gap between samples the lab accepts (default: none)
//     [columns]                       # all optional: ccal's own layout by default
//     time = "t_ms"                   # the time column (default "time")
//     time_unit = "ms"                # its unit (default "s"), or "iso8601" for timestamps
//     pulses = "piga_count"           # the cumulative pulse count (default "pulses"), or
//     output = "rate"                 #   the instrument's output, in its output unit (default "output")
//     theta1 = "enc_main"             # the main-axis encoder (default "theta1")
//     gamma = "enc_platform"          # the platform encoder (default "gamma")
//     angle_unit = "counts"           # the encoders' unit: an angle unit (rad, deg, …) or counts
//     counts_per_revolution = 16777216  # with counts: the encoders' counts per revolution (2^24 here)
//     count_rounding = "floor"        # with counts: count c is the angle in [c, c+1) counts (floor) or
//                                     #   c counts to the nearest (nearest, the default)
//     [instruments]                   # a test of several instruments: each id's output column, instead of
//     A = { pulses = "count_a" }      #   [columns] pulses or output (the configuration's [[instruments]])
//     B = { output = "rate_b" }
//     [runs]                          # run (its name or 1-based index) = file, relative to the folder
//     5g = "run_05g.csv"
//     10g = "run_10g.csv"
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/io/csv_stream.hpp"
#include "ccal/intake/run_log.hpp"

namespace ccal {

inline constexpr std::string_view kLogManifestName = "manifest.toml";

// How an encoder in counts latches its count c: floor, the angle lies in [c, c+1) counts and is read as
// (c + 1/2)·2π/cpr; nearest, c is the angle to the nearest count and is read as c·2π/cpr.
enum class CountRounding { nearest, floor };
inline constexpr std::string_view kCountRoundingNames[] = {"nearest", "floor"};  // in the enumeration's order

// How a folder's logs read: the file's format, the columns, and the units when the manifest states them.
struct LogLayout {
  CsvFormat format;
  LogColumns columns;
  // [instruments] of a test of several instruments (a configuration's [[instruments]]): each instrument's
  // output column, a cumulative pulse count or its output, in the manifest's order. Empty: one instrument, whose
  // column is [columns] pulses or output.
  struct InstrumentColumn {
    std::string id;      // the instrument's id in the configuration
    std::string column;  // its column's name
    bool pulses = true;  // a cumulative count (pulses), or the output itself (output)
    int line = 0;        // where the manifest names it
  };
  std::vector<InstrumentColumn> instruments;
  std::string angle_unit;        // as written ("rad", "deg", "counts"); empty: not stated
  double angle_scale = 1;        // rad per unit of the encoder columns (2π/counts for counts)
  long long counts_per_revolution = 0;  // with angle_unit = "counts"
  CountRounding count_rounding = CountRounding::nearest;  // with counts
  std::string time_unit;         // as written ("ms", "iso8601"); empty: not stated (seconds, or the units row's)
  double max_gap = 0;            // the longest gap between samples accepted [s]; 0: not stated
  std::string max_gap_text;      // as written
};

struct LogManifest {
  std::string source;  // the manifest's path, as in messages
  LogLayout layout;
  struct Entry {
    std::string run;                // as written: a run's name or its 1-based index
    std::filesystem::path file;     // the folder joined with the file as written
    int line = 0, column = 0;       // where the manifest names it (its key), for messages about the log
  };
  std::vector<Entry> runs;  // in the manifest's order
};

// Reads DIR/manifest.toml. Throws ConfigError, located (file, line, key), for a folder without one, a TOML error,
// an unknown table or key, a column name that is empty or used twice, a time unit that is no time, an angle
// unit that is no angle (or counts without counts_per_revolution, or that number or count_rounding without
// counts), an unknown delimiter, decimal separator or count rounding, a decimal comma with the comma as
// delimiter, a comment prefix with blanks, a negative or fractional skip_lines or header_line (or a header_line
// within the skipped lines), a units_row that is no boolean, a max_gap that is no positive time, an empty
// [runs] or a file that is not a relative path inside the folder.
LogManifest read_log_manifest(const std::filesystem::path& folder);
LogManifest parse_log_manifest(std::string_view text, std::string_view source_name,
                               const std::filesystem::path& folder);

// A layout alone (`ccal simulate --log-layout FILE`, `ccal reduce --log RUN=FILE --log-layout FILE`): a file with
// the [format] and [columns] tables of a manifest and nothing else (the runs are the plan's, or the --log
// options'). ConfigError as above.
LogLayout read_log_layout(const std::filesystem::path& file);
// What a layout file is, for messages.
inline constexpr std::string_view kLogLayoutAccepted =
    "a layout file in TOML: a manifest's [format] and [columns] tables, and its [instruments] for a test of several "
    "instruments (docs/cli.md, \"A folder of logs\")";
LogLayout parse_log_layout(std::string_view text, std::string_view source_name);

// The manifest's text for logs of this layout, one [runs] line per (run, file name).
std::string log_manifest_text(const LogLayout& layout, const std::vector<std::pair<std::string, std::string>>& runs);

}  // namespace ccal
