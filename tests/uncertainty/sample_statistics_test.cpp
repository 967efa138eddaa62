// The Monte Carlo's order statistics (src/uncertainty/sample_statistics.cpp): sort_tails leaves the tails a
// full sort leaves, whichever way it finds them (the thresholds from a subsample, or nth_element when a
// threshold holds too few values), for samples with ties, a constant one, and one whose subsample misleads.
#include "../src/uncertainty/sample_statistics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

namespace ccal {
namespace sample_statistics_test {

// The tails of `v` after sort_tails equal those of a full sort, value for value, and nothing is lost.
void expect_tails_of_a_full_sort(std::vector<double> v, std::uint64_t q, const std::string& label) {
  std::vector<double> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  sample_stats::sort_tails(v, q);
  const std::size_t M = v.size(), tail = M - q;
  for (std::size_t i = 0; i < tail; ++i) {
    ASSERT_EQ(v[i], sorted[i]) << label << ", low tail at " << i;
    ASSERT_EQ(v[M - 1 - i], sorted[M - 1 - i]) << label << ", high tail at " << M - 1 - i;
  }
  std::sort(v.begin(), v.end());
  EXPECT_EQ(v, sorted) << label << ": the same values";
}

TEST(SortTails, TheTailsOfAFullSortForEverySizeAndCoverage) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal;
  for (const std::size_t M : {std::size_t(10), std::size_t(999), std::size_t(16383), std::size_t(16384),
                              std::size_t(100000), std::size_t(1000003)})
    for (const double p : {0.5, 0.9, 0.95, 0.99, 0.9999}) {
      std::vector<double> v(M);
      for (double& x : v) x = normal(rng);
      const auto q = std::min<std::uint64_t>(sample_stats::rounded_points(M, p), M - 1);
      expect_tails_of_a_full_sort(v, q, "M " + std::to_string(M) + ", p " + std::to_string(p));
    }
}

TEST(SortTails, TiesAndAConstantSample) {
  std::mt19937_64 rng(6);
  std::uniform_int_distribution<int> few(0, 20);
  std::vector<double> ties(200000);
  for (double& x : ties) x = 0.25 * few(rng);  // 21 values, thresholds fall on ties
  expect_tails_of_a_full_sort(ties, 190000, "ties");
  expect_tails_of_a_full_sort(std::vector<double>(200000, 1.5), 190000, "constant");
}

TEST(SortTails, ASubsampleThatMisleadsFallsBackToTheExactSelection) {
  // Every value the strided subsample reads (i a multiple of M/4096) is far below the rest: the low threshold
  // then has about 300 values below it, fewer than the tail of 10000, and the exact selection runs.
  const std::size_t M = 200000, stride = M / 4096;
  std::vector<double> v(M);
  for (std::size_t i = 0; i < M; ++i) v[i] = i % stride == 0 ? -1000.0 - double(i) : double(i % 977);
  expect_tails_of_a_full_sort(v, 190000, "misleading subsample, low");
  for (double& x : v) x = -x;
  expect_tails_of_a_full_sort(v, 190000, "misleading subsample, high");
}

}  // namespace sample_statistics_test
}  // namespace ccal
