// The Type A part of a calibration statement (src/verbs/statement_type_a.hpp, docs/model.md §10.5) against closed
// forms. The paper's set-up with equal run durations T and white output noise of density N states σ = N/√T for
// every run mean, so that
//   - the noise model's covariance is σ² (HᵀH)⁻¹, i.e. u_A = (σ/s)·(the fit's standard error), ν = ∞;
//   - with no Type B inputs the residual statistic S = Σ r²/σ² = RSS/σ² has expectation tr(M) = n − p and is
//     exactly χ² with n − p degrees of freedom (the scaled χ² of the same two moments is that one);
//   - observations noisier than stated give S beyond the 99 % level, and the excess τ² = σ²(S − (n − p))/(n − p)
//     is charged: u_A² = (σ² + τ²)(HᵀH)⁻¹_kk with ν_A = (n − p)(σ² + τ²)²/τ⁴ (Welch–Satterthwaite);
//   - the Type B inputs' between-run effects raise the expected S.
#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <string>

#include "../../src/verbs/statement_type_a.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/verbs/simulate.hpp"
#include "ccal/verbs/statement.hpp"
#include "verbs_support.hpp"

namespace ccal::test {
namespace {

// The paper's set-up with the instrument's noise density `noise` (deg/s/√Hz), with or without its tolerances.
// Without: one tolerance that cannot act (dthx4 of 1e-12 rad, a tilt about the IA: its effects are below 1e-20 of
// σ), since a budget needs a source.
Config paper_noise(const std::string& noise, bool tolerances) {
  std::string text = edited(read_text(kPaperConfigPath), "noise_density = \"0 deg/s/rtHz\"",
                            "noise_density = \"" + noise + "\"");
  if (!tolerances) {
    const auto begin = text.find("[tolerances]\n"), end = text.find("[instrument]\n");
    text = text.substr(0, begin) + "[tolerances]\ndthx4 = \"1e-12 rad\"\n\n" + text.substr(end);
  }
  return parse_config(text, "noisy-paper.toml");
}

verbs::StatementOptions unchecked() {
  verbs::StatementOptions o;
  o.statement_trials = 0;
  return o;
}

// σ of every run mean in the fit's unit (deg/s).
double run_sigma(const Config& c) {
  return c.instrument.noise_density / std::sqrt(c.plan.runs.front().duration) / output_unit_si(c.instrument.output_unit);
}

TEST(StatementTypeA, WithoutTypeBInputsTheResidualStatisticIsAChiSquaredOfNMinusPDegrees) {
  const Config c = paper_noise("0.05 deg/s/rtHz", false);
  const verbs::Identification id = verbs::simulate(c).identification;
  const verbs::CalibrationStatement s = verbs::calibration_statement(c, id, unchecked(), "statement");
  const verbs::TypeAEvaluation& a = s.type_a;
  ASSERT_TRUE(a.from_noise_model);
  const double sigma = run_sigma(c), nu = double(id.fit.dof);
  ASSERT_EQ(a.run_sd.size(), c.plan.runs.size());
  for (double sd : a.run_sd) EXPECT_NEAR(sd, sigma, 1e-15 * sigma);
  // S = RSS/σ² (1e-12: one sum), E = n − p (1e-12: the trace of a projection), p-value from χ²_{n−p} (1e-9).
  const double rss = id.fit.residuals.squaredNorm();
  EXPECT_NEAR(a.statistic, rss / (sigma * sigma), 1e-12 * a.statistic);
  EXPECT_NEAR(a.expected, nu, 1e-12 * nu);
  const double p = boost::math::cdf(boost::math::complement(boost::math::chi_squared(nu), a.statistic));
  EXPECT_NEAR(a.p_value, p, 1e-9);
  EXPECT_EQ(a.excess, p < verbs::kResidualCheckLevel);
  ASSERT_FALSE(a.excess) << "the observations have the noise the set-up states";
  for (std::size_t k = 0; k < s.coefficients.size(); ++k) {
    const CoefficientStatement& st = s.coefficients[k];
    const double u_a = sigma / id.fit.residual_std * id.fit.std_error[Eigen::Index(k)];
    EXPECT_NEAR(st.input.type_a.u, u_a, 1e-10 * u_a) << st.input.coefficient;
    EXPECT_TRUE(std::isinf(st.input.type_a.dof));
    EXPECT_LT(st.input.type_b.u, 1e-12 * u_a);
  }
}

TEST(StatementTypeA, ScatterBeyondTheNoiseModelIsChargedWithItsDegreesOfFreedom) {
  // Observations with ten times the stated noise: S ≈ 100 (n − p), far beyond the 99 % level.
  const Config loud = paper_noise("0.5 deg/s/rtHz", false), stated = paper_noise("0.05 deg/s/rtHz", false);
  const verbs::Identification id = verbs::simulate(loud).identification;
  const verbs::CalibrationStatement s = verbs::calibration_statement(stated, id, unchecked(), "statement");
  const verbs::TypeAEvaluation& a = s.type_a;
  ASSERT_TRUE(a.excess);
  EXPECT_LT(a.p_value, verbs::kResidualCheckLevel);
  const double sigma = run_sigma(stated), nu = double(id.fit.dof);
  const double tau2 = sigma * sigma * (a.statistic - nu) / nu;
  EXPECT_NEAR(a.excess_variance, tau2, 1e-10 * tau2);
  for (std::size_t k = 0; k < s.coefficients.size(); ++k) {
    const CoefficientStatement& st = s.coefficients[k];
    const double inverse_kk = std::pow(id.fit.std_error[Eigen::Index(k)] / id.fit.residual_std, 2);  // (HᵀH)⁻¹_kk
    const double u_a = std::sqrt((sigma * sigma + tau2) * inverse_kk);
    EXPECT_NEAR(st.input.type_a.u, u_a, 1e-10 * u_a) << st.input.coefficient;
    const double dof = nu * std::pow(sigma * sigma + tau2, 2) / (tau2 * tau2);
    EXPECT_NEAR(st.input.type_a.dof, dof, 1e-9 * dof) << st.input.coefficient;
  }
  // The parts' Welch–Satterthwaite by itself: a known part alone is ν = ∞, an estimated one alone its own ν.
  EXPECT_TRUE(std::isinf(verbs::type_a_dof(1.0, 0.0, 3)));
  EXPECT_EQ(verbs::type_a_dof(0.0, 2.0, 3), 3.0);
  EXPECT_NEAR(verbs::type_a_dof(1.0, 1.0, 3), 12.0, 1e-15);
}

TEST(StatementTypeA, TheTypeBInputsBetweenRunEffectsRaiseTheExpectedScatter) {
  // The paper's tolerances move every run mean differently: the residuals they leave are predicted, so E exceeds
  // the n − p of the noise alone (by far: their between-run effects are much larger than σ here).
  const Config c = paper_noise("0.05 deg/s/rtHz", true);
  const verbs::CalibrationStatement s =
      verbs::calibration_statement(c, verbs::simulate(c).identification, unchecked(), "statement");
  EXPECT_GT(s.type_a.expected, 1.5 * double(s.type_a.dof));
}

TEST(StatementTypeA, KnownErrorsTheModelLeavesOutAreNotScatter) {
  // The lab example with a known levelling error of 20 arcsec, not compensated: its effect on the run means is
  // deterministic (the statement corrects for it), so the residuals' check removes its share M·Δy. The noise is
  // drawn alike (same seed) and the model's regressors are those without errors in both, so S is the lab's own,
  // to the round-off of removing a share some 10⁷ times larger (5 % of S allowed: 1e-9 of that share). Without
  // the removal S would be that share, and an excess charged.
  const Config clean = load_config(CCAL_SOURCE_DIR + "/examples/lab.toml");
  Config known = clean;
  known.centrifuge.errors[*known.centrifuge.layout.find_parameter("dthy1t")] = 20 * 4.84813681109536e-6;
  const verbs::CalibrationStatement a =
      verbs::calibration_statement(clean, verbs::simulate(clean).identification, unchecked(), "statement");
  const verbs::CalibrationStatement b =
      verbs::calibration_statement(known, verbs::simulate(known).identification, unchecked(), "statement");
  EXPECT_NEAR(b.type_a.statistic, a.type_a.statistic, 0.05 * a.type_a.statistic);
  EXPECT_FALSE(a.type_a.excess);
  EXPECT_FALSE(b.type_a.excess);
}

TEST(StatementTypeA, WithoutANoiseModelTheFitsScatterWithItsDegreesOfFreedom) {
  const Config loud = paper_noise("0.05 deg/s/rtHz", false), quiet = paper_noise("0 deg/s/rtHz", false);
  const verbs::Identification id = verbs::simulate(loud).identification;
  const verbs::CalibrationStatement s = verbs::calibration_statement(quiet, id, unchecked(), "statement");
  EXPECT_FALSE(s.type_a.from_noise_model);
  for (std::size_t k = 0; k < s.coefficients.size(); ++k) {
    EXPECT_EQ(s.coefficients[k].input.type_a.u, id.fit.std_error[Eigen::Index(k)]);
    EXPECT_EQ(s.coefficients[k].input.type_a.dof, double(id.fit.dof));
  }
}

}  // namespace
}  // namespace ccal::test
