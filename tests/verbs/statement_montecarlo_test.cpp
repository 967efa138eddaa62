// The Monte Carlo check of a calibration statement (src/verbs/statement_montecarlo.hpp, JCGM 101 §8) against
// closed forms:
//   - one dominant uniform tolerance of bound a: the coefficient shifts by c x, x ~ U(−a, a), so the 95 %
//     interval of y is y ∓ 0.95 |c| a, narrower than the normal U = 1.96 |c| a/√3 = 1.13 |c| a by 0.18 |c| a,
//     far beyond δ: the Monte Carlo's interval is stated, U half its width, k = U/u_c;
//   - many sources: the Student-t interval holds and the Monte Carlo's u(y) is u_c; a Type A part of 3 degrees
//     of freedom widens the interval beyond Welch–Satterthwaite's, and the Monte Carlo's is stated;
//   - the same seed gives the same numbers for any thread count; statement_trials = 0 runs no check.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/simulate.hpp"
#include "ccal/verbs/statement.hpp"
#include "verbs_support.hpp"

namespace ccal::test {
namespace {

// The paper's set-up with its [tolerances] replaced by `tolerances` and the instrument's noise density.
Config paper_with(const std::string& tolerances, const std::string& noise) {
  std::string text = read_text(kPaperConfigPath);
  const auto begin = text.find("[tolerances]\n"), end = text.find("[instrument]\n");
  text = text.substr(0, begin) + "[tolerances]\n" + tolerances + "\n" + text.substr(end);
  text = edited(text, "noise_density = \"0 deg/s/rtHz\"", "noise_density = \"" + noise + "\"");
  return parse_config(text, "paper-edited.toml");
}

verbs::StatementOptions trials(std::int64_t m, int threads = 0) {
  verbs::StatementOptions o;
  o.statement_trials = m;
  o.threads = threads;
  return o;
}

TEST(StatementMonteCarlo, OneUniformSourceGivesTheUniformsInterval) {
  const Config config = paper_with("dR_s = { bound = \"25 um\", distribution = \"uniform\" }", "0 deg/s/rtHz");
  const verbs::SimulateResult sim = verbs::simulate(config);
  const verbs::CalibrationStatement s =
      verbs::calibration_statement(config, sim.identification, trials(100000), "statement");
  EXPECT_EQ(s.monte_carlo_trials, 100000u);
  int checked = 0;
  for (const CoefficientStatement& c : s.coefficients) {
    SCOPED_TRACE(c.input.coefficient);
    ASSERT_TRUE(c.monte_carlo);
    // Only where the tolerance dominates (the noise-free fit's Type A is round-off).
    if (!(c.input.type_b.u > 1e3 * c.input.type_a.u)) continue;
    ++checked;
    const double ca = std::sqrt(3.0) * c.input.type_b.u;  // |c| a, from u_B = |c| a/√3
    // The 95 % quantiles of a uniform on (−|c|a, |c|a) scatter by √(p(1 − p)/M)·2|c|a = 0.001 |c|a at M = 10⁵:
    // 0.005 |c|a is five of those (the model's second order, ~(25 µm/R)², is far below).
    EXPECT_EQ(c.method, IntervalMethod::monte_carlo);
    EXPECT_NEAR(c.low, c.corrected - 0.95 * ca, 5e-3 * ca);
    EXPECT_NEAR(c.high, c.corrected + 0.95 * ca, 5e-3 * ca);
    EXPECT_DOUBLE_EQ(c.expanded, (c.high - c.low) / 2);
    EXPECT_DOUBLE_EQ(c.coverage_factor, c.expanded / c.combined);
    EXPECT_EQ(c.significant, c.low > 0 || c.high < 0);
    // What the check refused: the Student-t ends, 0.18 |c| a away, against δ of u_c's second digit.
    const OutputSummary& m = *c.monte_carlo;
    EXPECT_FALSE(m.validated);
    EXPECT_NEAR(m.lpu_expanded, 1.96 * c.combined, 1e-3 * c.combined);
    EXPECT_NEAR(m.d_low, (1.96 / std::sqrt(3.0) - 0.95) * ca, 5e-3 * ca);
    EXPECT_EQ(m.validation_delta, numerical_tolerance(c.combined, 2));
    // The uniform's u(y) = |c|a/√3 = u_B: its sample scatters by 0.3 % at M = 10⁵ (fourth moment 1.8 σ⁴).
    EXPECT_NEAR(m.std_dev, c.combined, 1e-2 * c.combined);
    // Written with the place of the half-width's second digit, each end on its own.
    const RoundedFigures r = round_figures(c);
    ASSERT_TRUE(r.place);
    EXPECT_EQ(std::stod(r.low), std::round(c.low / std::pow(10.0, *r.place)) * std::pow(10.0, *r.place));
  }
  EXPECT_GE(checked, 2) << "the radius error moves K2 and K3";
}

TEST(StatementMonteCarlo, ManySourcesKeepTheStudentIntervalAndAFitOfThreeDofWidensIt) {
  // The paper's 64 sources, noise-free: their sum is near normal, ν_eff = ∞, and every Student-t interval holds
  // (K0's ends differ by up to 2 standard errors of the Monte Carlo's: not a verdict against the LPU). u(y) is
  // u_c to 1 % (its sample scatters by ~0.3 % at M = 10⁵).
  const Config quiet = parse_config(read_text(kPaperConfigPath), "paper.toml");
  const verbs::CalibrationStatement s =
      verbs::calibration_statement(quiet, verbs::simulate(quiet).identification, trials(100000), "statement");
  for (const CoefficientStatement& c : s.coefficients) {
    SCOPED_TRACE(c.input.coefficient);
    ASSERT_TRUE(c.monte_carlo);
    EXPECT_EQ(c.method, IntervalMethod::student_t) << c.monte_carlo->d_low << " " << c.monte_carlo->d_high
                                                   << " > " << c.monte_carlo->validation_delta;
    EXPECT_NEAR(c.low, c.corrected - c.expanded, 1e-12 * c.expanded);
    EXPECT_NEAR(c.monte_carlo->std_dev, c.combined, 1e-2 * c.combined);
  }
  for (const CoefficientStatement& o : s.outputs) EXPECT_TRUE(o.monte_carlo) << o.input.coefficient;

  // With noise, 6 runs and 3 terms leave the fit ν_A = 3: Welch–Satterthwaite gives K2 ν_eff ≈ 98 and k ≈ 1.98,
  // but its Type A part is a t with 3 degrees of freedom, whose tails widen the 95 % interval by ~10 %, many
  // standard errors beyond δ: the Monte Carlo's interval is stated, wider than the Student-t one.
  const Config noisy = parse_config(
      edited(read_text(kPaperConfigPath), "noise_density = \"0 deg/s/rtHz\"", "noise_density = \"0.05 deg/s/rtHz\""),
      "noisy-paper.toml");
  // (Stated with the quiet set-up, whose Type A part is the fit's scatter: the noisy one's would be its noise
  // model, ν = ∞.)
  const verbs::CalibrationStatement n =
      verbs::calibration_statement(quiet, verbs::simulate(noisy).identification, trials(100000), "statement");
  const CoefficientStatement& k2 = n.coefficients[1];
  ASSERT_EQ(k2.input.coefficient, "K2");
  ASSERT_EQ(k2.input.type_a.dof, 3.0);
  ASSERT_GT(k2.effective_dof, 50.0);
  EXPECT_EQ(k2.method, IntervalMethod::monte_carlo);
  EXPECT_GT(k2.expanded, 1.05 * k2.monte_carlo->lpu_expanded);
  EXPECT_GT(validation_diagnosis(*k2.monte_carlo, n.monte_carlo_trials).excess_in_std_errors, 5.0);
}

TEST(StatementMonteCarlo, TheSameSeedGivesTheSameNumbersOnAnyThreadsAndNoTrialsNoCheck) {
  const Config config = paper_with("dR_s = { bound = \"25 um\", distribution = \"uniform\" }\n"
                                   "dthz5 = { bound = \"2e-5 rad\", distribution = \"arcsine\" }",
                                   "0.05 deg/s/rtHz");
  const verbs::SimulateResult sim = verbs::simulate(config);
  const verbs::CalibrationStatement one =
      verbs::calibration_statement(config, sim.identification, trials(20000, 1), "statement");
  const verbs::CalibrationStatement two =
      verbs::calibration_statement(config, sim.identification, trials(20000, 2), "statement");
  for (std::size_t k = 0; k < one.coefficients.size(); ++k) {
    EXPECT_EQ(one.coefficients[k].low, two.coefficients[k].low);
    EXPECT_EQ(one.coefficients[k].monte_carlo->std_dev, two.coefficients[k].monte_carlo->std_dev);
  }
  const verbs::CalibrationStatement none =
      verbs::calibration_statement(config, sim.identification, trials(0), "statement");
  EXPECT_EQ(none.monte_carlo_trials, 0u);
  for (const CoefficientStatement& c : none.coefficients) {
    EXPECT_FALSE(c.monte_carlo);
    EXPECT_EQ(c.method, IntervalMethod::student_t);
  }
}

TEST(StatementMonteCarlo, TooFewTrialsForTheIntervalAreRefusedNamingTheOption) {
  const Config config = paper_with("dR_s = \"25 um\"", "0.05 deg/s/rtHz");
  const verbs::SimulateResult sim = verbs::simulate(config);
  try {
    verbs::calibration_statement(config, sim.identification, trials(5), "statement");
    FAIL() << "5 trials accepted for a 95 % interval";
  } catch (const OptionError& e) {
    EXPECT_NE(std::string(e.what()).find("statement_trials"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ccal::test
