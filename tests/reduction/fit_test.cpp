// Tests of the linear least-squares fit. Every tolerance is stated next to its assertion with the
// reason for its size. (NIST StRD: tests/system/fit_nist_test.cpp; the differentiable
// solve: fit_solve_test.cpp.)
#include "fit_test_support.hpp"

namespace {

using namespace ccal::fit_test;

// ---------------------------------------------------------------------------------------------------
// 1. Exact recovery.

TEST(Fit, RecoversExactCoefficientsOfAWellConditionedDesign) {
  const MatrixXd h = random_design(40, 5, 7);
  VectorXd x(5);
  x << 1.5, -0.003, 42.0, 1e3, -7.25;
  FitProblem p{names_of(5), h, h * x, {}, {}, {}};
  for (const auto method : {FitMethod::qr, FitMethod::svd}) {
    FitOptions o;
    o.method = method;
    const FitResult r = ccal::fit(p, o);
    // Random columns scaled to unit norm give a condition number of a few units, so a backward-stable
    // solver recovers x to a few ulps of cond * eps ~ 1e-15; 1e-12 leaves ample margin.
    EXPECT_LT(relative_error(r.value, x), 1e-12);
    EXPECT_EQ(r.rank, 5);
    EXPECT_EQ(r.dof, 35);
    EXPECT_LT(r.condition_number, 10.0);  // sanity of the "well conditioned" premise
    // Exact data: residuals are rounding noise relative to |y| (max ~ 1e3 * 450); 1e-9 absolute is generous.
    EXPECT_LT(r.residuals.cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_TRUE(r.warnings.empty());
  }
}

// ---------------------------------------------------------------------------------------------------
// 2. Fixed terms.

TEST(Fit, FixedTermGivesTheSameOtherCoefficientsOnExactData) {
  const MatrixXd h = random_design(25, 4, 11);
  VectorXd x(4);
  x << 0.25, 3.0, -11.0, 0.5;
  FitProblem full{{"K0", "K1", "K2", "K3"}, h, h * x, {}, {}, {}};
  FitProblem held = full;
  held.fixed["K1"] = x(1);
  const FitResult rf = ccal::fit(full);
  const FitResult rh = ccal::fit(held);
  ASSERT_EQ(rh.names, (std::vector<std::string>{"K0", "K2", "K3"}));
  ASSERT_EQ(rh.value.size(), 3);
  EXPECT_EQ(rh.dof, 22);
  // Both fits are exact recoveries of well-conditioned problems (condition of the scaled design ~ a few),
  // so coefficient k is right to about cond * eps * |y| / |H_k|: the change of that coefficient that
  // moves y by a rounding error. That is what 1e-12 * |y| / |H_k| bounds with margin; a bound relative
  // to the coefficient itself would be wrong for a small column (K3, ~0.02) among large ones (K1, ~450).
  const int full_index[] = {0, 2, 3};
  for (int k = 0; k < 3; ++k) {
    const double tol = 1e-12 * full.y.norm() / h.col(full_index[k]).norm();
    EXPECT_NEAR(rh.value(k), rf.value(full_index[k]), tol);
    EXPECT_NEAR(rh.value(k), x(full_index[k]), tol);
  }
}

TEST(Fit, FixedTermValueIsSubtractedFromTheObservations) {
  // y = 2 + 3 t with K1 fixed at a wrong value 2.5: K0 absorbs the mean of 0.5 t and residuals show the rest.
  VectorXd t(4);
  t << 0, 1, 2, 3;
  const MatrixXd h = ccal::polynomial_design(t, 1);
  FitProblem p{ccal::polynomial_term_names(1), h, (2.0 + 3.0 * t.array()).matrix(), {}, {{"K1", 2.5}}, {}};
  const FitResult r = ccal::fit(p);
  ASSERT_EQ(r.value.size(), 1);
  // Simple arithmetic on small integers and halves: exact up to a few ulps.
  EXPECT_NEAR(r.value(0), 2.75, 1e-14);
  VectorXd expected(4);
  expected << -0.75, -0.25, 0.25, 0.75;
  EXPECT_LT((r.residuals - expected).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Fit, AllTermsFixedOnlyEvaluatesResiduals) {
  VectorXd t(3);
  t << 1, 2, 3;
  FitProblem p{{"K0", "K1"}, ccal::polynomial_design(t, 1), t, {}, {{"K0", 0.0}, {"K1", 1.0}}, {}};
  const FitResult r = ccal::fit(p);
  EXPECT_EQ(r.value.size(), 0);
  EXPECT_EQ(r.rank, 0);
  EXPECT_EQ(r.dof, 3);
  EXPECT_EQ(r.residuals.cwiseAbs().maxCoeff(), 0.0);  // y - 1 * t is exactly zero
}

// ---------------------------------------------------------------------------------------------------
// 4. Ill-posed plans.

TEST(Fit, DependentColumnsAreNamed) {
  const MatrixXd base = random_design(20, 3, 3);
  MatrixXd h(20, 4);
  h << base, base.col(2);  // K_pp duplicates K2
  FitProblem p{{"K0", "K1", "K2", "K_pp"}, h, h * VectorXd::Ones(4), {}, {}, {}};
  for (const auto method : {FitMethod::qr, FitMethod::svd}) {
    FitOptions o;
    o.method = method;
    try {
      ccal::fit(p, o);
      FAIL() << "expected IllPosedFit";
    } catch (const IllPosedFit& e) {
      const std::string what = e.what();
      EXPECT_TRUE(contains(what, "K2")) << what;
      EXPECT_TRUE(contains(what, "K_pp")) << what;
      EXPECT_TRUE(contains(what, "linearly dependent")) << what;
      EXPECT_FALSE(contains(what, "K0")) << what;  // bystanders are not blamed
      EXPECT_FALSE(contains(what, "K1")) << what;
    }
  }
  // Holding one of the pair fixed makes the plan solvable again, and exact: y = H·1, so with K_pp at its true
  // value 1 the free terms are 1 (a well-conditioned 20×3 design: round-off, 1e-12 relative to |y|/|H_k|).
  p.fixed["K_pp"] = 1.0;
  const FitResult held = ccal::fit(p);
  ASSERT_EQ(held.names, (std::vector<std::string>{"K0", "K1", "K2"}));
  for (Eigen::Index k = 0; k < 3; ++k)
    EXPECT_NEAR(held.value(k), 1.0, 1e-12 * p.y.norm() / h.col(k).norm()) << held.names[std::size_t(k)];
}

TEST(Fit, ThreeWayDependencyNamesAllThree) {
  const MatrixXd base = random_design(15, 3, 5);
  MatrixXd h(15, 4);
  h << base, base.col(0) - 2.0 * base.col(2);  // C = A - 2 B
  FitProblem p{{"A", "Q", "B", "C"}, h, h * VectorXd::Ones(4), {}, {}, {}};
  try {
    ccal::fit(p);
    FAIL() << "expected IllPosedFit";
  } catch (const IllPosedFit& e) {
    const std::string what = e.what();
    EXPECT_TRUE(contains(what, "A, B and C")) << what;
    EXPECT_FALSE(contains(what, "Q")) << what;
  }
}

TEST(Fit, ZeroColumnIsNamed) {
  MatrixXd h = random_design(10, 3, 9);
  h.col(1).setZero();
  FitProblem p{{"K0", "K_ip", "K2"}, h, VectorXd::Ones(10), {}, {}, {}};
  try {
    ccal::fit(p);
    FAIL() << "expected IllPosedFit";
  } catch (const IllPosedFit& e) {
    EXPECT_TRUE(contains(e.what(), "K_ip")) << e.what();
  }
}

TEST(Fit, FewerRowsThanTermsIsIllPosed) {
  const MatrixXd h = random_design(3, 4, 1);
  FitProblem p{{"K0", "K1", "K2", "K3"}, h, VectorXd::Ones(3), {}, {}, {}};
  try {
    ccal::fit(p);
    FAIL() << "expected IllPosedFit";
  } catch (const IllPosedFit& e) {
    const std::string what = e.what();
    EXPECT_TRUE(contains(what, "3 observations")) << what;
    EXPECT_TRUE(contains(what, "4 free terms")) << what;
  }
  // Fixing one term leaves a square, solvable problem: H_free x = y exactly, with x from an LU solve here.
  // The random 3×3 block has a condition number of a few hundred: tolerance 1e-11 relative.
  p.fixed["K3"] = 0.0;
  const FitResult square = ccal::fit(p);
  const VectorXd want = h.leftCols(3).fullPivLu().solve(p.y);
  ASSERT_EQ(square.value.size(), 3);
  for (Eigen::Index k = 0; k < 3; ++k) EXPECT_NEAR(square.value(k), want(k), 1e-11 * want.norm()) << k;
  EXPECT_EQ(square.dof, 0);
}

TEST(Fit, ExcessiveConditionNumberNamesTheMostCorrelatedPair) {
  const MatrixXd base = random_design(30, 3, 21);
  MatrixXd h(30, 4);
  std::mt19937 rng(4);
  std::normal_distribution<double> normal;
  VectorXd wiggle(30);
  for (auto& v : wiggle) v = normal(rng);
  // K_b differs from K_a by 1e-9 of its size: condition number ~1e9 after scaling.
  h << base, base.col(1) + 1e-9 * base.col(1).norm() / wiggle.norm() * wiggle;
  FitProblem p{{"K0", "K_a", "K2", "K_b"}, h, h * VectorXd::Ones(4), {}, {}, {}};
  FitOptions o;
  o.max_condition = 1e6;
  try {
    ccal::fit(p, o);
    FAIL() << "expected IllPosedFit";
  } catch (const IllPosedFit& e) {
    const std::string what = e.what();
    EXPECT_TRUE(contains(what, "K_a and K_b")) << what;
    EXPECT_TRUE(contains(what, "condition number")) << what;
  }
  // With the condition-number limit raised, the correlation limit (default 0.99999) still refuses it …
  o.max_condition = 1e12;
  try {
    ccal::fit(p, o);
    FAIL() << "expected IllPosedFit for correlation beyond refuse_correlation";
  } catch (const IllPosedFit& e) {
    EXPECT_TRUE(contains(e.what(), "cannot separate K_a and K_b")) << e.what();
  }
  // … and allowed to proceed, the fit solves it and warns about the pair instead.
  o.refuse_correlation = 1.0;
  const FitResult r = ccal::fit(p, o);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_TRUE(contains(r.warnings.front(), "K_a and K_b")) << r.warnings.front();
}

// Two columns at an angle whose cosine is c, plus an unrelated third: the estimates of the pair then
// have correlation -c.
FitProblem near_alias_problem(double c) {
  const MatrixXd q = random_design(12, 3, 17).householderQr().householderQ() * MatrixXd::Identity(12, 3);
  MatrixXd h(12, 3);
  h.col(0) = 5.0 * q.col(0);
  h.col(1) = 300.0 * (c * q.col(0) + std::sqrt(1 - c * c) * q.col(1));
  h.col(2) = q.col(2);
  return FitProblem{{"K2", "K_pp", "K0"}, h, h * VectorXd::Ones(3), {}, {}, {}};
}

TEST(Fit, NearAliasingIsAWarning) {
  const FitResult r = ccal::fit(near_alias_problem(0.9995));
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_TRUE(contains(r.warnings[0], "K2 and K_pp")) << r.warnings[0];
  EXPECT_TRUE(contains(r.warnings[0], "-0.9995")) << r.warnings[0];
  // The correlation is -c up to rounding (~1e-15); 1e-12 absolute leaves margin.
  EXPECT_NEAR(r.correlation(0, 1), -0.9995, 1e-12);
  // Exact data still recovered: condition ~ sqrt((1+c)/(1-c)) ~ 63, error ~ 63 * eps, checked to 1e-12.
  EXPECT_LT(relative_error(r.value, VectorXd::Ones(3)), 1e-12);
  // Below the threshold there is no warning.
  EXPECT_TRUE(ccal::fit(near_alias_problem(0.99)).warnings.empty());
  FitOptions strict;
  strict.alias_correlation = 0.9999;
  EXPECT_TRUE(ccal::fit(near_alias_problem(0.9995), strict).warnings.empty());
}

// ---------------------------------------------------------------------------------------------------
// 5. Weights.

TEST(Fit, WeightedFitEqualsUnweightedFitOfScaledRows) {
  const MatrixXd h = random_design(30, 3, 31);
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> w_dist(0.5, 4.0);
  std::normal_distribution<double> noise;
  VectorXd w(30), y(30);
  VectorXd x(3);
  x << 2.0, -0.01, 4.0;
  for (Eigen::Index i = 0; i < 30; ++i) {
    w(i) = w_dist(rng);
    y(i) = h.row(i).dot(x) + noise(rng) / std::sqrt(w(i));
  }
  const FitResult weighted = ccal::fit(FitProblem{{"a", "b", "c"}, h, y, w, {}, {}});
  const VectorXd sw = w.cwiseSqrt();
  const FitResult scaled =
      ccal::fit(FitProblem{{"a", "b", "c"}, sw.asDiagonal() * h, sw.cwiseProduct(y), {}, {}, {}});
  // Same problem, same algorithm, inputs differing only by the rounding of sqrt(w) * row: the
  // solutions agree to ~cond * eps ~ 1e-15; 1e-12 relative leaves margin.
  EXPECT_LT(relative_error(weighted.value, scaled.value), 1e-12);
  EXPECT_NEAR(weighted.chi2, scaled.chi2, 1e-12 * scaled.chi2);
  // Unweighted covariance carries s^2 = chi2/dof; with weights the covariance is (H^T W H)^-1.
  const MatrixXd rescaled = weighted.chi2_per_dof * weighted.covariance;
  EXPECT_LT((rescaled - scaled.covariance).norm() / scaled.covariance.norm(), 1e-12);
  // Residuals are in the units of y for the weighted fit; the scaled fit's are sqrt(w) times those.
  EXPECT_LT((sw.cwiseProduct(weighted.residuals) - scaled.residuals).norm() / scaled.residuals.norm(), 1e-10);

  // (H^T W H)^-1 by a direct 3x3 inverse: fine here because this small case is well conditioned
  // (cond(H^T W H) < 1e6 with these column magnitudes), so the direct inverse itself is good to ~1e-10.
  const MatrixXd direct = (h.transpose() * w.asDiagonal() * h).inverse();
  for (Eigen::Index i = 0; i < 3; ++i) {
    for (Eigen::Index j = 0; j < 3; ++j) {
      EXPECT_NEAR(weighted.covariance(i, j), direct(i, j), 1e-10 * std::sqrt(direct(i, i) * direct(j, j)));
    }
  }
  // Weights taken as 1/sigma^2 and the noise drawn with those sigmas: chi2/dof ~ 1 (27 dof; a 5-sigma
  // band of the chi2 distribution is 1 +- 5*sqrt(2/27) ~ [0, 2.4]).
  EXPECT_GT(weighted.chi2_per_dof, 0.1);
  EXPECT_LT(weighted.chi2_per_dof, 2.4);
}

TEST(Fit, NoDegreesOfFreedom) {
  const MatrixXd h = random_design(3, 3, 41);
  const VectorXd y = h * VectorXd::Ones(3);
  const FitResult plain = ccal::fit(FitProblem{{"a", "b", "c"}, h, y, {}, {}, {}});
  EXPECT_EQ(plain.dof, 0);
  EXPECT_EQ(plain.residual_std, 0.0);
  EXPECT_EQ(plain.std_error, VectorXd::Zero(3));
  EXPECT_EQ(plain.covariance, MatrixXd::Zero(3, 3));
  ASSERT_EQ(plain.warnings.size(), 1u);
  EXPECT_TRUE(contains(plain.warnings[0], "no degrees of freedom: standard errors are undefined"));
  // A square system is solved exactly: error ~ cond * eps.
  EXPECT_LT(relative_error(plain.value, VectorXd::Ones(3)), 1e-12);

  VectorXd w(3);
  w << 1.0, 4.0, 0.25;
  const FitResult weighted = ccal::fit(FitProblem{{"a", "b", "c"}, h, y, w, {}, {}});
  const MatrixXd direct = (h.transpose() * w.asDiagonal() * h).inverse();
  // Square, well-conditioned 3x3 case: the direct inverse is a fair reference to 1e-10.
  EXPECT_LT((weighted.covariance - direct).norm() / direct.norm(), 1e-10);
  ASSERT_EQ(weighted.warnings.size(), 1u);
  EXPECT_TRUE(contains(weighted.warnings[0], "covariance comes from the weights"));
}

TEST(Fit, QrAndSvdAgree) {
  // A moderately ill-conditioned cubic on [100, 110] (condition ~1e7 after scaling).
  VectorXd t = VectorXd::LinSpaced(25, 100.0, 110.0);
  const MatrixXd h = ccal::polynomial_design(t, 3);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1e-3);
  VectorXd y = h * VectorXd::Constant(4, 0.5);
  for (auto& v : y) v += noise(rng);
  FitProblem p{ccal::polynomial_term_names(3), h, y, {}, {}, {}};
  FitOptions q, s;
  s.method = FitMethod::svd;
  const FitResult rq = ccal::fit(p, q), rs = ccal::fit(p, s);
  // Both are backward stable; their solutions differ by ~cond * eps ~ 1e-9 relative; allow 1e-7.
  EXPECT_LT(relative_error(rq.value, rs.value), 1e-7);
  EXPECT_LT((rq.std_error - rs.std_error).norm() / rs.std_error.norm(), 1e-7);
  EXPECT_NEAR(rq.condition_number, rs.condition_number, 1e-12 * rs.condition_number);  // same SVD
}

// ---------------------------------------------------------------------------------------------------
// 6. Bad input.

TEST(Fit, NonFiniteObservationIsReportedWithItsRow) {
  const MatrixXd h = random_design(5, 2, 2);
  VectorXd y = VectorXd::Ones(5);
  y(2) = std::numeric_limits<double>::quiet_NaN();
  FitProblem p{{"K0", "K1"}, h, y, {}, {}, {}};
  try {
    ccal::fit(p);
    FAIL() << "expected invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "row 3")) << e.what();
    EXPECT_TRUE(contains(e.what(), " y ")) << e.what();
  }
  p.row_labels = {"r1", "r2", "run_pp_07", "r4", "r5"};
  try {
    ccal::fit(p);
    FAIL() << "expected invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "row 3 (run_pp_07)")) << e.what();
  }
}

TEST(Fit, NonFiniteDesignEntryIsReportedWithRowAndColumn) {
  MatrixXd h = random_design(5, 3, 2);
  h(1, 2) = std::numeric_limits<double>::infinity();
  FitProblem p{{"K0", "K1", "K_pp"}, h, VectorXd::Ones(5), {}, {}, {}};
  try {
    ccal::fit(p);
    FAIL() << "expected invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(contains(e.what(), "row 2, column 3 (K_pp)")) << e.what();
  }
}

TEST(Fit, UnknownFixedTermListsTheValidNames) {
  FitProblem p{{"K0", "K2", "K_pp"}, random_design(5, 3, 2), VectorXd::Ones(5), {}, {{"K3", 1.0}}, {}};
  try {
    ccal::fit(p);
    FAIL() << "expected invalid_argument";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_TRUE(contains(what, "\"K3\"")) << what;
    EXPECT_TRUE(contains(what, "K0, K2, K_pp")) << what;
  }
}

TEST(Fit, OtherMalformedInputIsRejected) {
  const MatrixXd h = random_design(5, 2, 2);
  const VectorXd y = VectorXd::Ones(5);
  EXPECT_THROW(ccal::fit(FitProblem{{"K0", "K0"}, h, y, {}, {}, {}}), std::invalid_argument);  // duplicate
  EXPECT_THROW(ccal::fit(FitProblem{{"K0"}, h, y, {}, {}, {}}), std::invalid_argument);  // too few names
  EXPECT_THROW(ccal::fit(FitProblem{{"K0", "K1"}, h, VectorXd::Ones(4), {}, {}, {}}), std::invalid_argument);
  EXPECT_THROW(ccal::fit(FitProblem{{"K0", "K1"}, h, y, VectorXd::Ones(4), {}, {}}), std::invalid_argument);
  VectorXd w = VectorXd::Ones(5);
  w(4) = 0.0;
  EXPECT_THROW(ccal::fit(FitProblem{{"K0", "K1"}, h, y, w, {}, {}}), std::invalid_argument);  // zero weight
  w(4) = -1.0;
  EXPECT_THROW(ccal::fit(FitProblem{{"K0", "K1"}, h, y, w, {}, {}}), std::invalid_argument);  // negative
  w(4) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ccal::fit(FitProblem{{"K0", "K1"}, h, y, w, {}, {}}), std::invalid_argument);  // infinite
  EXPECT_THROW(ccal::fit(FitProblem{{"K0", "K1"}, h, y, {}, {{"K1", NAN}}, {}}), std::invalid_argument);
  EXPECT_THROW(ccal::fit(FitProblem{{"K0", "K1"}, h, y, {}, {}, {"only one"}}), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------
// Polynomial helpers.

TEST(Polynomial, DesignAndNames) {
  VectorXd x(3);
  x << 2.0, -0.5, 0.0;
  const MatrixXd h = ccal::polynomial_design(x, 3);
  MatrixXd expected(3, 4);
  expected << 1, 2, 4, 8, 1, -0.5, 0.25, -0.125, 1, 0, 0, 0;
  EXPECT_EQ(h, expected);  // powers of 2 are exact
  EXPECT_EQ(ccal::polynomial_term_names(2), (std::vector<std::string>{"K0", "K1", "K2"}));
  EXPECT_THROW(ccal::polynomial_design(x, -1), std::invalid_argument);
}

}  // namespace

namespace {

// Finite data near the largest double (1e308) overflow in the solution: the fit returned NaN estimates
// without an error. It is refused, naming the estimate and what the user can change.
TEST(Fit, AnOverflowingSolutionIsRefusedNotReturnedAsNaN) {
  MatrixXd h(4, 2);
  h << 1, 1, 1, 2, 1, 3, 1, 4;
  VectorXd y(4);
  y << 1.0e308, 1.2e308, 1.4e308, 1.7e308;
  for (const auto method : {FitMethod::qr, FitMethod::svd}) {
    FitOptions o;
    o.method = method;
    try {
      const FitResult r = ccal::fit(FitProblem{{"K0", "K1"}, h, y, {}, {}, {}}, o);
      ADD_FAILURE() << "accepted: K0 = " << r.value(0) << ", chi2 = " << r.chi2;
    } catch (const ccal::InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("not a finite number"), std::string::npos) << message;
      EXPECT_NE(message.find("scale y"), std::string::npos) << message;
    }
  }
  // The same data scaled by 1e-300 are an ordinary fit (exact to rounding: 1e-12 relative is ample).
  const FitResult r = ccal::fit(FitProblem{{"K0", "K1"}, h, y * 1e-300, {}, {}, {}});
  EXPECT_NEAR(r.value(1), 0.23e8, 0.23e8 * 1e-12);  // Σ(x − x̄)(y − ȳ)/Σ(x − x̄)² = 1.15/5
}

}  // namespace
