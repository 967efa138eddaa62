// `ccal montecarlo` keeps its distribution: --samples-out (CSV and .npy) against the reported statistics and
// histogram, bit-identical for 1 and 2 threads; the traps of issue 10: --coverage refused, the default M
// validated on the bundled example, a failed validation at a fixed M explained.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "cli_support.hpp"

namespace ccal::test {
namespace {

using SamplesCli = Cli;

// The CSV's header and its columns.
struct Columns {
  std::vector<std::string> header;
  std::vector<std::vector<double>> values;
};

Columns read_csv(const std::string& text) {
  Columns c;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);
  for (std::istringstream h(line); std::getline(h, line, ',');) c.header.push_back(line);
  c.values.resize(c.header.size());
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::string cell;
    for (std::size_t k = 0; std::getline(row, cell, ','); ++k) c.values.at(k).push_back(std::stod(cell));
  }
  return c;
}

// Mean and standard deviation (1/(M − 1)) computed here in long double, two passes.
std::pair<double, double> moments(const std::vector<double>& v) {
  long double s = 0;
  for (double x : v) s += x;
  const long double m = s / v.size();
  long double q = 0;
  for (double x : v) q += (x - m) * (x - m);
  return {double(m), double(std::sqrt(q / (v.size() - 1)))};
}

TEST_F(SamplesCli, CsvHasTheReportedMeanStdAndHistogram) {
  const Result r = run("montecarlo --trials 3000 --seed 5 --format json -o mc.json --samples-out s.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json o = nlohmann::json::parse(read(dir_ / "mc.json"));
  const Columns c = read_csv(read(dir_ / "s.csv"));
  ASSERT_EQ(c.header, (std::vector<std::string>{"K0_deg_s", "K2_deg_s_g2", "K3_deg_s_g3"}));
  for (std::size_t k = 0; k < 3; ++k) {
    const std::string id = c.header[k].substr(0, 2);
    SCOPED_TRACE(id);
    const auto& j = o.at("coefficients").at(id);
    ASSERT_EQ(c.values[k].size(), 3000u);
    const auto [mean, sd] = moments(c.values[k]);
    // The file holds the reported values (17 digits: exact); the program's compensated sums and these
    // long-double ones differ by rounding only: 1e-12 of u(y).
    EXPECT_NEAR(mean, j.at("mean").get<double>(), 1e-12 * sd);
    EXPECT_NEAR(sd, j.at("std_dev").get<double>(), 1e-12 * sd);
    // The histogram: every trial in one bin, from the smallest to the largest value of the file.
    const auto& h = j.at("histogram");
    std::uint64_t total = 0;
    for (const auto& n : h.at("counts")) total += n.get<std::uint64_t>();
    EXPECT_EQ(total, 3000u);
    EXPECT_EQ(h.at("counts").size(), 60u);
    EXPECT_EQ(h.at("lowest").get<double>(), *std::min_element(c.values[k].begin(), c.values[k].end()));
    EXPECT_EQ(h.at("highest").get<double>(), *std::max_element(c.values[k].begin(), c.values[k].end()));
    // The bin of the file's first value holds it: recount that bin from the file.
    const double low = h.at("lowest"), width = h.at("bin_width");
    const auto bin = std::min<std::size_t>(59, std::size_t((c.values[k][0] - low) / width));
    std::uint64_t in_bin = 0;
    for (double x : c.values[k])
      if (std::min<std::size_t>(59, std::size_t((x - low) / width)) == bin) ++in_bin;
    EXPECT_EQ(in_bin, h.at("counts")[bin].get<std::uint64_t>());
  }
}

TEST_F(SamplesCli, SameFileForOneAndTwoThreads) {
  ASSERT_EQ(run("montecarlo --trials 5000 --seed 9 --threads 1 -o a.txt --samples-out a.csv").code, 0);
  ASSERT_EQ(run("montecarlo --trials 5000 --seed 9 --threads 2 -o b.txt --samples-out b.csv").code, 0);
  ASSERT_EQ(run("montecarlo --trials 5000 --seed 9 --threads 2 -o c.txt --samples-out c.npy").code, 0);
  ASSERT_EQ(run("montecarlo --trials 5000 --seed 9 --threads 1 -o d.txt --samples-out d.NPY").code, 0);
  EXPECT_EQ(read(dir_ / "a.csv"), read(dir_ / "b.csv"));
  EXPECT_EQ(read(dir_ / "c.npy"), read(dir_ / "d.NPY"));
  EXPECT_GT(read(dir_ / "a.csv").size(), 5000u * 3 * 10);
}

TEST_F(SamplesCli, NpyIsNumpyFormatWithTheCsvValues) {
  ASSERT_EQ(run("montecarlo --trials 1000 -o m.txt --samples-out s.npy").code, 0);
  ASSERT_EQ(run("montecarlo --trials 1000 -o n.txt --samples-out s.csv").code, 0);
  const std::string npy = read(dir_ / "s.npy");
  // numpy.lib.format 1.0: magic, version 1.0, little-endian header length, a dict, data 64-byte aligned.
  ASSERT_GT(npy.size(), 10u);
  EXPECT_EQ(npy.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t header = std::uint8_t(npy[8]) + 256u * std::uint8_t(npy[9]);
  EXPECT_EQ((10 + header) % 64, 0u);
  const std::string dict = npy.substr(10, header);
  EXPECT_NE(dict.find("'descr': '<f8'"), std::string::npos) << dict;
  EXPECT_NE(dict.find("'fortran_order': False"), std::string::npos) << dict;
  EXPECT_NE(dict.find("'shape': (1000, 3)"), std::string::npos) << dict;
  EXPECT_EQ(dict.back(), '\n');
  ASSERT_EQ(npy.size(), 10 + header + 1000 * 3 * 8);
  const Columns c = read_csv(read(dir_ / "s.csv"));
  for (std::size_t i = 0; i < 1000; ++i)
    for (std::size_t k = 0; k < 3; ++k) {
      double x;
      std::memcpy(&x, npy.data() + 10 + header + 8 * (3 * i + k), 8);  // C order, row i = trial i
      ASSERT_EQ(x, c.values[k][i]) << i << "," << k;
    }
}

TEST_F(SamplesCli, CoverageIsRefusedNamingTheNewOption) {
  // Before: `--coverage 0.95` was a probability here and a factor in budget (a trap); now refused.
  expect_bad_input(run("montecarlo --trials 100 --coverage 0.95"), {"--coverage-probability"});
  const Result r = run("montecarlo --trials 200 --coverage-probability 0.9 --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out).at("coverage_probability"), 0.9);
}

TEST_F(SamplesCli, TheDefaultMDecidesTheValidation) {
  // Before: M = 10⁴ by default, where the paper's set-up failed its validation of K3 by sampling noise alone
  // (at 10⁵ it passes). At the default 10⁶ the sampling error of the interval ends is a small part of δ, so
  // the verdict is about the LPU, not about M: every coefficient is validated, or fails by more than 3
  // standard errors. The bundled example fails that way (its rate ripples are arcsine-distributed and
  // dominate: the 95 % interval is about 1.84 u wide each side, not 1.96 u), so the paper's set-up is the
  // one that validates.
  for (const std::string& config : {kPaperExample, kExample}) {
    SCOPED_TRACE(config);
    const Result r = run("montecarlo " + config + " --format json");
    ASSERT_EQ(r.code, 0) << r.err;
    const nlohmann::json o = nlohmann::json::parse(r.out);
    EXPECT_EQ(o.at("trials"), 1000000);
    for (const auto& [id, c] : o.at("coefficients").items()) {
      SCOPED_TRACE(id);
      const auto& lpu = c.at("lpu");
      // The interval ends' sampling error at 10⁶ trials: about 2.7 u/√M = 0.0027 u for a normal output.
      EXPECT_LT(lpu.at("interval_end_std_error").get<double>(), 0.005 * c.at("std_dev").get<double>());
      EXPECT_FALSE(lpu.at("explained_by_sampling").get<bool>()) << c.dump();
      if (config == kPaperExample) {
        EXPECT_TRUE(lpu.at("validated").get<bool>()) << c.dump();
      }
    }
  }
}

TEST_F(SamplesCli, AFailedValidationAtFixedMSaysWhetherSamplingExplainsIt) {
  // The old default: at M = 10⁴ the paper's set-up misses δ on K3 by sampling noise (validated at 10⁵). The
  // text says so and what to run; the JSON has the same judgement.
  const Result t = run("montecarlo " + kPaperExample + " --trials 10000");
  ASSERT_EQ(t.code, 0) << t.err;
  const Result j = run("montecarlo " + kPaperExample + " --trials 10000 --format json");
  const nlohmann::json o = nlohmann::json::parse(j.out);
  int failed = 0;
  for (const auto& [id, c] : o.at("coefficients").items()) {
    const auto& lpu = c.at("lpu");
    if (lpu.at("validated").get<bool>()) continue;
    ++failed;
    SCOPED_TRACE(id);
    const double excess = std::max(lpu.at("d_low").get<double>(), lpu.at("d_high").get<double>()) -
                          lpu.at("delta").get<double>();
    const double se = lpu.at("interval_end_std_error").get<double>();
    // About 2.7 u/√M = 0.027 u at M = 10⁴ for a normal output (arcsine-heavy outputs have less): 0.01–0.05 u.
    EXPECT_GT(se, 0.01 * c.at("std_dev").get<double>());
    EXPECT_LT(se, 0.05 * c.at("std_dev").get<double>());
    EXPECT_EQ(lpu.at("explained_by_sampling").get<bool>(), excess <= 3 * se);
    EXPECT_NE(t.out.find(id + ": not validated"), std::string::npos) << t.out;
    if (excess <= 3 * se) {
      EXPECT_NE(t.out.find("sampling error explains it; run `ccal montecarlo --digits 2`"),
                std::string::npos);
      // M' = M (3 se/δ)², rounded up to 2 digits.
      const double needed = 10000 * std::pow(3 * se / lpu.at("delta").get<double>(), 2);
      EXPECT_GE(lpu.at("trials_needed").get<double>(), needed);
      EXPECT_LE(lpu.at("trials_needed").get<double>(), needed * 1.11);
    }
  }
  EXPECT_GE(failed, 1) << "the paper's set-up at M = 10⁴ no longer fails; pick a case that does";
}

}  // namespace
}  // namespace ccal::test
