// The streamed reduction of a log file against the reduction of the same log as a CsvTable in memory: the
// same bits (one accumulator for both), the same refusals in the same places, also when a log has several
// problems; and the one-pass line fit against the centred two-pass fit it replaced, written out here.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "ccal/io/csv_stream.hpp"
#include "ccal/intake/run_log.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

namespace fs = std::filesystem;
using ccal::test::kPi;

double wrap(double a) { return std::fmod(std::fmod(a, 2 * kPi) + 2 * kPi, 2 * kPi); }

fs::path temp_file(const std::string& name, const std::string& text) {
  const fs::path p = fs::temp_directory_path() / fmt::format("ccal_stream_{}_{}", ::getpid(), name);
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

// A 2 kHz log of 450 s (~60 MB: many 4 MiB blocks, lines across their ends) with a sampled output, a rippled
// main axis and a counter-rotating platform, CRLF line ends and a byte-order mark as a spreadsheet writes.
std::string big_log() {
  std::string text = "\xEF\xBB\xBF# logged run\r\ntime, output ,theta1,gamma,temperature\r\n";
  const double rate = 9.9;
  for (int k = 0; k <= 900000; ++k) {
    const double t = 5e-4 * k, th = 0.2 + rate * t;
    fmt::format_to(std::back_inserter(text), "{:.4f},{:.9g},{:.10f},{:.10f},21.5\r\n", t,
                   3 + 0.2 * std::cos(th) + 1e-3 * std::sin(7 * t), wrap(th + 1e-5 * std::sin(th)),
                   wrap(1.0 - rate * t + 2e-6 * std::cos(1.0 - rate * t)));
  }
  return text;
}

void expect_same_bits(const ReducedLog& a, const ReducedLog& b) {
  EXPECT_EQ(a.samples, b.samples);
  for (auto [x, y] : {std::pair{a.duration, b.duration},
                      {a.mean_output, b.mean_output},
                      {a.theta1_rate, b.theta1_rate},
                      {a.theta1_start, b.theta1_start},
                      {a.theta1_rms, b.theta1_rms},
                      {a.gamma_rate, b.gamma_rate},
                      {a.gamma_start, b.gamma_start},
                      {a.gamma_end, b.gamma_end},
                      {a.gamma_rms, b.gamma_rms},
                      {a.theta1_harmonic_sigma, b.theta1_harmonic_sigma}})
    EXPECT_EQ(x, y);  // bit for bit: the same accumulation in the same order
  EXPECT_EQ(a.theta1_harmonics, b.theta1_harmonics);
  EXPECT_EQ(a.gamma_harmonics, b.gamma_harmonics);
}

TEST(RunLogStream, FileAndTableGiveTheSameBits) {
  const std::string text = big_log();
  const fs::path path = temp_file("big.csv", text);
  RunLogOptions o;
  o.harmonic_order = 2;
  const ReducedLog streamed = reduce_run_log_file(path, o, 9.9);
  const ReducedLog table = reduce_run_log(parse_csv(text, path.string()), o, 9.9);
  fs::remove(path);
  expect_same_bits(streamed, table);
  EXPECT_EQ(streamed.samples, 900001u);
  ASSERT_EQ(streamed.theta1_harmonics.size(), 4u);
  // 10 ppm of angle ripple in sine phase at harmonic 1 (c1 = 10 ppm): to the 1e-10 rad of 10-decimal angles.
  EXPECT_NEAR(ripple_from_angle_harmonics(streamed.theta1_harmonics)[0], 1e-5, 1e-9);
}

// The one-pass fit against the centred two-pass least-squares line of the old reduction, on a log of wrapped
// 17-digit readings of θ1 = 0.3 + 8.8 t + 1e-7 sin 3t (a wobble to leave a residual), 4501 samples over 450
// s, unwrapped as before. Reference: the same centred fit in long double (64-bit mantissa). The old fit in
// double rounds its centred sums of ±2000 rad (~√n·ε relative: 4e-14 rad/s, 7e-12 rad here); the one-pass
// sums are of the angle less a reference line, ~1e-7 rad, and keep their digits: the new fit is exact to
// 1e-15.
TEST(RunLogStream, LineFitIsExactToRoundOff) {
  const int n = 4501;
  std::vector<double> t(n), a(n);
  std::string text = "time,pulses,theta1\n";
  for (int k = 0; k < n; ++k) {
    t[k] = 2 + 0.1 * k;
    const std::string reading =
        fmt::format("{:.17g}", wrap(0.3 + 8.8 * (t[k] - 2) + 1e-7 * std::sin(3 * t[k])));
    text += fmt::format("{:.17g},{},{}\n", t[k], k, reading);
    a[k] = std::stod(reading);  // the old unwrapping: each step from the previous unwrapped angle, in (−π, π]
    if (k > 0) {
      double step = std::remainder(a[k] - a[k - 1], 2 * kPi);
      if (step == -kPi) step = kPi;
      a[k] = a[k - 1] + step;
    }
  }
  long double tm = 0, am = 0, stt = 0, sta = 0, rss = 0;
  for (int k = 0; k < n; ++k) tm += t[k], am += a[k];
  tm /= n;
  am /= n;
  for (int k = 0; k < n; ++k) stt += (t[k] - tm) * (t[k] - tm), sta += (t[k] - tm) * (a[k] - am);
  const long double slope = sta / stt, start = am + slope * (t[0] - tm);
  for (int k = 0; k < n; ++k) rss += (a[k] - am - slope * (t[k] - tm)) * (a[k] - am - slope * (t[k] - tm));
  RunLogOptions o;
  o.pulse_weight = 1;
  const ReducedLog r = reduce_run_log(parse_csv(text, "line.csv"), o, 8.8);
  EXPECT_NEAR(r.theta1_rate, double(slope), 1e-14);   // measured: 3e-16
  EXPECT_NEAR(r.theta1_start, double(start), 1e-13);  // measured: 2e-15
  // the RMS of the 7e-8 rad wobble from Σd² − βᵀXᵀd, with d ~ 1e-7 rad: to 1e-6 of itself
  EXPECT_NEAR(r.theta1_rms, double(std::sqrt(rss / n)), 1e-6 * double(std::sqrt(rss / n)));
}

TEST(RunLogStream, PlainDecimalsReadAsStdFromCharsReadsThem) {
  // A million decimals of every length a logger writes (1 to 17 significant digits, 0 to 24 decimals,
  // integers, signs): the fast path gives std::from_chars' double to the bit, or declines.
  std::uint64_t state = 12345;
  auto next = [&] { return state = state * 6364136223846793005ull + 1442695040888963407ull; };
  int fast = 0;
  for (int k = 0; k < 1000000; ++k) {
    const double v = (double(next() >> 11) / double(1ull << 53) - 0.3) * std::pow(10.0, int(next() % 12) - 4);
    std::string cell = k % 3 == 0 ? fmt::format("{:.{}g}", v, 1 + int(next() % 17))
                                  : fmt::format("{:.{}f}", v, int(next() % 25));
    if (k % 11 == 0) cell = fmt::format("{}", std::llround(v * 1e3));
    double expected = 0, got = 0;
    std::from_chars(cell.data(), cell.data() + cell.size(), expected);
    if (!parse_plain_decimal(cell, got)) continue;
    ++fast;
    ASSERT_EQ(std::bit_cast<std::uint64_t>(got), std::bit_cast<std::uint64_t>(expected)) << cell;
  }
  EXPECT_GT(fast, 500000);  // most take the fast path
  double v = 0;
  for (const char* declined :
       {"1e5", "+1", " 1", "1.", ".5", "-", "", "1.2.3", "12345678901234567890", "nan",
        // 2^64 + 1 and 2^64 + 2^53 − 1 wrap to 1 and 2^53 − 1 in 64 bits: declined, not read as 1 or 2^53 − 1
        "18446744073709551617", "-18455751272964292607"})
    EXPECT_FALSE(parse_plain_decimal(declined, v)) << declined;
}

// scan_plain_decimal reads a row's cells in place: it stops at the character after each decimal (a comma,
// the end) and, when it declines, leaves the cursor and the value as they were.
TEST(RunLogStream, ScanStopsAfterEachDecimalAndDeclinesUntouched) {
  const std::string row = "12.5,-3,0.000125,7";
  const char* p = row.data();
  const char* const end = p + row.size();
  std::vector<double> values;
  while (true) {
    double v = 0;
    ASSERT_TRUE(scan_plain_decimal(p, end, v)) << std::string(p, end);
    values.push_back(v);
    if (p == end) break;
    ASSERT_EQ(*p, ',');
    ++p;
  }
  EXPECT_EQ(values, (std::vector<double>{12.5, -3, 0.000125, 7}));
  for (const std::string declined : {",1", "-,", "1.,", ".5,", "12345678901234567890,"}) {
    const char* q = declined.data();
    double v = 42;
    EXPECT_FALSE(scan_plain_decimal(q, q + declined.size(), v)) << declined;
    EXPECT_EQ(q, declined.data()) << declined;
    EXPECT_EQ(v, 42) << declined;
  }
  // A decimal followed by anything else is read up to it (the caller decides what may follow).
  const std::string exponent = "1.5e3";
  const char* q = exponent.data();
  double v = 0;
  EXPECT_TRUE(scan_plain_decimal(q, q + exponent.size(), v));
  EXPECT_EQ(v, 1.5);
  EXPECT_EQ(*q, 'e');
}

// The message of reducing `text` from a file and from a table (the same, or the test fails).
std::string log_refusal(const std::string& text) {
  const fs::path path = temp_file("bad.csv", text);
  RunLogOptions o;
  o.pulse_weight = 1e-5;
  std::string streamed, table;
  try {
    reduce_run_log_file(path, o, 8.8);
  } catch (const CsvError& e) {
    streamed = e.what();
  }
  try {
    reduce_run_log(parse_csv(text, path.string()), o, 8.8);
  } catch (const CsvError& e) {
    table = e.what();
  }
  fs::remove(path);
  EXPECT_EQ(streamed, table) << text;
  return streamed.substr(streamed.rfind('/') + 1);
}

TEST(RunLogStream, ProblemsAreReportedInTheOrderOfTheWholeTableReduction) {
  // Each log has two problems; the one the whole-table reduction reported first wins: a CSV problem before
  // any reduction, the time column before the output, the output before the encoders, an encoder's cells
  // before its sample spacing.
  EXPECT_NE(log_refusal("time,pulses\n0,1\n0,x\n1,2,3\n").find(":4:3"), std::string::npos);  // ragged
  EXPECT_NE(log_refusal("time,pulses\n0,x\n1,2\nbad,3\n").find(":4:1: time"),
            std::string::npos);                                                                  // time cell
  EXPECT_NE(log_refusal("time,pulses\n0,x\n2,2\n1,3\n").find(":4:1: time"), std::string::npos);  // order
  EXPECT_NE(log_refusal("time,pulses,theta1\n0,1,y\n1,z,0\n").find(":3:2: pulses"), std::string::npos);
  EXPECT_NE(log_refusal("time,count,theta1\n0,1,y\n1,2,0\n").find("no output column"), std::string::npos);
  // 1 s apart at 8.8 rad/s is too far for the unwrapping, but the bad cell further down is reported first
  EXPECT_NE(log_refusal("time,pulses,theta1\n0,1,0\n1,2,0\n1.1,3,x\n").find(":4:3: theta1"),
            std::string::npos);
  EXPECT_NE(log_refusal("time,pulses,theta1\n0,1,0\n1,2,0\n1.1,3,0\n").find(":3:3: theta1"),
            std::string::npos);
  EXPECT_NE(log_refusal("temperature\n1\n").find("no such column"), std::string::npos);
  EXPECT_NE(log_refusal("# only a comment\n").find("no header"), std::string::npos);
  // A file of less than three bytes (too short to tell a byte-order mark) is split into its lines too: the
  // header "x" is on line 2 (found by fuzz_run_log).
  EXPECT_NE(log_refusal("\nx").find(":2: time: no such column"), std::string::npos);
  EXPECT_NE(log_refusal("time,pulses\n0,1\n").find("at least two"), std::string::npos);
  // quoted fields go through parse_csv's splitter: a quoted number is a number, an open quote a CSV error
  EXPECT_NE(log_refusal("time,pulses\n\"0\",1\n1,\"x\"\n2,\"3\n").find(":4:2"), std::string::npos);
  EXPECT_NE(log_refusal("time,pulses\n\"0\",1\n1,\"x\"\n").find(":3:2: pulses: 'x' is not a number"),
            std::string::npos);
}

}  // namespace
}  // namespace ccal::test
