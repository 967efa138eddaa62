// The covariance between the coefficients of two instruments calibrated in one test (examples/two_instruments.toml):
// its diagonal blocks are each instrument's own budget, its cross blocks come from the machine's errors alone,
// and the Monte Carlo that draws the shared errors once agrees with the LPU.
#include <gtest/gtest.h>

#include <cmath>

#include "ccal/io/config_file.hpp"
#include "ccal/setup/measuring_chain.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/verbs/instrument_covariance.hpp"
#include "test_paths.hpp"

namespace ccal::verbs {
namespace {

const Config& two_instruments() {
  static const Config c = load_config(CCAL_SOURCE_DIR + "/examples/two_instruments.toml");
  return c;
}

TEST(InstrumentCovariance, EachInstrumentsOwnInputsAreItsMountingFixedTermsAndOutput) {
  for (const int own : {int(ch::dx5), int(ch::dy5), int(ch::dthx5), int(ch::dthy5), int(ch::dthz5),
                        chain_parameter({ChainKind::fixed_term, 1}), chain_parameter({ChainKind::output_gain, 0})})
    EXPECT_TRUE(instrument_own_input(own)) << own;
  for (const int shared : {int(ch::dthx4), int(ch::dR_s), int(ch::domega), chain_parameter({ChainKind::gravity, 0}),
                           chain_parameter({ChainKind::time_base, 0}), chain_parameter({ChainKind::encoder, 0})})
    EXPECT_FALSE(instrument_own_input(shared)) << shared;
}

// The diagonal block of an instrument is its budget's tolerance part G Gᵀ in the statement's units, to round-off
// (1e-12 of the largest variance: two sums of the same products in another order).
TEST(InstrumentCovariance, TheDiagonalBlocksAreEachInstrumentsBudget) {
  const Config& c = two_instruments();
  const InstrumentCovariance cov = instrument_covariance(c.instruments, ModelMode::exact, 0, 1, 0);
  ASSERT_EQ(cov.instruments, (std::vector<std::string>{"A", "B"}));
  ASSERT_EQ(cov.names.size(), 6u);
  EXPECT_EQ(cov.names[3], "B K0");
  EXPECT_EQ(cov.units[2], "deg/s/g^3");
  for (std::size_t a = 0; a < 2; ++a) {
    ccal::BudgetOptions bo;
    bo.compare_with_paper = false;
    const ccal::BudgetDetail b = ccal::compute_budget(c.instruments[a], bo);
    const Eigen::MatrixXd g = independent_effects(b);
    Eigen::VectorXd scale(3);
    for (int k = 0; k < 3; ++k) scale[k] = b.display_scale[std::size_t(k)];
    const Eigen::MatrixXd expected = scale.asDiagonal() * g * g.transpose() * scale.asDiagonal();
    const Eigen::MatrixXd block = cov.lpu.block(cov.first_row[a], cov.first_row[a], 3, 3);
    EXPECT_LE((block - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.diagonal().maxCoeff()) << "instrument " << a;
  }
}

// The two instruments share the machine: their K2 and K3 are correlated (B's IA along A's PA, so the same errors
// act on them through other paths), and the Monte Carlo, the shared errors drawn once, gives the LPU's cross
// covariance. 4000 trials: the sampling error of a covariance is about √((1 + ρ²)/M) σ_a σ_b ≤ 0.023 σ_a σ_b; the
// tolerance 0.1 σ_a σ_b is four of them plus the model's non-linearity over the tolerances (below 1e-3, §10.2).
TEST(InstrumentCovariance, TheMonteCarloOfSharedDrawsAgreesWithTheLpu) {
  const Config& c = two_instruments();
  const InstrumentCovariance cov = instrument_covariance(c.instruments, ModelMode::exact, 4000, 7, 0);
  ASSERT_EQ(cov.monte_carlo.rows(), 6);
  EXPECT_EQ(cov.trials, 4000u);
  double largest_correlation = 0;
  for (Eigen::Index i = 0; i < 6; ++i)
    for (Eigen::Index j = 0; j < 6; ++j) {
      const double scale = std::sqrt(cov.lpu(i, i) * cov.lpu(j, j));
      EXPECT_NEAR(cov.monte_carlo(i, j), cov.lpu(i, j), 0.1 * scale) << cov.names[std::size_t(i)] << " × "
                                                                     << cov.names[std::size_t(j)];
      if (i < 3 && j >= 3) largest_correlation = std::max(largest_correlation, std::abs(cov.lpu(i, j)) / scale);
    }
  EXPECT_GT(largest_correlation, 0.2);  // a correlation worth stating
  EXPECT_LT(largest_correlation, 1.0);  // each has errors of its own
}

// Each instrument's mounting is its own: with its azimuth and tilt tolerances 300 times the lab's (dominant), the
// Monte Carlo draws them apart for each instrument, and the LPU's cross blocks leave them out. Were they shared,
// the cross blocks would hold them (the mask in instrument_covariance), which the Monte Carlo refutes. Tolerance
// as above.
TEST(InstrumentCovariance, EachInstrumentsMountingErrorsAreItsOwn) {
  std::vector<Config> each = two_instruments().instruments;
  for (Config& c : each)
    for (Tolerance& t : c.tolerances)
      if (t.id == "dthz5" || t.id == "dthy5" || t.id == "dthx5") t.bound *= 300;
  const InstrumentCovariance cov = instrument_covariance(each, ModelMode::exact, 4000, 3, 0);
  for (Eigen::Index i = 0; i < 6; ++i)
    for (Eigen::Index j = 0; j < 6; ++j)
      EXPECT_NEAR(cov.monte_carlo(i, j), cov.lpu(i, j), 0.1 * std::sqrt(cov.lpu(i, i) * cov.lpu(j, j)))
          << cov.names[std::size_t(i)] << " × " << cov.names[std::size_t(j)];
}

}  // namespace
}  // namespace ccal::verbs
