// The manifest's [format] table and the new [columns] keys (intake/log_manifest.hpp): the file as a data acquisition
// system writes it (delimiter, decimal separator, comment prefix, preamble, header line, units row, the longest
// gap accepted; timestamps and the encoders' count rounding) read as written, written back by
// log_manifest_text to the same layout, and every bad value refused at its file, line and key with what is
// accepted.
#include <gtest/gtest.h>

#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/intake/log_manifest.hpp"

namespace ccal {
namespace {

const std::string kRuns = "[runs]\n1 = \"a.csv\"\n";

std::string refusal(const std::string& text) {
  try {
    parse_log_manifest(text + kRuns, "logs/manifest.toml", "logs");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(LogManifestFormat, TheFileIsDescribedAsTheDaqWroteIt) {
  const LogManifest m = parse_log_manifest(R"([format]
delimiter = "semicolon"
decimal = "comma"
comment = "//"
skip_lines = 2
header_line = 4
units_row = true
max_gap = "10 s"
[columns]
time_unit = "iso8601"
angle_unit = "counts"
counts_per_revolution = 4096
count_rounding = "floor"
)" + kRuns,
                                           "m", ".");
  const CsvFormat& f = m.layout.format;
  EXPECT_EQ(f.delimiter, ';');
  EXPECT_EQ(f.decimal, ',');
  EXPECT_EQ(f.comment, "//");
  EXPECT_EQ(f.skip_lines, 2);
  EXPECT_EQ(f.header_line, 4);
  EXPECT_TRUE(f.units_row);
  EXPECT_EQ(m.layout.max_gap, 10.0);
  EXPECT_TRUE(m.layout.columns.iso_time);
  EXPECT_EQ(m.layout.count_rounding, CountRounding::floor);
  // The other delimiters by name; the defaults when [format] is left out.
  EXPECT_EQ(parse_log_layout("[format]\ndelimiter = \"tab\"\n", "l").format.delimiter, '\t');
  EXPECT_EQ(parse_log_layout("[format]\ndelimiter = \"whitespace\"\n", "l").format.delimiter, ' ');
  const LogLayout plain = parse_log_layout("[columns]\ntime_unit = \"us\"\n", "l");
  EXPECT_TRUE(plain.format.is_default());
  EXPECT_EQ(plain.max_gap, 0.0);
  EXPECT_EQ(plain.count_rounding, CountRounding::nearest);
  EXPECT_DOUBLE_EQ(plain.columns.time_scale, 1e-6);
  EXPECT_DOUBLE_EQ(parse_log_layout("[columns]\ntime_unit = \"µs\"\n", "l").columns.time_scale, 1e-6);
  // Written back (ccal simulate --logs-out) and read again: the same layout.
  const LogLayout back = parse_log_manifest(log_manifest_text(m.layout, {{"1", "a.csv"}}), "again", ".").layout;
  EXPECT_EQ(back.format.delimiter, ';');
  EXPECT_EQ(back.format.decimal, ',');
  EXPECT_EQ(back.format.comment, "//");
  EXPECT_EQ(back.format.skip_lines, 2);
  EXPECT_EQ(back.format.header_line, 4);
  EXPECT_TRUE(back.format.units_row);
  EXPECT_EQ(back.max_gap, 10.0);
  EXPECT_TRUE(back.columns.iso_time);
  EXPECT_EQ(back.count_rounding, CountRounding::floor);
  // A layout file (--log-layout) takes [format] and [columns], not [runs].
  EXPECT_THROW(parse_log_layout("[format]\ndelimiter = \"tab\"\n" + kRuns, "l"), ConfigError);
}

TEST(LogManifestFormat, EveryBadValueIsRefusedWhereItIsWritten) {
  EXPECT_EQ(refusal("[format]\ndelimiter = \";\"\n"),
            "logs/manifest.toml:2:13: format.delimiter: unknown value ';'; accepted: comma, semicolon, tab, "
            "whitespace");
  EXPECT_EQ(refusal("[format]\ndecimal = \"dot\"\n"),
            "logs/manifest.toml:2:11: format.decimal: unknown value 'dot'; accepted: point, comma");
  EXPECT_EQ(refusal("[format]\ndecimal = \"comma\"\n"),
            "logs/manifest.toml:2:11: format.decimal: a decimal comma cannot be told from the comma between cells; "
            "accepted: decimal = \"comma\" with delimiter = \"semicolon\", \"tab\" or \"whitespace\"");
  EXPECT_EQ(refusal("[format]\ncomment = \"# \"\n"),
            "logs/manifest.toml:2:11: format.comment: '# ' holds a blank; accepted: the prefix of a comment line "
            "without blanks (e.g. \"#\", \"//\", \"%\"), or \"\" for none");
  EXPECT_EQ(refusal("[format]\ncomment = 1\n"),
            "logs/manifest.toml:2:11: format.comment: expected a string, got an integer");
  EXPECT_EQ(refusal("[format]\nskip_lines = -1\n"),
            "logs/manifest.toml:2:14: format.skip_lines: -1 is not a line count; accepted: a whole number from 0 "
            "to 1000000");
  EXPECT_EQ(refusal("[format]\nskip_lines = 2.5\n"),
            "logs/manifest.toml:2:14: format.skip_lines: 2.5 is not a line count; accepted: a whole number from 0 "
            "to 1000000");
  EXPECT_EQ(refusal("[format]\nheader_line = 0\n"),
            "logs/manifest.toml:2:15: format.header_line: 0 is not a line number; accepted: a whole number from 1 "
            "to 1000000");
  EXPECT_EQ(refusal("[format]\nskip_lines = 3\nheader_line = 2\n"),
            "logs/manifest.toml:3:15: format.header_line: line 2 is among the 3 skipped lines; accepted: a "
            "header_line after skip_lines, or one of the two");
  EXPECT_EQ(refusal("[format]\nunits_row = \"yes\"\n"),
            "logs/manifest.toml:2:13: format.units_row: expected true or false, got a string");
  EXPECT_EQ(refusal("[format]\nmax_gap = 10\n"),
            "logs/manifest.toml:2:11: format.max_gap: expected a quantity string such as \"10 s\", got the bare "
            "number 10");
  EXPECT_EQ(refusal("[format]\nmax_gap = \"0 s\"\n"),
            "logs/manifest.toml:2:11: format.max_gap: 0 s is no gap; accepted: a positive time, e.g. \"10 s\"");
  EXPECT_EQ(refusal("[format]\nmax_gap = \"10 m\"\n").rfind("logs/manifest.toml:2:11: format.max_gap: ", 0), 0u)
      << refusal("[format]\nmax_gap = \"10 m\"\n");
  EXPECT_EQ(refusal("[format]\nheader = 2\n"),
            "logs/manifest.toml:2:1: format.header: unknown key; accepted keys: delimiter, decimal, comment, "
            "skip_lines, header_line, units_row, max_gap");
  EXPECT_EQ(refusal("[columns]\ncount_rounding = \"round\"\n"),
            "logs/manifest.toml:2:18: columns.count_rounding: unknown value 'round'; accepted: nearest, floor");
  EXPECT_EQ(refusal("[columns]\ncount_rounding = \"floor\"\n"),
            "logs/manifest.toml:2:18: columns.count_rounding: is read only for encoders in counts; accepted: with "
            "angle_unit = \"counts\"");
  EXPECT_EQ(refusal("[columns]\ntime_unit = \"iso\"\n").rfind(
                "logs/manifest.toml:2:13: columns.time_unit: 'iso' is not a time unit; accepted: s, ms, us (or µs), "
                "min, …, or \"iso8601\"",
                0),
            0u);
}

}  // namespace
}  // namespace ccal
