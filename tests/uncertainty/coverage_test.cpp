// The coverage convention (uncertainty/coverage.hpp): k from p for a normal quantity and back, Student's t at
// ν = ∞ the same k bit for bit (so a statement without Type A equals the budget's U), a stated k, and the
// words beside every U.
#include "ccal/uncertainty/coverage.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "ccal/core/errors.hpp"
#include "test_constants.hpp"

namespace ccal {
namespace {

// Φ⁻¹(0.975) and erf(√2) = 2Φ(2) − 1 to 16 digits (any table of the normal distribution); the functions
// are erf⁻¹ and erf of double precision: a few ulp.
using ccal::test::kZ975;
constexpr double kP2 = 0.9544997361036416;
constexpr double kUlps = 4e-16;

TEST(Coverage, TheDefaultProbabilitysTextIsTheConstant) {
  // Messages show the default as text (an example of the accepted values); it must read back as the constant.
  EXPECT_EQ(std::stod(std::string(kDefaultCoverageProbabilityText)), kDefaultCoverageProbability);
}

TEST(Coverage, NormalFactorAndProbabilityAreInverse) {
  EXPECT_NEAR(normal_coverage_factor(0.95), kZ975, kUlps * kZ975);
  EXPECT_EQ(kDefaultCoverageFactor, normal_coverage_factor(kDefaultCoverageProbability));
  EXPECT_NEAR(normal_coverage_probability(2.0), kP2, kUlps);
  EXPECT_NEAR(normal_coverage_probability(kZ975), 0.95, kUlps);
  for (double p : {0.5, 0.6827, 0.9, 0.99, 0.9973})
    EXPECT_NEAR(normal_coverage_probability(normal_coverage_factor(p)), p, 2e-15) << p;
  EXPECT_THROW(normal_coverage_factor(1.0), InputError);
  EXPECT_THROW(normal_coverage_factor(0.0), InputError);
  EXPECT_THROW(normal_coverage_probability(0.0), InputError);
  EXPECT_THROW(normal_coverage_probability(std::nan("")), InputError);
}

TEST(Coverage, StudentAtInfiniteDegreesIsTheNormalFactorExactly) {
  // One function for the normal k: a statement with no Type A part gives the budget's U to the last bit.
  for (double p : {0.9, 0.95, 0.99}) EXPECT_EQ(student_coverage_factor(p, INFINITY), normal_coverage_factor(p));
  EXPECT_NEAR(student_coverage_factor(0.95, 10), 2.228138851986274, 1e-14);  // t_0.975(10), to 16 digits
  EXPECT_THROW(student_coverage_factor(0.95, 0.5), std::invalid_argument);
}

TEST(Coverage, AStatedFactorCarriesItsNormalProbability) {
  const Coverage from_p = normal_coverage(0.95);
  EXPECT_EQ(from_p.method, CoverageMethod::normal);
  EXPECT_EQ(from_p.probability, 0.95);
  EXPECT_EQ(from_p.factor, normal_coverage_factor(0.95));
  const Coverage stated = normal_coverage(0.95, 2.0);  // the stated k wins over p
  EXPECT_EQ(stated.method, CoverageMethod::stated);
  EXPECT_EQ(stated.factor, 2.0);
  EXPECT_NEAR(stated.probability, kP2, kUlps);
}

TEST(Coverage, EveryUIsWordedWithItsKAndP) {
  EXPECT_EQ(coverage_text(normal_coverage(0.95)), "k = 1.96, p = 95 %");
  EXPECT_EQ(coverage_text(normal_coverage(0.99)), "k = 2.58, p = 99 %");
  EXPECT_EQ(coverage_text(normal_coverage(0.95, 2.0)), "k = 2 (stated), p = 95.45 % for a normal quantity");
  EXPECT_EQ(coverage_text({0.95, 2.228138851986274, CoverageMethod::student_t}), "k = 2.23 (Student t), p = 95 %");
  EXPECT_EQ(coverage_method_name(CoverageMethod::monte_carlo), "Monte Carlo");
}

}  // namespace
}  // namespace ccal
