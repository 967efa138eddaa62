// What calibrations on one set-up share (uncertainty/history_shared.hpp): Cov(x_i, x_j) = Σ e_i R e_j over
// the inputs both charged at their tolerance, against hand sums; nothing across set-ups, measured inputs or
// unknown parts.
#include "ccal/uncertainty/history_shared.hpp"

#include <gtest/gtest.h>

namespace ccal {
namespace {

// Three inputs: a and b in group "arm", c correlated with a at ρ = 0.5 ([[correlations]]).
SharedPart machine(double scale, bool c_measured = false, const std::string& setup = "s1") {
  SharedPart p;
  p.setup_sha256 = setup;
  p.inputs = {{"a", false, "arm", {{"K0", 1e-3 * scale}, {"K2", 2e-5}}},
              {"b", false, "arm", {{"K0", -4e-4 * scale}}},
              {"c", c_measured, "", {{"K0", 3e-4 * scale}}}};
  if (!c_measured) p.correlations = {{"a", "c", 0.5}};
  return p;
}

TEST(HistoryShared, TheInputsCorrelationWithinOneCalibration) {
  const SharedPart p = machine(1);
  EXPECT_EQ(input_correlation(p, "a", "a"), 1.0);
  EXPECT_EQ(input_correlation(p, "a", "b"), 1.0);  // one group
  EXPECT_EQ(input_correlation(p, "c", "a"), 0.5);  // either order
  EXPECT_EQ(input_correlation(p, "b", "c"), 0.0);
}

TEST(HistoryShared, TheCovarianceOfTwoCalibrationsByHand) {
  // e_i = (1, −0.4, 0.3)e-3, e_j = 2 e_i (its effects twice as large); R = [[1, 1, 0.5], [1, 1, 0], [0.5, 0,
  // 1]]: e_iᵀ R e_j = 2 e_iᵀ R e_i = 2 (1 + 0.16 + 0.09 − 2·0.4 + 2·0.5·0.3) 1e-6 = 2 · 0.75e-6 = 1.5e-6
  // (exact to round-off of nine products: 1e-18).
  const std::optional<SharedPart> i = machine(1), j = machine(2);
  EXPECT_NEAR(shared_covariance(i, j, "K0"), 1.5e-6, 1e-18);
  EXPECT_NEAR(shared_covariance(j, i, "K0"), 1.5e-6, 1e-18);
  // K2: only a has an effect, 2e-5 in both: 4e-10.
  EXPECT_NEAR(shared_covariance(i, j, "K2"), 4e-10, 1e-22);
  EXPECT_EQ(shared_covariance(i, j, "K3"), 0.0);
  const Eigen::MatrixXd c = shared_covariance_matrix({&i, &j}, "K0");
  EXPECT_NEAR(c(0, 0), 0.75e-6, 1e-18);
  EXPECT_NEAR(c(1, 1), 3e-6, 1e-18);
  EXPECT_NEAR(c(0, 1), 1.5e-6, 1e-18);
}

TEST(HistoryShared, NothingSharedAcrossSetUpsMeasuredInputsOrUnknownParts) {
  const std::optional<SharedPart> i = machine(1), other = machine(1, false, "s2"), unknown;
  EXPECT_EQ(shared_covariance(i, other, "K0"), 0.0);
  EXPECT_EQ(shared_covariance(i, unknown, "K0"), 0.0);
  EXPECT_EQ(shared_covariance(unknown, unknown, "K0"), 0.0);
  // c measured in j: a and b remain, (1 + 0.16 − 0.8)e-6 = 0.36e-6.
  const std::optional<SharedPart> measured = machine(1, true);
  EXPECT_NEAR(shared_covariance(i, measured, "K0"), 0.36e-6, 1e-18);
  // An empty fingerprint names no set-up.
  const std::optional<SharedPart> blank = machine(1, false, "");
  EXPECT_EQ(shared_covariance(blank, blank, "K0"), 0.0);
}

TEST(HistoryShared, ACorrelationBothDoNotStateIsNotCounted) {
  // j without the a–c pair: only the pairs both state, (1 + 0.16 + 0.09 − 0.8)e-6 = 0.45e-6.
  const std::optional<SharedPart> i = machine(1);
  std::optional<SharedPart> j = machine(1);
  j->correlations.clear();
  EXPECT_NEAR(shared_covariance(i, j, "K0"), 0.45e-6, 1e-18);
}

}  // namespace
}  // namespace ccal
