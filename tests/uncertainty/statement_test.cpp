// The calibration statement (JCGM 100 §7, Annex G; docs/model.md §10.5): Welch–Satterthwaite, the coverage
// factor from Student's t, and the statement of a coefficient, against closed forms and published t tables.
#include "ccal/uncertainty/statement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "test_constants.hpp"

namespace ccal {
namespace {

// Quantiles of Student's t at 0.975 (two-sided 95 %) as printed in the usual tables (e.g. GUM Table G.2
// gives 95.45 %; these are the 95 % column of any statistics table), 4 decimals: tolerance half a unit of
// the last decimal.
constexpr double kTable = 5e-5;
constexpr double kT975_3 = 3.1824, kT975_5 = 2.5706, kT975_10 = 2.2281, kT975_30 = 2.0423, kT975_31 = 2.0395;
// Φ⁻¹(0.975), the normal quantile, to 16 digits.
using ccal::test::kZ975;

TEST(Statement, PureTypeBIsNormal) {
  // Only a Type B part (ν = ∞): ν_eff = ∞ and k = 1.96 at 95 %, relative 1e-12 (the quantile is computed to
  // double precision).
  StatementInput in;
  in.estimate = 3e-3;
  in.type_b = {2e-4, kInfiniteDof};
  const CoefficientStatement s = state_coefficient(in, 0.95);
  EXPECT_TRUE(std::isinf(s.effective_dof));
  EXPECT_NEAR(s.coverage_factor, kZ975, 1e-12 * kZ975);
  EXPECT_NEAR(s.combined, 2e-4, 1e-18);
  EXPECT_NEAR(s.expanded, kZ975 * 2e-4, 1e-15);
}

TEST(Statement, OneTypeAPartIsStudentsTAtItsDof) {
  // u_c = u_A: ν_eff = ν_A exactly, k = t_{0.975, ν_A}.
  for (const auto& [dof, t] : {std::pair{3.0, kT975_3}, {5.0, kT975_5}, {10.0, kT975_10}}) {
    StatementInput in;
    in.type_a = {1.5, dof};
    const CoefficientStatement s = state_coefficient(in, 0.95);
    EXPECT_DOUBLE_EQ(s.effective_dof, dof);
    EXPECT_NEAR(s.coverage_factor, t, kTable) << dof;
    EXPECT_NEAR(s.expanded, 1.5 * s.coverage_factor, 1e-14);
  }
}

TEST(Statement, MixedCaseByHand) {
  // u_A = 3 with ν_A = 4, u_B = 4 (ν = ∞), correction −0.5 on an estimate of 10:
  //   u_c = √(9 + 16) = 5; ν_eff = 5⁴ / (3⁴/4) = 2500/81 = 30.864…, truncated to 30 (G.4.1 note 1);
  //   k = t_{0.975, 30} = 2.0423; U = 5 k = 10.2115; interval 9.5 ∓ U.
  StatementInput in;
  in.estimate = 10;
  in.correction = -0.5;
  in.type_a = {3, 4};
  in.type_b = {4, kInfiniteDof};
  const CoefficientStatement s = state_coefficient(in, 0.95);
  EXPECT_DOUBLE_EQ(s.corrected, 9.5);
  EXPECT_DOUBLE_EQ(s.combined, 5);
  EXPECT_NEAR(s.effective_dof, 2500.0 / 81.0, 1e-12);
  EXPECT_EQ(s.dof_for_k, 30);
  EXPECT_NEAR(s.coverage_factor, kT975_30, kTable);
  // Truncation, not rounding: t at 31 would differ by 2.8e-3, far beyond the table's half unit.
  EXPECT_GT(std::abs(s.coverage_factor - kT975_31), 10 * kTable);
  EXPECT_NEAR(s.expanded, 5 * kT975_30, 5 * kTable);
  EXPECT_NEAR(s.low, 9.5 - 5 * kT975_30, 5 * kTable);
  EXPECT_NEAR(s.high, 9.5 + 5 * kT975_30, 5 * kTable);
}

TEST(Statement, WelchSatterthwaiteOfTwoTypeAParts) {
  // Two equal parts of 10 degrees of freedom: ν_eff = (2u²)² / (2 u⁴/10) = 20 (G.2b by hand).
  EXPECT_NEAR(welch_satterthwaite({{1.0, 10}, {1.0, 10}}), 20, 1e-12);
  // Parts of zero size do not count; no finite part at all gives ∞.
  EXPECT_NEAR(welch_satterthwaite({{2.0, 7}, {0.0, 1}}), 7, 1e-12);
  EXPECT_TRUE(std::isinf(welch_satterthwaite({{2.0, kInfiniteDof}, {0.0, 3}})));
}

TEST(Statement, OtherProbabilities) {
  // p = 0.99 at ν = ∞: Φ⁻¹(0.995) = 2.5758293035489 (16-digit value of the normal quantile); p = 0.6827 at
  // ν = ∞ gives k ≈ 1 (the 1σ interval holds 68.27 %): 4 decimals of that probability.
  EXPECT_NEAR(student_coverage_factor(0.99, kInfiniteDof), 2.5758293035489004, 1e-12);
  EXPECT_NEAR(student_coverage_factor(0.6827, kInfiniteDof), 1.0, 1e-4);
}

TEST(Statement, BadInputsAreRefused) {
  EXPECT_THROW(student_coverage_factor(1.0, 5), std::invalid_argument);
  EXPECT_THROW(student_coverage_factor(0.0, 5), std::invalid_argument);
  EXPECT_THROW(student_coverage_factor(0.95, 0.5), std::invalid_argument);
  EXPECT_THROW(welch_satterthwaite({{-1.0, 5}}), std::invalid_argument);
  EXPECT_THROW(welch_satterthwaite({{1.0, 0}}), std::invalid_argument);
}

TEST(Statement, FiguresAreRoundedToTwoSignificantDigitsOfU) {
  // JCGM 100 §7.2.6: U to two significant digits, the estimate to the same place, the interval's ends the
  // written estimate ∓ the written U.
  const RoundedFigures a = round_figures(0.0030046263, 0.046162);
  EXPECT_EQ(a.place, -3);
  EXPECT_EQ(a.estimate, "0.003");
  EXPECT_EQ(a.expanded, "0.046");
  EXPECT_EQ(a.low, "-0.043");
  EXPECT_EQ(a.high, "0.049");
  // 0.06202 ± 0.03649: the ends of the full values would round to 0.026 and 0.099, but the certificate reads
  // 0.062 ± 0.036, whose ends are 0.026 and 0.098.
  const RoundedFigures k0 = round_figures(0.062024946, 0.036486914);
  EXPECT_EQ(k0.low, "0.026");
  EXPECT_EQ(k0.high, "0.098");
  // 0.0996 rounds to 0.100: one place coarser keeps two digits, 0.10.
  const RoundedFigures b = round_figures(1.23456, 0.0996);
  EXPECT_EQ(b.place, -2);
  EXPECT_EQ(b.expanded, "0.10");
  EXPECT_EQ(b.estimate, "1.23");
  EXPECT_EQ(b.high, "1.33");
  // An exact power of ten and a large U: 1000 → "1000" (place 2), 56789 ± 1234 → 56800 ± 1200.
  EXPECT_EQ(round_figures(5, 1000).expanded, "1000");
  const RoundedFigures c = round_figures(56789, 1234);
  EXPECT_EQ(c.place, 2);
  EXPECT_EQ(c.estimate, "56800");
  EXPECT_EQ(c.expanded, "1200");
  EXPECT_EQ(c.low, "55600");
  // A value that rounds to zero is written without a sign; small magnitudes keep their leading zeros.
  EXPECT_EQ(round_figures(-0.0001, 0.012).estimate, "0.000");
  EXPECT_EQ(round_figures(-2.5e-7, 3.1e-8).estimate, "-0.000000250");
  EXPECT_EQ(round_figures(-2.5e-7, 3.1e-8).low, "-0.000000281");
  // No U to round to, or an estimate too far above it: 8 significant digits and no place.
  const RoundedFigures d = round_figures(0.123456789, 0);
  EXPECT_FALSE(d.place.has_value());
  EXPECT_EQ(d.estimate, "0.12345679");
  EXPECT_FALSE(round_figures(1e20, 1e-3).place.has_value());
}

TEST(Statement, ATermIsSignificantWhenItsIntervalExcludesZero) {
  StatementInput in;
  in.type_b = {1, kInfiniteDof};
  in.estimate = 1.9;  // U = 1.96: the interval holds 0
  EXPECT_FALSE(state_coefficient(in, 0.95).significant);
  in.estimate = -2.0;
  EXPECT_TRUE(state_coefficient(in, 0.95).significant);
  in.estimate = 2.0;
  EXPECT_TRUE(state_coefficient(in, 0.95).significant);
}

TEST(Statement, TheMonteCarloCheckKeepsAnIntervalWithinDeltaAndReplacesOneBeyond) {
  // y = 1, u_c = 0.0235 (δ = ½·10⁻³ for two digits, 0.023|5), U = 1.96 u_c = 0.04606: Monte Carlo ends
  // 0.0004 off are kept (d ≤ δ), 0.0006 off replaced.
  StatementInput in;
  in.estimate = 1;
  in.type_b = {0.0235, kInfiniteDof};
  const CoefficientStatement t = state_coefficient(in, 0.95);
  OutputSummary mc;
  mc.low_symmetric = t.low + 4e-4;
  mc.high_symmetric = t.high - 4e-4;
  CoefficientStatement kept = t;
  check_by_monte_carlo(kept, mc, 100000);
  ASSERT_TRUE(kept.monte_carlo);
  EXPECT_EQ(kept.monte_carlo_trials, 100000u);
  EXPECT_DOUBLE_EQ(kept.monte_carlo->validation_delta, 5e-4);
  EXPECT_NEAR(kept.monte_carlo->d_low, 4e-4, 1e-15);
  EXPECT_TRUE(kept.monte_carlo->validated);
  EXPECT_EQ(kept.method, IntervalMethod::student_t);
  EXPECT_EQ(kept.low, t.low);
  EXPECT_EQ(kept.expanded, t.expanded);

  mc.low_symmetric = t.low + 6e-4;  // one end beyond δ is enough
  CoefficientStatement replaced = t;
  check_by_monte_carlo(replaced, mc, 100000);
  EXPECT_FALSE(replaced.monte_carlo->validated);
  EXPECT_EQ(replaced.method, IntervalMethod::monte_carlo);
  EXPECT_EQ(replaced.low, mc.low_symmetric);
  EXPECT_EQ(replaced.high, mc.high_symmetric);
  EXPECT_DOUBLE_EQ(replaced.expanded, (mc.high_symmetric - mc.low_symmetric) / 2);
  EXPECT_DOUBLE_EQ(replaced.coverage_factor, replaced.expanded / t.combined);
  EXPECT_EQ(replaced.monte_carlo->lpu_expanded, t.expanded);  // what was checked stays on record
  EXPECT_TRUE(replaced.significant);

  // The same excess within three standard errors of the Monte Carlo's ends says nothing about the LPU: kept.
  mc.interval_end_std_error = 1e-4;  // excess 1e-4 = 1 standard error
  CoefficientStatement undecided = t;
  check_by_monte_carlo(undecided, mc, 100000);
  EXPECT_FALSE(undecided.monte_carlo->validated);
  EXPECT_EQ(undecided.method, IntervalMethod::student_t);
  EXPECT_EQ(undecided.low, t.low);
  mc.interval_end_std_error = 0;

  // An interval that the Monte Carlo widens over 0 is no longer significant.
  in.estimate = 0.05;
  CoefficientStatement near_zero = state_coefficient(in, 0.95);
  ASSERT_TRUE(near_zero.significant);  // 0.05 − 0.04606 > 0
  mc.low_symmetric = -0.001;
  mc.high_symmetric = 0.1;
  check_by_monte_carlo(near_zero, mc, 100000);
  EXPECT_EQ(near_zero.method, IntervalMethod::monte_carlo);
  EXPECT_FALSE(near_zero.significant);
}

TEST(Statement, AStatedCoverageFactorGivesUEqualToKTimesUc) {
  // u_A = 3 (ν_A = 4), u_B = 4: u_c = 5, ν_eff = 30.86 (MixedCaseByHand). k = 2 stated: U = 10 exactly (k u_c in
  // one multiplication of exact doubles), whatever ν_eff; p = 2Φ(2) − 1 = 0.954499736103642 for a normal
  // quantity and 2F_t(2; 30) − 1 = 0.94537496 for Student's t at ⌊ν_eff⌋ = 30 (the t density integrated
  // over [−2, 2] by the midpoint rule in 2·10⁵ steps, error below 1e-10; tolerance 1e-8, the digits given).
  StatementInput in;
  in.estimate = 10;
  in.correction = -0.5;
  in.type_a = {3, 4};
  in.type_b = {4, kInfiniteDof};
  const CoefficientStatement s = state_coefficient(in, 0.95, 2.0);
  EXPECT_EQ(s.method, IntervalMethod::coverage_factor);
  EXPECT_EQ(s.coverage_factor, 2.0);
  EXPECT_EQ(s.expanded, 10.0);
  EXPECT_EQ(s.low, -0.5);
  EXPECT_EQ(s.high, 19.5);
  ASSERT_TRUE(s.stated);
  EXPECT_NEAR(s.stated->normal, 0.954499736103642, 1e-14);
  EXPECT_NEAR(s.stated->student_t, 0.94537496, 1e-8);
  EXPECT_LT(s.stated->student_t, s.stated->normal);  // t's tails are wider: less coverage at one k
  // ν_eff = ∞: Student's t is the normal, bit for bit.
  StatementInput b;
  b.type_b = {4, kInfiniteDof};
  const CoefficientStatement n = state_coefficient(b, 0.95, 2.5);
  EXPECT_EQ(n.expanded, 10.0);
  EXPECT_EQ(n.stated->student_t, n.stated->normal);
  // The Monte Carlo check reports, but the stated interval stays, however far its ends are.
  OutputSummary mc;
  mc.low_symmetric = s.low - 3;
  mc.high_symmetric = s.high + 3;
  CoefficientStatement checked = s;
  check_by_monte_carlo(checked, mc, 100000);
  EXPECT_FALSE(checked.monte_carlo->validated);
  EXPECT_EQ(checked.method, IntervalMethod::coverage_factor);
  EXPECT_EQ(checked.expanded, 10.0);
  EXPECT_EQ(checked.low, -0.5);
  EXPECT_EQ(trials_to_settle(s, mc, 100000), 0u);  // nothing to settle
}

TEST(Statement, AVerdictWithinTheSamplingErrorAsksForMoreTrials) {
  // y = 1, u_c = 0.0235 (δ = 5e-4): ends 6e-4 off with a standard error of 1e-4 (excess 1 s_e): unsettled, and
  // the M at which s_e = δ/3 is M (3·1e-4/5e-4)² = 0.36 M; never less than M + 1, so M grows. With s_e = 1e-5
  // the excess is 10 s_e: settled (refused); ends within δ: settled (validated).
  StatementInput in;
  in.estimate = 1;
  in.type_b = {0.0235, kInfiniteDof};
  const CoefficientStatement t = state_coefficient(in, 0.95);
  OutputSummary mc;
  mc.low_symmetric = t.low + 6e-4;
  mc.high_symmetric = t.high;
  mc.interval_end_std_error = 1e-4;
  EXPECT_EQ(trials_to_settle(t, mc, 100000), 100001u);
  mc.interval_end_std_error = 3e-4;  // M (3·3e-4/5e-4)² = 3.24 M, rounded up to two digits
  EXPECT_EQ(trials_to_settle(t, mc, 100000), 330000u);
  mc.interval_end_std_error = 1e-5;
  EXPECT_EQ(trials_to_settle(t, mc, 100000), 0u);
  mc.low_symmetric = t.low + 4e-4;
  mc.interval_end_std_error = 1e-3;
  EXPECT_EQ(trials_to_settle(t, mc, 100000), 0u);
}

TEST(Statement, AnIntervalNotCentredIsRoundedAtItsHalfWidthsSecondDigit) {
  // [−0.04316, 0.04917] about 0.0030046: half-width 0.046165 → the place 10⁻³, each end on its own.
  const RoundedFigures r = round_interval(0.0030046263, -0.043158576, 0.049167828);
  ASSERT_TRUE(r.place);
  EXPECT_EQ(*r.place, -3);
  EXPECT_EQ(r.estimate, "0.003");
  EXPECT_EQ(r.expanded, "0.046");
  EXPECT_EQ(r.low, "-0.043");
  EXPECT_EQ(r.high, "0.049");
  // Asymmetric: [9.2, 10.94] about 10: half-width 0.87 → hundredths; the ends are not 10 ∓ 0.87.
  const RoundedFigures a = round_interval(10, 9.2, 10.94);
  EXPECT_EQ(a.estimate, "10.00");
  EXPECT_EQ(a.expanded, "0.87");
  EXPECT_EQ(a.low, "9.20");
  EXPECT_EQ(a.high, "10.94");
  // No place for a zero width: 8 significant digits.
  EXPECT_FALSE(round_interval(1, 1, 1).place);
}

}  // namespace
}  // namespace ccal
