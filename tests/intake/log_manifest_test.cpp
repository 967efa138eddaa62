// A folder of run logs and its manifest (intake/log_manifest.hpp): the layout a data acquisition system writes —
// column names, time unit, encoders in counts — read from the manifest; the manifest ccal writes read back to
// the same layout and runs; logs written in a DAQ layout reduce to the run's mean and rates as ccal's own do;
// every refusal located with what is accepted.
#include "ccal/intake/log_manifest.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/intake/run_log_writer.hpp"

namespace ccal {
namespace {

const std::string kDaq = R"([columns]
time = "t_ms"
time_unit = "ms"
pulses = "piga_count"
theta1 = "enc_main"
gamma = "enc_platform"
angle_unit = "counts"
counts_per_revolution = 16777216
[runs]
5g = "run_05g.csv"
3 = "sub/run3.csv"
)";

std::string manifest_refusal(const std::string& text) {
  try {
    parse_log_manifest(text, "logs/manifest.toml", "logs");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(LogManifest, ADaqLayoutIsReadAsWritten) {
  const LogManifest m = parse_log_manifest(kDaq, "logs/manifest.toml", "logs");
  EXPECT_EQ(m.layout.columns.time, "t_ms");
  EXPECT_EQ(m.layout.columns.pulses, "piga_count");
  EXPECT_EQ(m.layout.columns.output, "output");  // not stated: ccal's name
  EXPECT_EQ(m.layout.columns.theta1, "enc_main");
  EXPECT_EQ(m.layout.columns.gamma, "enc_platform");
  EXPECT_DOUBLE_EQ(m.layout.columns.time_scale, 1e-3);
  EXPECT_EQ(m.layout.counts_per_revolution, 16777216);
  EXPECT_DOUBLE_EQ(m.layout.angle_scale, 2 * std::numbers::pi / 16777216);
  ASSERT_EQ(m.runs.size(), 2u);
  EXPECT_EQ(m.runs[0].run, "5g");
  EXPECT_EQ(m.runs[0].file, std::filesystem::path("logs/run_05g.csv"));
  EXPECT_EQ(m.runs[1].run, "3");
  EXPECT_EQ(m.runs[1].file, std::filesystem::path("logs/sub/run3.csv"));
  // An angle unit: its size in rad.
  const LogManifest deg =
      parse_log_manifest("[columns]\nangle_unit = \"deg\"\n[runs]\n1 = \"a.csv\"\n", "m", ".");
  EXPECT_DOUBLE_EQ(deg.layout.angle_scale, std::numbers::pi / 180);
}

TEST(LogManifest, TheManifestCcalWritesReadsBackToTheSameLayoutAndRuns) {
  const LogManifest m = parse_log_manifest(kDaq, "logs/manifest.toml", "logs");
  const std::string text = log_manifest_text(m.layout, {{"5g", "run_05g.csv"}, {"3", "sub/run3.csv"}});
  const LogManifest back = parse_log_manifest(text, "again.toml", "logs");
  EXPECT_EQ(back.layout.columns.time, m.layout.columns.time);
  EXPECT_EQ(back.layout.columns.time_scale, m.layout.columns.time_scale);
  EXPECT_EQ(back.layout.angle_scale, m.layout.angle_scale);
  ASSERT_EQ(back.runs.size(), 2u);
  EXPECT_EQ(back.runs[1].file, m.runs[1].file);
  // A counter's width is written back (and a pulse log written in that layout wraps: the round trip of
  // tests/intake/run_log_test.cpp's unwrapping).
  LogLayout counter = m.layout;
  counter.columns.counter_bits = 16;
  EXPECT_EQ(parse_log_manifest(log_manifest_text(counter, {{"1", "a.csv"}}), "m", ".").layout.columns.counter_bits,
            16);
  // A run name TOML must quote (a dot, a space) is written quoted.
  const LogManifest odd = parse_log_manifest(log_manifest_text({}, {{"run 1.5", "run_1.5.csv"}}), "m", ".");
  EXPECT_EQ(odd.runs[0].run, "run 1.5");
}

// Runs "a b" and "a_b" map to one log file: refused naming both runs and the file, before anything is written
// (they once met as "it is also the --logs-out file", naming no run).
TEST(LogManifest, RunsWhoseLogFilesWouldCoincideAreRefused) {
  Config config = bundled_example();
  config.plan.runs[1].name = "a b";
  config.plan.runs[4].name = "a_b";
  const std::vector<double> means(config.plan.runs.size(), 0.5);
  try {
    write_run_logs(config, config.centrifuge.errors, means, default_log_step(config));
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("runs 'a b' and 'a_b' would both be logged to a_b.csv"),
              std::string::npos)
        << e.what();
  }
  config.plan.runs[4].name = "a-b";  // another file name: accepted
  EXPECT_EQ(write_run_logs(config, config.centrifuge.errors, means, default_log_step(config)).size(), 6u);
}

TEST(LogManifest, LogsInADaqLayoutReduceAsCcalsOwnDo) {
  // The bundled example's 20 g run written twice from the same mean: in ccal's layout and in the DAQ's (time
  // in ms, encoders as whole counts of 2^24 a revolution). Its instrument has no quantum: the output column
  // holds the same numbers, so the mean output is the same to the rounding of the times' ms → s (1e-12
  // relative); the encoders' rates differ by their quantisation, 2π/2^24 = 3.7e-7 rad over a 450 s line fit
  // of 4500 samples: 1e-9 rad/s.
  const Config config = bundled_example();
  const std::vector<double> means(config.plan.runs.size(), 0.5);
  const double step = default_log_step(config);
  LogLayout daq = parse_log_manifest(kDaq, "m", ".").layout;
  const auto own = write_run_logs(config, config.centrifuge.errors, means, step);
  const auto theirs = write_run_logs(config, config.centrifuge.errors, means, step, daq);
  EXPECT_EQ(theirs[3].text.substr(0, theirs[3].text.find('\n')), "t_ms,output,enc_main,enc_platform");
  RunLogOptions a, b;
  a.pulse_weight = b.pulse_weight = 1e-6;
  b.columns = daq.columns;
  b.angle_scale = daq.angle_scale;
  const double rate = 8.85;  // the 20 g run's Ω, for the encoders' spacing check
  const ReducedLog ra = reduce_run_log(parse_csv(own[3].text, "own.csv"), a, rate);
  const ReducedLog rb = reduce_run_log(parse_csv(theirs[3].text, "daq.csv"), b, rate);
  EXPECT_NEAR(rb.duration, ra.duration, 1e-12 * ra.duration);
  EXPECT_NEAR(rb.mean_output, ra.mean_output, 1e-12 * std::abs(ra.mean_output));
  ASSERT_TRUE(rb.has_theta1 && rb.has_gamma);
  EXPECT_NEAR(rb.theta1_rate, ra.theta1_rate, 1e-9);
  EXPECT_NEAR(rb.gamma_rate, ra.gamma_rate, 1e-9);
}

TEST(LogManifest, RefusalsAreLocatedWithWhatIsAccepted) {
  EXPECT_EQ(manifest_refusal("[runs]\n"),
            "logs/manifest.toml:1:1: runs: no run; accepted: run = \"file\" lines, one per run");
  EXPECT_EQ(
      manifest_refusal("[columns]\n"),
      "logs/manifest.toml:1:1: runs: missing table; accepted: run = \"file\" lines, one per logged run");
  EXPECT_EQ(
      manifest_refusal("[runs]\n5g = \"../elsewhere.csv\"\n"),
      "logs/manifest.toml:2:6: runs.5g: '../elsewhere.csv' is not a file inside the folder; accepted: a path "
      "relative to logs");
  EXPECT_EQ(
      manifest_refusal("[columns]\nangle_unit = \"counts\"\n[runs]\n1 = \"a.csv\"\n"),
      "logs/manifest.toml:2:14: columns.angle_unit: counts need the encoders' resolution; accepted: with "
      "counts_per_revolution = N (e.g. 16777216)");
  EXPECT_EQ(manifest_refusal("[columns]\ncounts_per_revolution = 4096\n[runs]\n1 = \"a.csv\"\n"),
            "logs/manifest.toml:2:25: columns.counts_per_revolution: is read only for encoders in counts; "
            "accepted: "
            "with angle_unit = \"counts\"");
  EXPECT_EQ(
      manifest_refusal("[columns]\ntime_unit = \"m\"\n[runs]\n1 = \"a.csv\"\n"),
      "logs/manifest.toml:2:13: columns.time_unit: 'm' is not a time unit; accepted: s, ms, us (or µs), min, …, "
      "or \"iso8601\" for timestamps (2026-11-30T10:15:02.125Z)");
  EXPECT_EQ(
      manifest_refusal("[columns]\ntheta1 = \"time\"\n[runs]\n1 = \"a.csv\"\n"),
      "logs/manifest.toml:2:10: columns.theta1: 'time' is also the column of columns.time (its default); "
      "accepted: a column of its own for each of time, pulses, output, theta1 and gamma");
  // Said of both keys, each given or by default: the refused key is not the one the user changed here.
  EXPECT_EQ(manifest_refusal("[columns]\ntheta1 = \"gamma\"\n[runs]\n1 = \"a.csv\"\n"),
            "logs/manifest.toml:1:1: columns.gamma: 'gamma' (its default) is also the column of columns.theta1; "
            "accepted: a column of its own for each of time, pulses, output, theta1 and gamma");
  EXPECT_EQ(manifest_refusal("[columns]\ncounter_bits = 12.5\n[runs]\n1 = \"a.csv\"\n"),
            "logs/manifest.toml:2:16: columns.counter_bits: 12.5 is not a counter's width; accepted: a whole "
            "number of bits from 8 to 52 (e.g. 16, 24, 32)");
  EXPECT_EQ(manifest_refusal("[colums]\n")
                .rfind("logs/manifest.toml:1:2: colums: unknown key; did you mean 'columns'?", 0),
            0u);
  try {
    read_log_manifest("no/such/folder");
    FAIL() << "a folder without a manifest was read";
  } catch (const ConfigError& e) {
    EXPECT_EQ(
        std::string(e.what()).rfind("no/such/folder/manifest.toml: no manifest in the folder; accepted: ", 0),
        0u)
        << e.what();
  }
}

// [instruments]: each instrument's output column, one of pulses and output, a name of its own; refused at its key.
TEST(LogManifest, InstrumentColumnsAreCheckedWhereTheyAreWritten) {
  const LogManifest m = parse_log_manifest(
      "[instruments]\nA = { pulses = \"count_a\" }\nB = { output = \"rate_b\" }\n[runs]\n1 = \"a.csv\"\n", "m", ".");
  ASSERT_EQ(m.layout.instruments.size(), 2u);
  EXPECT_EQ(m.layout.instruments[1].column, "rate_b");
  EXPECT_FALSE(m.layout.instruments[1].pulses);
  const std::string runs = "[runs]\n1 = \"a.csv\"\n";
  EXPECT_NE(manifest_refusal("[instruments]\nA = \"count_a\"\n" + runs).find("manifest.toml:2:5: instruments.A: "
                                                                            "expected the instrument's output column"),
            std::string::npos);
  EXPECT_NE(manifest_refusal("[instruments]\nA = { pulses = \"a\", output = \"b\" }\n" + runs)
                .find("instruments.A: needs exactly one of pulses"),
            std::string::npos);
  EXPECT_NE(manifest_refusal("[instruments]\nA = { pulses = \"time\" }\n" + runs)
                .find("instruments.A.pulses: 'time' is also the column of columns.time; accepted: a column of its "
                      "own for each instrument's output"),
            std::string::npos);
  EXPECT_NE(manifest_refusal("[instruments]\nA = { pulses = \"c\" }\nB = { output = \"c\" }\n" + runs)
                .find("instruments.B.output: 'c' is also the column of instruments.A.pulses;"),
            std::string::npos);
  EXPECT_NE(manifest_refusal("[instruments]\nA = { pulse = \"a\" }\n" + runs).find("did you mean 'pulses'?"),
            std::string::npos);
}

}  // namespace
}  // namespace ccal
