// Logs as data acquisition systems write them (io/csv_stream.hpp CsvFormat, intake/run_log.hpp): the same samples
// written comma-, semicolon- (with decimal commas), tab- and whitespace-separated, behind a preamble, with another
// comment prefix and a units row, reduce to the same bits; a units row supplies or contradicts the layout's
// units; a header of another delimiter and an undeclared decimal comma are refused saying which key to set;
// ISO 8601 timestamps read from the first sample; encoder counts read by their rounding; a declared gap is
// bridged (the pulse mean and the encoders' rates as without it, the missing time recorded) and an undeclared
// or longer one refused at its line with its length.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/intake/iso_time.hpp"
#include "ccal/intake/run_log.hpp"

namespace ccal {
namespace {

namespace fs = std::filesystem;

constexpr double kRate = 8.0;          // the joint's rate [rad/s]
constexpr double kPulsesPerS = 1000.25;  // the pulse rate
constexpr double kStep = 0.01;         // s between samples

// One sample's cells: t [s], the pulse count, θ1 in rad (9 decimals, wrapped).
std::vector<std::string> cells(int k) {
  const double t = kStep * k;
  return {fmt::format("{:.3f}", t), fmt::format("{}", std::floor(kPulsesPerS * t)),
          fmt::format("{:.9f}", std::fmod(1.5 + kRate * t, 2 * std::numbers::pi))};
}

struct Written {
  CsvFormat format;
  std::string preamble;    // lines before the header
  std::string units_line;  // after the header, as written
};

// The log of samples 0 … n−1 (skipping those `drop` says) in a format.
std::string log_text(const Written& w, int n, const std::function<bool(int)>& drop = {}) {
  const char d = w.format.delimiter;
  auto line = [&](std::vector<std::string> c) {
    std::string s;
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (k > 0) s += d == ' ' ? std::string("   ") : std::string(1, d);
      if (w.format.decimal == ',')
        for (char& ch : c[k]) ch = ch == '.' ? ',' : ch;
      s += c[k];
    }
    return s + "\n";
  };
  std::string text = w.preamble + line({"time", "pulses", "theta1"}) + w.units_line;
  for (int k = 0; k < n; ++k)
    if (!drop || !drop(k)) text += line(cells(k));
  return text;
}

class RunLogDaq : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ccal-run-log-daq-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    options_.pulse_weight = 1e-3;
  }
  void TearDown() override { fs::remove_all(dir_); }
  ReducedLog reduce(const std::string& text, const RunLogOptions& o) {
    const fs::path p = dir_ / "log.csv";
    std::ofstream(p) << text;
    return reduce_run_log_file(p, o, kRate);
  }
  std::string refusal(const std::string& text, const RunLogOptions& o) {
    try {
      reduce(text, o);
    } catch (const CsvError& e) {
      std::string s = e.what();
      return s.substr(s.find("log.csv"));
    }
    return "accepted";
  }
  fs::path dir_;
  RunLogOptions options_;
};

TEST_F(RunLogDaq, EveryDelimiterAndDecimalSeparatorGivesTheSameBits) {
  const ReducedLog comma = reduce(log_text({}, 2001), options_);
  ASSERT_TRUE(comma.has_theta1);
  EXPECT_NEAR(comma.theta1_rate, kRate, 1e-9);  // the 9 decimals' rounding over 20 s
  std::vector<Written> formats(4);
  formats[0].format.delimiter = ';';
  formats[0].format.decimal = ',';
  formats[1].format.delimiter = '\t';
  formats[2].format.delimiter = ' ';
  formats[2].format.comment = "//";
  formats[2].format.header_line = 4;
  formats[2].preamble = "DAQ 7 v2.1\n// operator: A\n\n";
  formats[3].format.delimiter = ';';
  formats[3].format.decimal = ',';
  formats[3].format.skip_lines = 2;
  formats[3].format.units_row = true;
  formats[3].preamble = "serial;42\nrate;100 Hz\n";
  formats[3].units_line = "s;counts;rad\n";
  for (const Written& w : formats) {
    RunLogOptions o = options_;
    o.format = w.format;
    const ReducedLog r = reduce(log_text(w, 2001), o);
    SCOPED_TRACE(std::string(csv_delimiter_name(w.format.delimiter)));
    // The same numbers, read by the same path: the same bits.
    EXPECT_EQ(r.samples, comma.samples);
    EXPECT_EQ(r.duration, comma.duration);
    EXPECT_EQ(r.mean_output, comma.mean_output);
    EXPECT_EQ(r.theta1_rate, comma.theta1_rate);
    EXPECT_EQ(r.theta1_start, comma.theta1_start);
  }
}

TEST_F(RunLogDaq, AUnitsRowSuppliesTheUnitsOrIsCheckedAgainstThem) {
  const ReducedLog s = reduce(log_text({}, 2001), options_);
  // Times in ms, said only by the units row.
  Written ms;
  ms.format.units_row = true;
  ms.units_line = "ms,counts,rad\n";
  std::string text = log_text(ms, 0);  // header and units
  for (int k = 0; k < 2001; ++k) {
    std::vector<std::string> c = cells(k);
    text += fmt::format("{},{},{}\n", 10 * k, c[1], c[2]);
  }
  RunLogOptions o = options_;
  o.format = ms.format;
  EXPECT_NEAR(reduce(text, o).duration, s.duration, 1e-12);
  EXPECT_NEAR(reduce(text, o).theta1_rate, kRate, 1e-9);
  // Without units_row the units are a row of bad cells (the "'ms' is not a number").
  EXPECT_NE(refusal(text, options_).find("log.csv:2:1: time: "), std::string::npos) << refusal(text, options_);
  // Stated twice, differently: refused naming both.
  o.time_unit_stated = "s";  // seconds, as the layout says: named as it writes them
  EXPECT_EQ(refusal(text, o),
            "log.csv:2:1: time: the units row says 'ms', the layout's time_unit is 's'; accepted: one unit (the "
            "manifest's time_unit left out, the units row gives it)");
  o.time_unit_stated.clear();
  Written deg = ms;
  deg.units_line = "s,counts,deg\n";
  o.angle_unit_stated = "rad";
  EXPECT_EQ(refusal(log_text(deg, 10), o),
            "log.csv:2:3: theta1: the units row says 'deg', the layout's angle_unit is 'rad'; accepted: one unit "
            "(the angle_unit left out, the units row gives it)");
  Written counts = ms;
  counts.units_line = "s,counts,counts\n";
  EXPECT_EQ(refusal(log_text(counts, 10), o),
            "log.csv:2:3: theta1: 'counts': the layout gives no counts per revolution; accepted: angle_unit = "
            "\"counts\" with counts_per_revolution in the [columns] table");
  Written pulses = ms;
  pulses.units_line = "s,V,rad\n";
  EXPECT_EQ(refusal(log_text(pulses, 10), o),
            "log.csv:2:2: pulses: 'V' is no count; accepted: counts, pulses, 1 or nothing");
  Written missing = ms;
  missing.units_line = "";
  EXPECT_EQ(refusal(log_text(missing, 0), o),
            "log.csv:1: no units row after the header; accepted: a line of the columns' units under the header, or "
            "units_row = false in the [format] table");
}

TEST_F(RunLogDaq, AnotherDelimiterOrAnUndeclaredDecimalCommaSaysWhichKeyToSet) {
  Written semicolon;
  semicolon.format.delimiter = ';';
  EXPECT_EQ(refusal(log_text(semicolon, 10), options_),
            "log.csv:1:1: the header is one name, 'time;pulses;theta1', which holds ';' between names: the "
            "delimiter is probably ';' (the file is read with comma); accepted: names separated by commas, or, in a "
            "run log, delimiter = \"semicolon\" in the [format] table of the manifest or of the layout file");
  Written tab;
  tab.format.delimiter = '\t';
  EXPECT_NE(refusal(log_text(tab, 10), options_).find("the delimiter is probably a tab"), std::string::npos);
  Written blanks;
  blanks.format.delimiter = ' ';
  EXPECT_NE(refusal(log_text(blanks, 10), options_).find("delimiter = \"whitespace\""), std::string::npos);
  // A comma file read as semicolon-separated.
  RunLogOptions o = options_;
  o.format.delimiter = ';';
  EXPECT_NE(refusal(log_text({}, 10), o).find("the delimiter is probably ',' (the file is read with semicolon); "
                                              "accepted: delimiter = \"comma\""),
            std::string::npos);
  // Decimal commas not declared: the cell as written, and the key.
  Written decimal = semicolon;
  decimal.format.decimal = ',';
  EXPECT_EQ(refusal(log_text(decimal, 10), o),
            "log.csv:2:1: time: '0,000' is not a number: a decimal comma? accepted: decimal = \"comma\" in the "
            "[format] table, or numbers with a decimal point");
}

TEST_F(RunLogDaq, TimestampsAreReadFromTheFirstSample) {
  const ReducedLog s = reduce(log_text({}, 2001), options_);
  std::string text = "time,pulses,theta1\n";
  const std::int64_t origin = *parse_iso8601_ns("2026-11-30T23:59:55.000+01:00");  // across midnight
  for (int k = 0; k < 2001; ++k) {
    const std::vector<std::string> c = cells(k);
    text += fmt::format("{},{},{}\n", iso8601_text(origin + std::int64_t(k) * 10000000), c[1], c[2]);
  }
  RunLogOptions o = options_;
  o.columns.iso_time = true;
  const ReducedLog r = reduce(text, o);
  // The times are the same multiples of 10 ms (exact in ns): the same reduction to the rounding of k·0.01.
  EXPECT_NEAR(r.duration, s.duration, 1e-12);
  EXPECT_NEAR(r.mean_output, s.mean_output, 1e-9 * s.mean_output);
  EXPECT_NEAR(r.theta1_rate, s.theta1_rate, 1e-9);
  text.insert(text.find('\n') + 1, "2026-11-30T25:00:00Z,0,1.5\n");
  EXPECT_EQ(refusal(text, o),
            "log.csv:2:1: time: '2026-11-30T25:00:00Z' is not a timestamp: there is no time of day 25:00:00; "
            "accepted: an ISO 8601 timestamp such as "
            "2026-11-30T10:15:02.125Z (or with an offset, +01:00; a fraction of up to 9 digits) (time_unit = "
            "\"iso8601\")");
}

TEST_F(RunLogDaq, CountsAreReadByTheirRounding) {
  // θ1 = 1.5 + 8 t in counts of 2^12 a revolution, latched down (floor) and to the nearest. Read by their own
  // convention, both give θ1(0) to the fit's resolution (the quantisation's error, at most half a count, averages
  // over 2001 samples to a few hundredths of a count); floor read as nearest is half a count (7.7e-4 rad) early.
  const double cpr = 4096, q = 2 * std::numbers::pi / cpr;
  auto text = [&](bool floor) {
    std::string s = "time,pulses,theta1\n";
    for (int k = 0; k < 2001; ++k) {
      const double t = kStep * k, c = (1.5 + kRate * t) / q;
      s += fmt::format("{:.3f},{},{}\n", t, std::floor(kPulsesPerS * t),
                       static_cast<long long>(floor ? std::floor(c) : std::nearbyint(c)) % 4096);
    }
    return s;
  };
  RunLogOptions o = options_;
  o.angle_scale = o.angle_quantum = q;
  const double nearest_read = reduce(text(false), o).theta1_start;
  const double floor_as_nearest = reduce(text(true), o).theta1_start;
  o.angle_offset = 0.5 * q;  // count_rounding = "floor"
  const double floor_read = reduce(text(true), o).theta1_start;
  EXPECT_NEAR(nearest_read, 1.5, 0.05 * q);
  EXPECT_NEAR(floor_read, 1.5, 0.05 * q);
  EXPECT_NEAR(floor_as_nearest, 1.5 - 0.5 * q, 0.05 * q);
}

TEST_F(RunLogDaq, ADeclaredGapIsBridgedAndALongerOneRefused) {
  // 60 s at 100 Hz with 5 s missing from t = 20 s (the samples 20.01 … 24.99 s): the pulse mean is from the
  // first and last counts, the same; the encoder's line over the samples present has the same rate to the
  // 9 decimals' rounding; the missing time is the gap less one step.
  const int n = 6001;
  const auto drop = [](int k) { return k > 2000 && k < 2500; };
  const ReducedLog whole = reduce(log_text({}, n), options_);
  RunLogOptions o = options_;
  o.max_gap = 10;
  const ReducedLog gap = reduce(log_text({}, n, drop), o);
  EXPECT_EQ(gap.samples, whole.samples - 499);
  EXPECT_EQ(gap.duration, whole.duration);
  EXPECT_EQ(gap.mean_output, whole.mean_output);
  EXPECT_NEAR(gap.theta1_rate, whole.theta1_rate, 1e-10);
  EXPECT_NEAR(gap.theta1_start, whole.theta1_start, 1e-9);
  EXPECT_EQ(gap.gaps, 1u);
  EXPECT_NEAR(gap.longest_gap, 5.0, 1e-9);
  EXPECT_NEAR(gap.missing, 4.99, 1e-9);
  EXPECT_EQ(whole.gaps, 0u);
  EXPECT_EQ(whole.missing, 0.0);
  // Not declared: the encoder cannot be unwrapped across it, and the message says what to declare.
  EXPECT_EQ(refusal(log_text({}, n, drop), options_),
            "log.csv:2003:3: theta1: samples 5 s apart turn the joint by 40 rad at the planned rate; accepted: less "
            "than 0.75π rad between encoder samples, or a gap in the log declared by max_gap in the [format] table "
            "(bridged at the encoder's mean rate)");
  // Longer than declared: refused at the sample after it, with its length.
  o.max_gap = 2;
  EXPECT_EQ(refusal(log_text({}, n, drop), o),
            "log.csv:2003:1: time: a gap of 5 s after the sample at 20 s (from the log's first); accepted: at most "
            "max_gap = 2 s (the [format] table)");
  // A pulse counter of 8 bits wraps 19 times in the gap: read across it at the count's mean rate.
  o.max_gap = 10;
  o.columns.counter_bits = 8;
  std::string wrapped = "time,pulses,theta1\n";
  for (int k = 0; k < n; ++k) {
    if (drop(k)) continue;
    const std::vector<std::string> c = cells(k);
    wrapped += fmt::format("{},{},{}\n", c[0], std::fmod(std::stod(c[1]), 256.0), c[2]);
  }
  EXPECT_EQ(reduce(wrapped, o).mean_output, whole.mean_output);
}

TEST_F(RunLogDaq, AGapAtTheLogsStartIsReportedAndNotBridged) {
  // 60 s at 100 Hz without the samples 0.01 … 4.99 s: the first step is the gap. A pulse log reads it as any
  // step (the mean from the first and last counts, the same bits) and reports it as a gap anywhere else is
  // (it was reported as none).
  const int n = 6001;
  const auto drop = [](int k) { return k > 0 && k < 500; };
  std::string whole = "time,pulses\n", gap = whole;
  for (int k = 0; k < n; ++k) {
    const std::vector<std::string> c = cells(k);
    whole += c[0] + "," + c[1] + "\n";
    if (!drop(k)) gap += c[0] + "," + c[1] + "\n";
  }
  const ReducedLog r = reduce(gap, options_);
  EXPECT_EQ(r.mean_output, reduce(whole, options_).mean_output);
  EXPECT_EQ(r.gaps, 1u);
  EXPECT_NEAR(r.longest_gap, 5.0, 1e-9);  // the times' 3 decimals, exact to 1e-12 s
  EXPECT_NEAR(r.missing, 4.99, 1e-9);
  // An encoder cannot bridge it (its rate is not known yet): refused saying so, not to declare max_gap.
  RunLogOptions o = options_;
  o.max_gap = 10;
  EXPECT_EQ(refusal(log_text({}, n, drop), o),
            "log.csv:3:3: theta1: samples 5 s apart turn the joint by 40 rad at the planned rate; accepted: less "
            "than 0.75π rad between encoder samples, and max_gap bridges a gap only after shorter steps (not at the "
            "log's start: the log from after the gap)");
}

TEST_F(RunLogDaq, APreambleTooLongOrAHeaderLineBeyondTheFileIsRefused) {
  RunLogOptions o = options_;
  o.format.header_line = 50;
  EXPECT_EQ(refusal(log_text({}, 10), o),
            "log.csv:11: the file ends at line 11, before its header at line 50; accepted: the header's line as "
            "header_line of the [format] table");
  // Found by the careless round: a file within its skip_lines was "no header row (only comments and blank
  // lines)"; a header_line at a comment was read as a header of one name, "the delimiter is probably
  // whitespace".
  o.format.header_line = 0;
  o.format.skip_lines = 100;
  EXPECT_EQ(refusal(log_text({}, 10), o),
            "log.csv:11: the file ends at line 11, within its skip_lines = 100 lines skipped; accepted: the count "
            "of lines before the header as skip_lines of the [format] table");
  o.format.skip_lines = 0;
  o.format.header_line = 1;
  Written commented;
  commented.preamble = "# DAQ 7\n";
  EXPECT_EQ(refusal(log_text(commented, 10), o),
            "log.csv:1:1: line 1, the header_line of the [format] table, is a comment ('# DAQ 7'); accepted: the "
            "line of the column names as header_line, or comment = \"\" for a header that begins with '#'");
}

}  // namespace
}  // namespace ccal
