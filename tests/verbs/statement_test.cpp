// verbs::calibration_statement in-process (JCGM 100 §7, docs/model.md §10.5): the statement of a simulated
// identification against its parts computed by the other library functions — the fit's standard errors
// (Type A, ν = runs − free terms), verbs::budget's u (Type B, of a configuration without rate noise), u_c² =
// u_A² + u_B², Welch–Satterthwaite, Student's k, U = k u_c; the correction for known errors the model leaves
// out (minus known_error_shift); and its refusals naming the option.
#include "ccal/uncertainty/statement.hpp"

#include <gtest/gtest.h>

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

TEST(StatementVerb, EachPartIsWhatTheOtherVerbsGive) {
  const Config config = noisy_paper(false);
  const verbs::SimulateResult sim = verbs::simulate(config);
  const verbs::BudgetResult budget = verbs::budget(config);
  ASSERT_TRUE(budget.budget.rate_noise.empty()) << "the paper's set-up has no rate noise";
  verbs::StatementOptions o;
  o.coverage_probability = 0.9;
  const verbs::CalibrationStatement s =
      verbs::calibration_statement(config, sim.identification, o, "statement");
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
  }
}

TEST(StatementVerb, KnownErrorsTheModelLeavesOutAreCorrected) {
  // correction b = −(the shift of the known errors), in the fit's unit; the corrected estimate K̂ + b.
  const Config config = noisy_paper(true);
  const verbs::SimulateResult sim = verbs::simulate(config);
  const verbs::CalibrationStatement s =
      verbs::calibration_statement(config, sim.identification, {}, "statement");
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
