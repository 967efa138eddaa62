// `ccal montecarlo --samples-out` as written (render/montecarlo_samples.hpp), in-process on a kept run of the
// bundled example: the format by the extension, the CSV's header and 17-digit values in the display units, the
// NPY's header and little-endian float64 values equal to the CSV's, the blocks handed to the sink, a failing
// sink that stops the writer, and a run that kept no samples refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/render/montecarlo_samples.hpp"
#include "ccal/verbs/montecarlo.hpp"

namespace ccal {
namespace montecarlo_samples_test {

// 5000 trials: more than one block of kSampleBlockRows rows, so the sink gets two.
const verbs::MonteCarloResult& kept_run() {
  static const verbs::MonteCarloResult r = [] {
    verbs::MonteCarloOptions o;
    o.propagation.trials = 5000;
    o.propagation.seed = 11;
    o.propagation.threads = 1;
    o.propagation.keep_samples = true;
    return verbs::monte_carlo(bundled_example(), o);
  }();
  return r;
}

// Everything the writer hands over, and how many pieces.
struct Collected {
  std::string bytes;
  int pieces = 0;
};
Collected write(const verbs::MonteCarloResult& r, render::SampleFileFormat format) {
  Collected c;
  EXPECT_TRUE(render::write_samples(r, format, [&](std::string_view piece) {
    c.bytes += piece;
    ++c.pieces;
    return true;
  }));
  return c;
}

TEST(SampleFileFormat, NpyByItsExtensionInAnyCaseElseCsv) {
  using render::SampleFileFormat;
  EXPECT_EQ(render::sample_file_format("s.npy"), SampleFileFormat::npy);
  EXPECT_EQ(render::sample_file_format("dir/S.NPY"), SampleFileFormat::npy);
  EXPECT_EQ(render::sample_file_format("s.csv"), SampleFileFormat::csv);
  EXPECT_EQ(render::sample_file_format("s.npy.txt"), SampleFileFormat::csv);
  EXPECT_EQ(render::sample_file_format("npy"), SampleFileFormat::csv);
}

TEST(SamplesCsv, AHeaderThenEveryTrialInDisplayUnitsToSeventeenDigits) {
  const verbs::MonteCarloResult& r = kept_run();
  const Collected c = write(r, render::SampleFileFormat::csv);
  std::istringstream in(c.bytes);
  std::string header;
  std::getline(in, header);
  // One column per coefficient, each named with its display unit and no spaces (K0_deg_s: deg/s, not rad/s).
  ASSERT_EQ(r.budget.coefficients.size(), 3u);
  EXPECT_EQ(header, "K0_deg_s,K2_deg_s_g2,K3_deg_s_g3");
  std::string line;
  Eigen::Index row = 0;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::string cell;
    for (Eigen::Index k = 0; std::getline(cells, cell, ','); ++k) {
      // 17 significant digits read back to the same double: exact equality.
      const double want = r.monte_carlo.samples(row, k) * r.budget.display_scale[std::size_t(k)];
      ASSERT_EQ(std::strtod(cell.c_str(), nullptr), want) << "row " << row << " column " << k;
    }
    ++row;
  }
  EXPECT_EQ(row, 5000);
  EXPECT_EQ(c.pieces, 2);  // one full block of 4096 rows (with the header), then the rest
}

TEST(SamplesNpy, NumpysHeaderThenLittleEndianDoublesEqualToTheCsvValues) {
  const verbs::MonteCarloResult& r = kept_run();
  const Collected c = write(r, render::SampleFileFormat::npy);
  ASSERT_GE(c.bytes.size(), 10u);
  EXPECT_EQ(c.bytes.substr(0, 6), "\x93NUMPY");
  EXPECT_EQ(c.bytes[6], char(1));  // version 1.0
  EXPECT_EQ(c.bytes[7], char(0));
  const auto header_length = std::size_t(std::uint8_t(c.bytes[8])) | std::size_t(std::uint8_t(c.bytes[9])) << 8;
  const std::size_t data = 10 + header_length;
  EXPECT_EQ(data % 64, 0u);  // the data aligned as numpy writes them
  const std::string dict = c.bytes.substr(10, header_length);
  EXPECT_NE(dict.find("'descr': '<f8'"), std::string::npos) << dict;
  EXPECT_NE(dict.find("'fortran_order': False"), std::string::npos) << dict;
  EXPECT_NE(dict.find("'shape': (5000, 3)"), std::string::npos) << dict;
  EXPECT_EQ(dict.back(), '\n');
  ASSERT_EQ(c.bytes.size(), data + 5000 * 3 * 8);
  for (Eigen::Index i : {Eigen::Index(0), Eigen::Index(4095), Eigen::Index(4096), Eigen::Index(4999)})
    for (Eigen::Index k = 0; k < 3; ++k) {
      std::uint64_t bits = 0;
      const std::size_t at = data + std::size_t(i * 3 + k) * 8;  // C order: row after row
      for (int b = 7; b >= 0; --b) bits = bits << 8 | std::uint8_t(c.bytes[at + std::size_t(b)]);
      EXPECT_EQ(std::bit_cast<double>(bits), r.monte_carlo.samples(i, k) * r.budget.display_scale[std::size_t(k)])
          << "row " << i << " column " << k;
    }
}

TEST(SamplesFile, AFailingSinkStopsTheWriterAndARunWithoutSamplesIsRefused) {
  const verbs::MonteCarloResult& r = kept_run();
  for (const auto format : {render::SampleFileFormat::csv, render::SampleFileFormat::npy}) {
    int calls = 0;
    EXPECT_FALSE(render::write_samples(r, format, [&](std::string_view) {
      ++calls;
      return false;
    }));
    EXPECT_EQ(calls, 1);  // nothing more after the first failed write
  }
  verbs::MonteCarloResult without = r;
  without.monte_carlo.samples.resize(0, 0);
  EXPECT_THROW(render::write_samples(without, render::SampleFileFormat::csv, [](std::string_view) { return true; }),
               InputError);
}

}  // namespace montecarlo_samples_test
}  // namespace ccal
