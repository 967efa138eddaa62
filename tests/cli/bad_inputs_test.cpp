// A catalogue of bad inputs across configuration, CSV files, run logs and command-line options: each must
// give exit code 2, one line on standard error naming the place (file, key, option), nothing on standard
// output, and leave every file in the folder as it was. Table-driven: one row per input.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <sstream>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "cli_support.hpp"

namespace ccal::test {
namespace {

struct BadInput {
  std::string name;                                        // test name
  std::vector<std::pair<std::string, std::string>> files;  // written into the folder before the run
  std::string args;                                        // command line (shell words)
  std::vector<std::string> hints;                          // in the message: the place, and what is wrong
};

std::string example() { return read(kExample); }

// The example with the first occurrence of `from` replaced by `to`.
std::string example_with(const std::string& from, const std::string& to) {
  std::string text = example();
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("not in the example: " + from);
  return text.replace(at, from.size(), to);
}

// A log of the run at `g_level` (bundled example: R0 = 2.5 m, g = 9.8 m/s²): 0.05 s samples over 20 s, the
// output column, and the main-axis encoder turning at rate_factor × the planned rate, in `scale` units per
// rad.
std::string log_text(double g_level, double rate_factor = 1.0, double scale = 1.0, double output = 100.0) {
  const double rate = std::sqrt(g_level * 9.8 / 2.5);
  std::string text = "time,output,theta1\n";
  for (int k = 0; k <= 400; ++k) {
    const double t = 0.05 * k;
    text += std::to_string(t) + "," + std::to_string(output) + "," +
            std::to_string(std::fmod(rate_factor * rate * t, 2 * std::numbers::pi) * scale) + "\n";
  }
  return text;
}

// A log's text with its time column as ISO 8601 timestamps in the minute `start` ("2026-11-30T10:15:"), the
// seconds (from `second`) with 3 decimals and `zone` appended ("Z", "+01:00" or "").
std::string iso_log_text(const std::string& text, const std::string& start, const std::string& zone,
                         double second = 0) {
  std::istringstream in(text);
  std::string out, line;
  std::getline(in, line);
  out = line + "\n";
  while (std::getline(in, line)) {
    const auto comma = line.find(',');
    out += fmt::format("{}{:06.3f}{}{}\n", start, second + std::stod(line.substr(0, comma)), zone,
                       line.substr(comma));
  }
  return out;
}

// `text` without its lines first … last (1-based).
std::string without_lines(const std::string& text, int first, int last) {
  std::istringstream in(text);
  std::string out, line;
  for (int k = 1; std::getline(in, line); ++k)
    if (k < first || k > last) out += line + "\n";
  return out;
}

const std::string kObs = "obs.csv";
std::string observations() {  // a plain x, y table
  return "x,y\n1,1.1\n2,2.0\n3,2.9\n4,4.2\n5,5.0\n";
}

std::vector<BadInput> catalogue() {
  using F = std::vector<std::pair<std::string, std::string>>;
  const F cfg = {{"c.toml", example()}};
  auto config = [](const std::string& from, const std::string& to) {
    return F{{"c.toml", example_with(from, to)}};
  };
  // The logs span 20 s: so does the plan of their configuration (a shorter log is reported, on its own line).
  const std::string logged = example_with("duration = \"450 s\"", "duration = \"20 s\"");
  const F logs = {
      {"c.toml", logged}, {"a.csv", log_text(5)}, {"b.csv", log_text(10)}, {"d.csv", log_text(15)}};
  auto logs_with = [&](const std::string& a) {
    return F{{"c.toml", logged}, {"a.csv", a}, {"b.csv", log_text(10)}, {"d.csv", log_text(15)}};
  };
  const std::string reduce = "reduce c.toml --log 5g=a.csv --log 10g=b.csv --log 15g=d.csv";
  // The logs with a layout file (its text), the 5 g run's log given.
  const std::string lay = " --log-layout lay.toml";
  auto layout = [&](const std::string& tables, const std::string& a) {
    return F{{"c.toml", logged}, {"a.csv", a}, {"b.csv", log_text(10)}, {"d.csv", log_text(15)},
             {"lay.toml", tables}};
  };
  const std::string iso = "[columns]\ntime_unit = \"iso8601\"\n";
  const F obs = {{kObs, observations()}};
  auto csv = [](const std::string& text) { return F{{"t.csv", text}}; };
  const std::string fit = "identify t.csv --input-column x --output-column y --terms K0,K1";
  std::string huge_cell(100000, '9');
  huge_cell = "x,y\n1," + huge_cell + "x\n2,2\n3,3\n";

  return {
      // --- configuration -------------------------------------------------------------------------------
      {"ConfigMissing", {}, "budget nothere.toml", {"nothere.toml"}},
      {"ConfigFolder", {}, "budget .", {"."}},
      {"ConfigEmpty", {{"c.toml", ""}}, "budget c.toml", {"c.toml"}},
      {"ConfigNotToml", {{"c.toml", "[site\nlatitude = 1\n"}}, "budget c.toml", {"c.toml:1"}},
      {"ConfigUnknownKey",
       config("height = \"0 m\"", "heigth = \"0 m\""),
       "budget c.toml",
       {"c.toml", "heigth"}},
      {"ConfigLatitudeRange",
       config("\"45.75 deg\"", "\"100 deg\""),
       "budget c.toml",
       {"c.toml", "latitude"}},
      {"ConfigNegativeG", config("\"9.8 m/s^2\"", "\"-9.8 m/s^2\""), "budget c.toml", {"c.toml", "g"}},
      {"ConfigRadiusUnit", config("\"2.5 m\"", "\"2.5 kg\""), "budget c.toml", {"c.toml", "radius"}},
      {"ConfigRadiusZero", config("\"2.5 m\"", "\"0 m\""), "budget c.toml", {"c.toml", "radius"}},
      {"ConfigRadiusHuge", config("\"2.5 m\"", "\"1e30 m\""), "budget c.toml", {"c.toml", "radius"}},
      {"ConfigRadiusText", config("\"2.5 m\"", "\"two metres\""), "budget c.toml", {"c.toml", "radius"}},
      {"ConfigHarmonicOrder",
       config("harmonic_order = 1 ", "harmonic_order = -3 "),
       "budget c.toml",
       {"c.toml", "harmonic_order"}},
      {"ConfigUnknownError",
       config("[errors]\n", "[errors]\ndxyz = \"1 um\"\n"),
       "budget c.toml",
       {"c.toml", "dxyz"}},
      {"ConfigErrorUnit",
       config("[errors]\n", "[errors]\ndthz5 = \"2 m\"\n"),
       "budget c.toml",
       {"c.toml", "dthz5"}},
      {"ConfigToleranceNegative",
       config("dx3_s1 = { bound = \"10 um\"", "dx3_s1 = { bound = \"-10 um\""),
       "budget c.toml",
       {"c.toml", "dx3_s1"}},
      {"ConfigToleranceDistribution",
       config("distribution = \"arcsine\" }", "distribution = \"cauchy\" }"),
       "budget c.toml",
       {"c.toml", "cauchy"}},
      {"ConfigUnknownTerm",
       config("terms = [\"K0\", \"K2\", \"K3\"]", "terms = [\"K0\", \"K2\", \"Kx\"]"),
       "budget c.toml",
       {"c.toml", "Kx"}},
      {"ConfigMode", config("mode = \"exact\"", "mode = \"fast\""), "budget c.toml", {"c.toml", "fast"}},
      {"ConfigDurationZero",
       config("duration = \"450 s\"", "duration = \"0 s\""),
       "budget c.toml",
       {"c.toml", "duration"}},
      {"ConfigDurationHuge",
       config("duration = \"450 s\"", "duration = \"1e12 s\""),
       "budget c.toml",
       {"c.toml", "duration"}},
      {"ConfigPlatform",
       config("platform = \"counter_rotating\"", "platform = \"spinning\""),
       "budget c.toml",
       {"c.toml", "platform"}},
      {"ConfigGLevelNegative",
       config("g_level = \"5 g\"", "g_level = \"-5 g\""),
       "budget c.toml",
       {"c.toml", "g_level"}},
      {"ConfigGLevelHuge",
       config("g_level = \"5 g\"", "g_level = \"1e6 g\""),
       "budget c.toml",
       {"c.toml", "g_level"}},
      {"ConfigOutputUnit",
       config("output_unit = \"deg/s\"", "output_unit = \"furlong\""),
       "budget c.toml",
       {"c.toml", "output_unit"}},
      {"ConfigEscapeSequence",
       config("mode = \"exact\"", "mode = \"\\u001b[2Jexact\""),
       "budget c.toml",
       {"c.toml", "\\x1b"}},
      // "\u0000" in a TOML string cut the message at the NUL: shown as \x00, the accepted values follow.
      {"ConfigNulInAString",
       config("mode = \"exact\"", "mode = \"ex\\u0000act\""),
       "budget c.toml",
       {"c.toml", "'ex\\x00act'", "accepted: exact, paper"}},
      {"ConfigErrorOverflowsTheRunMeans",
       config("[errors]\n", "[errors]\ndR_s = \"1e300 m\"\n"),
       "simulate c.toml",
       {"c.toml:", "errors.dR_s: 1e300 m is implausible for a measured error of the machine"}},
      // More free terms than runs: refused by simulate before any fit, naming the configuration.
      {"ConfigMoreTermsThanRuns",
       config("terms = [\"K0\", \"K2\", \"K3\"]",
              "terms = [\"K0\", \"K2\", \"K3\", \"K4\", \"K5\", \"K6\", \"K7\"]"),
       "simulate c.toml",
       {"c.toml", "6 runs cannot determine 7 free terms", "at least 7 runs"}},
      // 1e300 µm reached allocate and was reported as "configured U = inf" without a place: refused where it
      // is written, with the accepted range.
      {"ConfigToleranceBeyondAnyPhysicalSize",
       config("dx3_s1 = { bound = \"10 um\"", "dx3_s1 = { bound = \"1e300 um\""),
       "allocate c.toml --target K3=1e-6 --verify-trials 0",
       {"c.toml:", "tolerances.dx3_s1.bound", "1e+294 m is too large", "up to 1e100 m"}},
      {"ConfigToleranceBeyondAnyPhysicalSizePlain",
       config("dthz5 = \"1e-5 rad\"", "dthz5 = \"1e101 rad\""),
       "budget c.toml",
       {"c.toml:", "tolerances.dthz5", "up to 1e100 rad"}},
      {"ConfigToleranceOverflowsTheBudget",
       config("dx3_s1 = { bound = \"10 um\"", "dx3_s1 = { bound = \"1e200 m\""),
       "budget c.toml",
       {"c.toml", "dx3_s1", "not a finite number"}},
      // --- CSV files (identify) -------------------------------------------------------------------------
      {"CsvMissing", {}, "identify none.csv", {"none.csv"}},
      {"CsvEmpty", csv(""), fit, {"t.csv"}},
      {"CsvNumbersFirst", csv("1,2\n3,4\n"), fit, {"t.csv:1"}},
      {"CsvDuplicateColumn", csv("x,y,x\n1,2,3\n"), fit, {"t.csv:1:3", "duplicate"}},
      {"CsvRaggedRow", csv("x,y\n1,2\n3\n"), fit, {"t.csv:3", "ragged"}},
      {"CsvNotANumber", csv("x,y\n1,2\n3,abc\n4,5\n"), fit, {"t.csv:3:2", "abc"}},
      {"CsvNan", csv("x,y\n1,2\n3,nan\n4,5\n"), fit, {"t.csv:3:2"}},
      {"CsvHugeCell", csv(huge_cell), fit, {"t.csv:2:2", "bytes left out"}},
      {"CsvTooFewRows", csv("x,y\n1,2\n"), fit, {"t.csv", "K0, K1"}},
      // Old Mac line ends (CR only) read as one line, refused as "no header row" without saying why.
      {"CsvCarriageReturnLineEnds",
       csv("# ccal observations\rx,y\r1,1\r2,2\r3,3\r"),
       fit,
       {"t.csv:1:20", "CR-only line ends", "LF or CRLF"}},
      // A NUL byte cut the message short at the C string of what(): it is shown as \x00, and the rest
      // follows.
      {"CsvNulByteInACell",
       csv(std::string("x,y\n1,2\n3,a\0b\n4,5\n", 18)),
       fit,
       {"t.csv:3:2", "a\\x00b' is not a number", "accepted: a decimal number"}},
      // Finite data near 1e308 overflowed in the fit: "K0 = -nan ± -nan" with exit code 0.
      {"CsvFitOverflows",
       csv("x,y\n1,1e308\n2,1.2e308\n3,1.4e308\n4,1.7e308\n"),
       fit,
       {"t.csv: the estimate of K0", "not a finite number", "scale y"}},
      {"CsvMissingInputColumn",
       obs,
       "identify obs.csv --input-column a --output-column y --terms K0,K1",
       {"obs.csv", "a"}},
      {"CsvUnknownTerm",
       obs,
       "identify obs.csv --input-column x --output-column y --terms K0,Q7",
       {"--terms", "Q7"}},
      {"CsvPowerOverflow",
       csv("x,y\n1e200,1\n2e200,2\n3e200,3\n4e200,4\n"),
       "identify t.csv --input-column x --output-column y --terms K0,K1,K2",
       {"t.csv:2:1", "K2"}},
      {"CsvWeightZero", csv("x,y,s\n1,1,1\n2,2,0\n3,3,1\n"), fit + " --weight-column s", {"t.csv:3:3", "σ"}},
      {"CsvWeightHuge",
       csv("x,y,s\n1,1,1e200\n2,2,1e200\n3,3,1e200\n"),
       fit + " --weight-column s",
       {"t.csv:2:3", "underflows"}},
      {"CsvWeightColumnMissing",
       obs,
       "identify obs.csv --input-column x --output-column y --terms K0,K1 --weight-column sd",
       {"obs.csv", "sd"}},
      // --- run logs (reduce) ------------------------------------------------------------------------------
      {"LogNotRunEqualsFile", logs, "reduce c.toml --log a.csv", {"--log", "a.csv"}},
      {"LogUnknownRun",
       logs,
       "reduce c.toml --log 7g=a.csv --log 10g=b.csv --log 15g=d.csv",
       {"--log", "7g"}},
      {"LogRunTwice", logs, "reduce c.toml --log 5g=a.csv --log 5g=b.csv --log 15g=d.csv", {"--log", "5g"}},
      {"LogMissingFile", logs, "reduce c.toml --log 5g=zz.csv --log 10g=b.csv --log 15g=d.csv", {"zz.csv"}},
      {"LogTooFew", logs, "reduce c.toml --log 5g=a.csv", {"--log", "K0, K2, K3"}},
      {"LogTimeNotIncreasing", logs_with("time,output\n0,1\n2,1\n1,1\n"), reduce, {"a.csv:4:1", "time"}},
      {"LogNoOutputColumn", logs_with("time,volts\n0,1\n1,1\n"), reduce, {"a.csv", "output"}},
      {"LogPulsesAndOutput", logs_with("time,pulses,output\n0,1,1\n1,2,1\n"), reduce, {"a.csv", "pulses"}},
      {"LogOneSample", logs_with("time,output\n0,1\n"), reduce, {"a.csv", "two"}},
      {"LogEmpty", logs_with(""), reduce, {"a.csv:1", "empty file"}},
      {"LogOutputOverflows", logs_with("time,output\n0,1e308\n1,1e308\n"), reduce, {"a.csv", "overflows"}},
      {"LogEncoderInDegrees",
       logs_with(log_text(5, 1.0, 180 / std::numbers::pi)),
       reduce,
       {"a.csv", "theta1", "372 of 401 readings depart", "angle_unit = deg"}},
      {"LogEncoderReversed", logs_with(log_text(5, -1.0)), reduce, {"a.csv", "5g", "reversed"}},
      {"LogEncoderOtherRun", logs_with(log_text(10)), reduce, {"a.csv", "5g", "another run"}},
      {"LogAngleUnit", logs, reduce + " --angle-unit grad", {"--angle-unit", "grad"}},
      {"LogCarriageReturnLineEnds",
       logs_with("time,output\r0,1\r1,1\r2,1\r"),
       reduce,
       {"a.csv:1:12", "CR-only line ends", "LF or CRLF"}},
      {"LogPulseWeight", logs, reduce + " --pulse-weight -1", {"--pulse-weight", "-1"}},
      // --- run logs in a layout (reduce --log-layout; a folder's manifest reads the same tables) -----------
      {"LayoutHeaderLineAComment",
       layout("[format]\nheader_line = 1\n", "# DAQ 7, serial 0815\n" + log_text(5)),
       reduce + lay,
       {"a.csv:1:1", "line 1, the header_line of the [format] table, is a comment ('# DAQ 7, serial 0815')",
        "comment = \"\""}},
      {"LayoutHeaderLineBlank",
       layout("[format]\nheader_line = 2\n", "# DAQ 7\n\n" + log_text(5)),
       reduce + lay,
       {"a.csv:2:1", "is blank; accepted: the line of the column names"}},
      {"LayoutSkipLinesPastTheEnd",
       layout("[format]\nskip_lines = 100000\n", log_text(5)),
       reduce + lay,
       {"a.csv:402", "the file ends at line 402, within its skip_lines = 100000 lines skipped"}},
      {"LayoutUnitsRowMissing",
       layout("[format]\nunits_row = true\n", log_text(5)),
       reduce + lay,
       {"a.csv:2:1", "a row of numbers where the units row should be", "units_row = false"}},
      {"LayoutNotToml",
       F{{"c.toml", logged},
         {"a.csv", log_text(5)},
         {"b.csv", log_text(10)},
         {"d.csv", log_text(15)},
         {"lay.toml", "delimiter: semicolon\n"}},
       reduce + lay,
       {"lay.toml:1", "TOML syntax error",
        "accepted: a layout file in TOML: a manifest's [format] and [columns]"}},
      {"LayoutAFolder",
       logs,
       reduce + " --log-layout .",
       {".: it is a folder; accepted: a layout file in TOML"}},
      {"LayoutDelimiterANumber",
       layout("[format]\ndelimiter = 59\n", log_text(5)),
       reduce + lay,
       {"lay.toml:2:13",
        "format.delimiter: expected a string, got an integer; accepted: \"comma\", "
        "\"semicolon\", \"tab\", \"whitespace\""}},
      {"LayoutSkipLinesQuoted",
       layout("[format]\nskip_lines = \"2\"\n", log_text(5)),
       reduce + lay,
       {"lay.toml:2:14",
        "format.skip_lines: expected a number, got a string; accepted: a whole number from 0"}},
      {"LayoutMaxGapNaN",
       layout("[format]\nmax_gap = \"nan s\"\n", log_text(5)),
       reduce + lay,
       {"lay.toml:2:11", "format.max_gap", "accepted: a finite number and its unit, e.g. '1 s'"}},
      // A gap after the first sample cannot be bridged: the message said to declare max_gap, declared.
      {"LayoutGapAtTheStart",
       layout("[format]\nmax_gap = \"10 s\"\n", without_lines(log_text(5), 3, 41)),
       reduce + lay,
       {"a.csv:3:3", "samples 2 s apart",
        "max_gap bridges a gap only after shorter steps (not at the log's "
        "start"}},
      {"LayoutMillisecondsReadAsSeconds",
       layout("[columns]\ntime_unit = \"ms\"\n", log_text(5)),
       reduce + lay,
       {"a.csv: run '5g'", "1000 times the plan's", "times in another unit than the one read (0.001 s)",
        "time_unit"}},
      {"LayoutNoHeaderAPreamble",
       F{{"c.toml", logged},
         {"a.csv", "DAQ 7, serial 0815\n" + log_text(5)},
         {"b.csv", log_text(10)},
         {"d.csv", log_text(15)}},
       reduce,
       {"a.csv:1",
        "the header, line 1 ('DAQ 7,serial 0815'), names none of a log's columns: a preamble above "
        "it? accepted: header_line or skip_lines"}},
      // Radians read as degrees: the message said "degrees read as radians".
      {"LayoutRadiansReadAsDegrees",
       layout("[columns]\nangle_unit = \"deg\"\n", log_text(5)),
       reduce + lay,
       {"a.csv:1:3", "theta1", "likely cause: angles in another unit than the one read (0.0174533 rad"}},
      // The first timestamps in UTC, the next without a zone: the time between them was read as written.
      {"LogIsoTimestampsWithAndWithoutZone",
       layout(iso, without_lines(iso_log_text(log_text(5), "2026-11-30T10:15:", "Z"), 12, 402) +
                       without_lines(iso_log_text(log_text(5), "2026-11-30T10:15:", ""), 1, 11)),
       reduce + lay,
       {"a.csv:12:1", "'2026-11-30T10:15:00.500' states no zone, the log's first timestamp (line 2) does",
        "accepted: every timestamp of a log with its zone"}},
      {"LogIsoLeapSecond",
       layout(iso, iso_log_text(log_text(5), "2016-12-31T23:59:", "Z", 45)),
       reduce + lay,
       {"a.csv:302:1", "'2016-12-31T23:59:60.000Z' is not a timestamp: a leap second (:60)"}},
      {"LogIsoNoSuchDay",
       layout(iso, iso_log_text(log_text(5), "2026-02-30T10:15:", "Z")),
       reduce + lay,
       {"a.csv:2:1", "'2026-02-30T10:15:00.000Z' is not a timestamp: 2026-02 has no day 30"}},
      {"LogIsoNotIncreasing",
       layout(iso, without_lines(iso_log_text(log_text(5), "2026-11-30T10:15:", "Z"), 4, 402) +
                       without_lines(iso_log_text(log_text(5), "2026-11-30T10:15:", "Z"), 1, 2)),
       reduce + lay,
       {"a.csv:4:1",
        "'2026-11-30T10:15:00.050Z' (0.05 s from the log's first sample) does not follow the sample "
        "before it (0.05 s from the first)"}},
      // --- command-line options -------------------------------------------------------------------------
      {"UnknownCommand", {}, "budgit", {"budgit", "budget"}},
      {"UnknownOption", {}, "budget --frobnicate", {"--frobnicate"}},
      {"Format", {}, "budget --format xml", {"--format", "xml"}},
      {"BudgetMode", {}, "budget --mode fast", {"--mode", "fast"}},
      {"TrialsOne", {}, "montecarlo --trials 1", {"--trials", "2 to"}},
      {"TrialsMemory", {}, "montecarlo --trials 1000000000", {"1000000000 trials", "GiB"}},
      {"TrialsText", {}, "montecarlo --trials many", {"--trials", "many"}},
      {"Threads", {}, "montecarlo --threads 5000", {"--threads", "1 to 1024"}},
      {"Coverage", {}, "montecarlo --coverage-probability 1.5", {"--coverage-probability", "1.5"}},
      {"Digits", {}, "montecarlo --digits 9", {"--digits", "9"}},
      // 10 trials cannot give a 99.9999 % interval (q = round(pM) = M: no end values); it printed inf.
      {"CoverageBeyondTheTrials",
       {},
       "montecarlo --coverage-probability 0.999999 --trials 10",
       {"--coverage-probability: 0.999999 with --trials = 10", "--trials at least 500001",
        "below 1 − 1/(2M) = 0.95"}},
      {"CoverageBeyondTheDefaultTrials",
       {},
       "montecarlo --coverage-probability 0.9999999999",
       {"with --trials = 1000000", "--trials at least 5000", "below 1 − 1/(2M) = 0.9999995"}},
      // --coverage meant the factor k in budget and a probability here: refused, naming the new option.
      {"CoverageAmbiguous",
       {},
       "montecarlo --trials 100 --coverage 0.95",
       {"--coverage", "--coverage-probability"}},
      {"SamplesOutIsOutput",
       {},
       "montecarlo --trials 100 -o s.csv --samples-out s.csv",
       {"--samples-out", "s.csv"}},
      {"SamplesOutMissingFolder",
       {},
       "montecarlo --trials 100 -o x.txt --samples-out no/such/s.npy",
       {"--samples-out", "no/such/s.npy"}},
      {"ReportRun", {}, "report --trials 100 --run 99 -o r.html", {"--run", "99"}},
      {"ReportTrials", {}, "report --trials 1 -o r.html", {"--trials"}},
      // The sections' targets are refused naming the report's own options, before anything is computed.
      {"ReportAllocateTarget",
       {},
       "report --trials 100 --allocate-target K9=1 -o r.html",
       {"--allocate-target", "K9"}},
      {"ReportAllocateValue",
       {},
       "report --trials 100 --allocate-target K3=-1 -o r.html",
       {"--allocate-target", "-1"}},
      {"ReportAllocateTiny",
       {},
       "report --trials 100 --allocate-target K3=1e-300 -o r.html",
       {"K3", "1e-300"}},
      {"ReportDesignTarget",
       {},
       "report --trials 100 --design-target 'K3=1e-4 kg' -o r.html",
       {"--design-target", "kg"}},
      // A flag takes no value but true or false.
      {"DesignFreshCandidatesValue", {}, "design --fresh-candidates=maybe", {"--fresh-candidates", "maybe"}},
      // The statement's observations: a file that cannot be read, and one whose terms are not the
      // configuration's (K0, K1 against the bundled example's K0, K2, K3).
      {"ReportObservationsMissing",
       {},
       "report --trials 100 --observations none.csv -o r.html",
       {"--observations", "none.csv"}},
      {"ReportObservationsTerms",
       {{"obs.csv",
         "# ccal observations v1; terms=K0:K0,K1:K1; fixed=; known=; output_unit=deg/s\n"
         "run,a_i,output,K0,K1\n1g,1,1.1,1,1\n2g,2,2.0,1,2\n3g,3,2.9,1,3\n4g,4,4.2,1,4\n"}},
       "report --trials 100 --observations obs.csv -o r.html",
       {"--observations", "K1", "K0, K2, K3"}},
      // A plain table (not an observations file): the report has no --terms to offer.
      {"ReportObservationsPlainTable",
       obs,
       "report --trials 100 --observations obs.csv -o r.html",
       {"--observations", "obs.csv", "no '# ccal observations' line", "simulate or reduce writes (--observations-out)"}},
      {"SeedNegative", {}, "montecarlo --trials 100 --seed -1", {"--seed", "-1"}},
      {"AllocateTinyTarget", {}, "allocate --target K3=1e-300 --verify-trials 0", {"K3", "1e-300"}},
      {"AllocateUnknownTarget", {}, "allocate --target K9=1", {"K9"}},
      {"AllocateMaxScale", {}, "allocate --target K3=1e-3 --max-scale -1", {"--max-scale", "-1"}},
      {"AllocateNoTarget", {}, "allocate", {"target"}},
      {"ForceRun", {}, "force --run 99", {"--run", "99"}},
      {"ForceTimeUnit", {}, "force --time '10 kg'", {"--time", "kg"}},
      {"OutputIsTheConfig", cfg, "budget c.toml -o c.toml", {"-o", "c.toml", "input"}},
      {"OutputIsALog", logs, reduce + " -o b.csv", {"-o", "b.csv", "input"}},
      {"ObservationsOutIsOutput",
       cfg,
       "simulate c.toml -o x.txt --observations-out x.txt",
       {"--observations-out", "x.txt"}},
      // One file by two spellings: compared by identity (device and inode, or the resolved path of a new
      // file), not by spelling; both were written, one over the other.
      {"ObservationsOutIsOutputSpelledTwoWays",
       cfg,
       "simulate c.toml -o ./same.txt --observations-out same.txt",
       {"--observations-out", "same.txt", "-o file"}},
      {"ObservationsOutIsOutputSpelledThreeWays",
       cfg,
       "simulate c.toml -o same.txt --observations-out .//same.txt",
       {"--observations-out", ".//same.txt", "-o file"}},
      {"SamplesOutIsOutputSpelledTwoWays",
       {},
       "montecarlo --trials 100 -o s.csv --samples-out ./s.csv",
       {"--samples-out", "./s.csv", "-o file"}},
      {"OutputIsAFolder", {}, "budget -o .", {"-o", "'.'"}},
      {"OutputInAMissingFolder", {}, "budget -o no/such/x.txt", {"-o", "no/such/x.txt"}},
  };
}

class BadInputs : public Cli, public ::testing::WithParamInterface<BadInput> {
 protected:
  // Every file in the folder with its bytes and permissions.
  std::map<std::string, std::pair<std::string, fs::perms>> snapshot() const {
    std::map<std::string, std::pair<std::string, fs::perms>> files;
    for (const auto& e : fs::recursive_directory_iterator(dir_))
      files[e.path().string()] = {e.is_regular_file() ? read(e.path()) : "", e.status().permissions()};
    return files;
  }
};

TEST_P(BadInputs, ExitTwoWithOneLinedMessageAndNoFileChanged) {
  const BadInput& c = GetParam();
  for (const auto& [name, text] : c.files) write(name, text);
  const auto before = snapshot();
  const Result r = run(c.args);
  std::vector<std::string> hints(c.hints.begin(), c.hints.end());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_TRUE(r.err.starts_with("ccal: error: ")) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_LT(r.err.size(), 1200u) << "the message is not shortened";
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << "a raw escape character in " << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  for (const auto& h : hints) EXPECT_NE(r.err.find(h), std::string::npos) << "'" << h << "' in " << r.err;
  EXPECT_EQ(snapshot(), before) << "a file was changed, created or removed";
}

INSTANTIATE_TEST_SUITE_P(Catalogue, BadInputs, ::testing::ValuesIn(catalogue()),
                         [](const ::testing::TestParamInfo<BadInput>& info) { return info.param.name; });

TEST(BadInputsCatalogue, HoldsAtLeastSixtyInputs) { EXPECT_GE(catalogue().size(), 60u); }

}  // namespace
}  // namespace ccal::test
