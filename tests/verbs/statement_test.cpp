// verbs::calibration_statement in-process (JCGM 100 §7, docs/model.md §10.5): the statement of a simulated
// identification against its parts computed by the other library functions — the fit's standard errors
// (Type A of a configuration that states no noise, ν = runs − free terms), verbs::budget's u (Type B, of a configuration without rate noise), u_c² =
// u_A² + u_B², Welch–Satterthwaite, Student's k, U = k u_c; the correction for known errors the model leaves
// out (minus known_error_shift); and its refusals naming the option.
#include "ccal/uncertainty/statement.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/simulate.hpp"
#include "ccal/verbs/statement.hpp"
#include "verbs_support.hpp"

namespace ccal::test {
namespace {

// The paper's set-up with a noisy instrument (so that the fit has a Type A part), and optionally a known
// azimuth zero error that the model leaves out.
Config noisy_paper(bool known_error) {
  std::string text = edited(read_text(kPaperConfigPath), "noise_density = \"0 deg/s/rtHz\"",
                            "noise_density = \"0.05 deg/s/rtHz\"");
  if (known_error) text = edited(text, "[errors]\n", "[errors]\ndthz5 = \"2 arcsec\"\n");
  return parse_config(text, "noisy-paper.toml");
}

// The same set-up stating no noise, for the statement of noisy_paper's observations: its Type A part is then
// the fit's scatter (ν = n − p), the scheme these tests check (the noise model's: statement_type_a_test.cpp).
Config scatter_only(bool known_error) {
  std::string text = read_text(kPaperConfigPath);
  if (known_error) text = edited(text, "[errors]\n", "[errors]\ndthz5 = \"2 arcsec\"\n");
  return parse_config(text, "paper.toml");
}

// The statement without its Monte Carlo check: the Student-t intervals as they are (the check is
// statement_montecarlo_test's).
verbs::StatementOptions no_check() {
  verbs::StatementOptions o;
  o.statement_trials = 0;
  return o;
}

TEST(StatementVerb, EachPartIsWhatTheOtherVerbsGive) {
  const Config config = noisy_paper(false);
  const verbs::SimulateResult sim = verbs::simulate(config);
  const verbs::BudgetResult budget = verbs::budget(config);
  ASSERT_TRUE(budget.budget.rate_noise.empty()) << "the paper's set-up has no rate noise";
  verbs::StatementOptions o;
  o.coverage_probability = 0.9;
  o.statement_trials = 0;  // the Student-t interval as it is (the Monte Carlo check: statement_montecarlo_test)
  const verbs::CalibrationStatement s =
      verbs::calibration_statement(scatter_only(false), sim.identification, o, "statement");
  EXPECT_FALSE(s.type_a.from_noise_model);
  EXPECT_EQ(s.coverage_probability, 0.9);
  EXPECT_EQ(s.known_errors, 0);
  ASSERT_EQ(s.coefficients.size(), budget.budget.coefficients.size());
  const double nu_a = double(config.plan.runs.size() - config.identification.free_terms.size());
  for (std::size_t k = 0; k < s.coefficients.size(); ++k) {
    const CoefficientStatement& c = s.coefficients[k];
    const Eigen::Index i = Eigen::Index(k);
    SCOPED_TRACE(c.input.coefficient);
    EXPECT_EQ(c.input.coefficient, budget.budget.coefficients[k]);
    EXPECT_EQ(c.input.estimate, sim.identification.fit.value[i]);
    EXPECT_EQ(c.input.correction, 0.0);
    EXPECT_EQ(c.input.type_a.u, sim.identification.fit.std_error[i]);
    EXPECT_EQ(c.input.type_a.dof, nu_a);
    // Type B: the budget's u in the fit's unit (SI × display scale), 1e-12 relative (one product).
    const double u_b = budget.budget.standard_uncertainty[i] * budget.budget.display_scale[k];
    EXPECT_NEAR(c.input.type_b.u, u_b, 1e-12 * u_b);
    EXPECT_TRUE(std::isinf(c.input.type_b.dof));
    const double u_a = c.input.type_a.u, u_c = std::hypot(u_a, u_b);
    EXPECT_NEAR(c.combined, u_c, 1e-12 * u_c);
    // ν_eff = u_c⁴ / (u_A⁴/ν_A) (Type B has ν = ∞), k = t_p(⌊ν_eff⌋): 1e-9 relative (fourth powers).
    const double nu = std::pow(u_c, 4) / (std::pow(u_a, 4) / nu_a);
    EXPECT_NEAR(c.effective_dof, nu, 1e-9 * nu);
    EXPECT_NEAR(c.coverage_factor, student_coverage_factor(0.9, std::floor(nu)), 1e-12);
    EXPECT_NEAR(c.expanded, c.coverage_factor * u_c, 1e-12 * c.expanded);
    EXPECT_NEAR(c.low, c.corrected - c.expanded, 1e-12 * c.expanded);
    EXPECT_NEAR(c.high, c.corrected + c.expanded, 1e-12 * c.expanded);
    EXPECT_EQ(c.method, IntervalMethod::student_t);
    EXPECT_FALSE(c.monte_carlo);
  }
  EXPECT_EQ(s.monte_carlo_trials, 0u);
}

TEST(StatementVerb, KnownErrorsTheModelLeavesOutAreCorrected) {
  // correction b = −(the shift of the known errors), in the fit's unit; the corrected estimate K̂ + b.
  const Config config = noisy_paper(true);
  const verbs::SimulateResult sim = verbs::simulate(config);
  const verbs::CalibrationStatement s =
      verbs::calibration_statement(config, sim.identification, no_check(), "statement");
  EXPECT_EQ(s.known_errors, 1);
  EXPECT_FALSE(s.compensated);
  const Eigen::VectorXd shift = known_error_shift(config, config.mode);
  for (std::size_t k = 0; k < s.coefficients.size(); ++k) {
    const CoefficientStatement& c = s.coefficients[k];
    const double b = -shift[Eigen::Index(k)] / sim.output_unit_si;
    SCOPED_TRACE(c.input.coefficient);
    EXPECT_NE(b, 0.0);
    EXPECT_NEAR(c.input.correction, b, 1e-12 * std::abs(b));
    EXPECT_NEAR(c.corrected, c.input.estimate + b, 1e-12 * std::abs(c.corrected));
  }
}

TEST(StatementVerb, TheCovarianceIsTheFitsPlusTheBudgetsAndItsDiagonalIsTheSquaredUc) {
  // Type A: the fit's covariance, as it is. Type B: the budget's coefficient covariance (Σ_groups g gᵀ, SI)
  // in the fit's units, an independent product of the same effects: 1e-12 relative to u_i u_j. The sum is
  // symmetric, positive semi-definite (eigenvalues ≥ −1e-12 of the largest: round-off of a 3×3 sum) and its
  // diagonal is u_c² (1e-12 relative: u_c is a hypot of the same parts).
  const Config config = noisy_paper(true);
  const verbs::SimulateResult sim = verbs::simulate(config);
  const verbs::BudgetResult budget = verbs::budget(config);
  const verbs::CalibrationStatement s =
      verbs::calibration_statement(scatter_only(true), sim.identification, no_check(), "statement");
  const Eigen::Index n = Eigen::Index(s.coefficients.size());
  ASSERT_EQ(s.covariance.rows(), n);
  ASSERT_EQ(s.covariance.cols(), n);
  EXPECT_EQ(s.covariance_a, sim.identification.fit.covariance);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      const double scale = budget.budget.display_scale[std::size_t(i)] * budget.budget.display_scale[std::size_t(j)];
      const double u_ij = s.coefficients[std::size_t(i)].combined * s.coefficients[std::size_t(j)].combined;
      EXPECT_NEAR(s.covariance_b(i, j), budget.budget.covariance(i, j) * scale, 1e-12 * u_ij) << i << "," << j;
      EXPECT_EQ(s.covariance(i, j), s.covariance(j, i));
      EXPECT_NEAR(s.correlation(i, j), s.covariance(i, j) / u_ij, 1e-15);
    }
  for (Eigen::Index i = 0; i < n; ++i) {
    const double u_c = s.coefficients[std::size_t(i)].combined;
    EXPECT_NEAR(s.covariance(i, i), u_c * u_c, 1e-12 * u_c * u_c);
    EXPECT_DOUBLE_EQ(s.correlation(i, i), 1.0);
  }
  const Eigen::VectorXd eigen = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(s.covariance).eigenvalues();
  EXPECT_GE(eigen.minCoeff(), -1e-12 * eigen.maxCoeff());
  // The correlation is not the identity: K2 and K3 share tolerances and the fit couples them.
  EXPECT_GT(std::abs(s.correlation(1, 2)), 0.1);
}

TEST(StatementVerb, TheModelledOutputOfEachRunIsStatedFromTheCovariance) {
  // ŷ_r is the fit's modelled output of the run (the observed output less the residual); its u_c² = Σ h_i h_j
  // ρ_ij u_i u_j, summed here from the per-coefficient u_c and the correlation (another path than hᵀ C h): 1e-10
  // relative (cancellation in a sum of signed terms); the correction hᵀb; ν_A the fit's; k and U as for a
  // coefficient.
  const Config config = noisy_paper(true);
  const verbs::SimulateResult sim = verbs::simulate(config);
  const verbs::CalibrationStatement s = verbs::calibration_statement(config, sim.identification, no_check(), "statement");
  const verbs::Identification& id = sim.identification;
  ASSERT_EQ(s.outputs.size(), config.plan.runs.size());
  ASSERT_EQ(s.g_levels.size(), config.plan.runs.size());
  for (std::size_t r = 0; r < s.outputs.size(); ++r) {
    const CoefficientStatement& o = s.outputs[r];
    SCOPED_TRACE(o.input.coefficient);
    EXPECT_EQ(o.input.coefficient, config.plan.runs[r].name);
    EXPECT_EQ(s.g_levels[r], config.plan.runs[r].g_level);
    const Eigen::Index row = Eigen::Index(r);
    double var = 0, b = 0;
    for (std::size_t i = 0; i < s.coefficients.size(); ++i) {
      b += id.design(row, Eigen::Index(i)) * s.coefficients[i].input.correction;
      for (std::size_t j = 0; j < s.coefficients.size(); ++j)
        var += id.design(row, Eigen::Index(i)) * id.design(row, Eigen::Index(j)) *
               s.correlation(Eigen::Index(i), Eigen::Index(j)) * s.coefficients[i].combined *
               s.coefficients[j].combined;
    }
    EXPECT_NEAR(o.combined, std::sqrt(var), 1e-10 * std::sqrt(var));
    EXPECT_NEAR(o.input.correction, b, 1e-12 * std::abs(b) + 1e-300);
    EXPECT_EQ(o.input.type_a.dof, s.coefficients.front().input.type_a.dof);
    EXPECT_NEAR(o.expanded, o.coverage_factor * o.combined, 1e-12 * o.expanded);
    EXPECT_EQ(o.input.unit, id.residual_unit);
    EXPECT_EQ(o.input.estimate, id.modelled[row]);
  }
}

TEST(StatementVerb, RefusalsNameTheOption) {
  const Config config = noisy_paper(false);
  const verbs::SimulateResult sim = verbs::simulate(config);
  auto message = [&](const Config& budget_config, double p) -> std::string {
    verbs::StatementOptions o;
    o.coverage_probability = p;
    try {
      verbs::calibration_statement(budget_config, sim.identification, o, "statement");
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(message(config, 1.0).rfind("coverage_probability: 1 ", 0), 0u) << message(config, 1.0);
  // A budget whose free terms are not the fit's.
  Config other = config;
  other.identification.free_terms = {"K0", "K2"};
  EXPECT_EQ(message(other, 0.95).rfind("statement: the fit's free terms (K0, K2, K3) are not those of ", 0), 0u)
      << message(other, 0.95);
}

}  // namespace
}  // namespace ccal::test
