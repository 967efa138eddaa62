#include "ccal/render/montecarlo_samples.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstdint>
#include <cstring>

#include "budget_parts.hpp"
#include "ccal/core/errors.hpp"

namespace ccal::render {
namespace {

bool write_csv(const Eigen::MatrixXd& samples, const BudgetDetail& b, const ChunkSink& sink) {
  std::string block;
  for (std::size_t k = 0; k < b.coefficients.size(); ++k) {
    if (k > 0) block += ',';
    block += budget_parts::csv_column(b.coefficients[k], b.units[k]);
  }
  block += '\n';
  for (Eigen::Index i = 0; i < samples.rows(); ++i) {
    for (Eigen::Index k = 0; k < samples.cols(); ++k)
      fmt::format_to(std::back_inserter(block), "{}{:.17g}", k ? "," : "",
                     samples(i, k) * b.display_scale[std::size_t(k)]);
    block += '\n';
    if ((std::size_t(i) + 1) % kSampleBlockRows == 0) {
      if (!sink(block)) return false;
      block.clear();
    }
  }
  return block.empty() || sink(block);
}

// NPY format 1.0: magic, version, a little-endian uint16 header length, then the header (a Python dict
// literal) padded with spaces and ended by a newline so that the data start at a multiple of 64 bytes.
std::string npy_header(Eigen::Index rows, Eigen::Index cols) {
  std::string dict =
      fmt::format("{{'descr': '<f8', 'fortran_order': False, 'shape': ({}, {}), }}", rows, cols);
  const std::size_t preamble = 10;  // magic (6), version (2), header length (2)
  const std::size_t total = (preamble + dict.size() + 1 + 63) / 64 * 64;
  dict.append(total - preamble - dict.size() - 1, ' ');
  dict += '\n';
  const auto length = std::uint16_t(dict.size());
  std::string header = "\x93NUMPY";
  header += char(1);
  header += char(0);
  header += char(length & 0xff);
  header += char(length >> 8);
  return header + dict;
}

void append_little_endian(std::string& out, double x) {
  auto bits = std::bit_cast<std::uint64_t>(x);
  for (int k = 0; k < 8; ++k, bits >>= 8) out += char(bits & 0xff);
}

bool write_npy(const Eigen::MatrixXd& samples, const BudgetDetail& b, const ChunkSink& sink) {
  if (!sink(npy_header(samples.rows(), samples.cols()))) return false;
  std::string block;
  for (Eigen::Index i = 0; i < samples.rows(); ++i) {
    for (Eigen::Index k = 0; k < samples.cols(); ++k)
      append_little_endian(block, samples(i, k) * b.display_scale[std::size_t(k)]);
    if ((std::size_t(i) + 1) % kSampleBlockRows == 0) {
      if (!sink(block)) return false;
      block.clear();
    }
  }
  return block.empty() || sink(block);
}

}  // namespace

SampleFileFormat sample_file_format(std::string_view path) {
  if (path.size() < 4) return SampleFileFormat::csv;
  std::string ext(path.substr(path.size() - 4));
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".npy" ? SampleFileFormat::npy : SampleFileFormat::csv;
}

bool write_samples(const verbs::MonteCarloResult& r, SampleFileFormat format, const ChunkSink& sink) {
  const Eigen::MatrixXd& samples = r.monte_carlo.samples;
  if (samples.rows() == 0 || std::size_t(samples.cols()) != r.budget.coefficients.size())
    throw InputError("the Monte Carlo run kept no samples (verbs::MonteCarloOptions::keep_samples)");
  return format == SampleFileFormat::npy ? write_npy(samples, r.budget, sink)
                                         : write_csv(samples, r.budget, sink);
}

}  // namespace ccal::render
