// `ccal design`'s "Expected if run as written" (verbs/design.hpp, expected_statement): the U the calibration
// statement gives when the designed plan is run as written. The lab example (encoders declared) is designed, its
// designed plan run as logs on the machine of examples/lab_truth.toml with the instrument's noise, and reduced
// with the statement: the expected U of every coefficient must be within 10 % of the stated one (the stated U
// scatters with the residual check and the logs' noise only through the Type A part's excess, which is none
// here, so the agreement is in fact far closer). And the statement's method is the one the expectation uses:
// the expected statement of a plan equals the statement of its noise-free simulation with the inputs the
// encoders will measure.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/intake/measured_inputs.hpp"
#include "ccal/intake/run_log_writer.hpp"
#include "ccal/io/truth_file.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/design.hpp"
#include "ccal/verbs/reduce.hpp"
#include "ccal/verbs/simulate.hpp"
#include "ccal/verbs/statement.hpp"

namespace ccal::test {
namespace {

namespace fs = std::filesystem;

const std::string kLabPath = CCAL_SOURCE_DIR + "/examples/lab.toml";
const std::string kLabTruthPath = CCAL_SOURCE_DIR + "/examples/lab_truth.toml";

TEST(DesignExpected, TheDesignedPlansExpectedUIsWhatItsStatementGives) {
  const Config lab = load_config(kLabPath);
  ASSERT_TRUE(lab.centrifuge.encoders.main && lab.centrifuge.encoders.platform);
  verbs::DesignOptions o;
  o.verify_trials = 0;
  const verbs::DesignResult d = verbs::design(lab, o);
  ASSERT_TRUE(d.expected_after.has_value());
  // The inputs the encoders will measure are credited: domega, dOmega and both drives' first ripple harmonics.
  int credited = 0;
  for (const verbs::StatementSource& s : d.expected_after->inputs) credited += s.measured;
  EXPECT_EQ(credited, 6);

  const fs::path dir = fs::temp_directory_path() / ("ccal-design-expected-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  verbs::SimulateOptions so;
  so.truth = load_truth(kLabTruthPath, d.designed);
  const verbs::SimulateResult sim = verbs::simulate(d.designed, so);
  const Eigen::VectorXd& means = sim.observations.output;
  const auto logs = write_run_logs(d.designed, sim.machine_errors,
                                   std::vector<double>(means.data(), means.data() + means.size()),
                                   default_log_step(d.designed));
  verbs::ReduceOptions ro;
  for (std::size_t r = 0; r < logs.size(); ++r) {
    std::ofstream(dir / logs[r].name) << logs[r].text;
    ro.logs.push_back({d.designed.plan.runs[r].name, (dir / logs[r].name).string()});
  }
  ro.statement = true;
  ro.statement_options.statement_trials = 0;
  const verbs::ReduceResult reduced = verbs::reduce(d.designed, ro);
  fs::remove_all(dir);
  ASSERT_TRUE(reduced.statement.has_value());
  ASSERT_EQ(reduced.statement->coefficients.size(), d.expected_after->coefficients.size());
  for (std::size_t k = 0; k < reduced.statement->coefficients.size(); ++k) {
    const CoefficientStatement &stated = reduced.statement->coefficients[k], &expected = d.expected_after->coefficients[k];
    SCOPED_TRACE(stated.input.coefficient);
    EXPECT_EQ(stated.input.coefficient, expected.input.coefficient);
    EXPECT_NEAR(expected.expanded, stated.expanded, 0.1 * stated.expanded);
  }
}

TEST(DesignExpected, WithoutEncodersNothingIsCreditedAndTheTypeAIsTheNoiseModels) {
  // The bundled example declares no encoders: every input at its tolerance. It states no instrument noise, so its
  // Type A part is the drives' rate noise alone and the expected statement's u_c is the budget's u (1e-9: the
  // fit's regressors against the budget's own, both of the same plan).
  const Config config = bundled_example();
  EXPECT_TRUE(expected_measured_inputs(config).empty());
  const verbs::CalibrationStatement st = verbs::expected_statement(config, 0.95);
  for (const verbs::StatementSource& s : st.inputs) EXPECT_FALSE(s.measured) << s.id;
  EXPECT_TRUE(st.type_a.from_noise_model);
  const verbs::BudgetResult b = verbs::budget(config);
  for (std::size_t k = 0; k < st.coefficients.size(); ++k) {
    const double u = b.budget.standard_uncertainty[Eigen::Index(k)] * b.budget.display_scale[k];
    EXPECT_NEAR(st.coefficients[k].combined, u, 1e-9 * u) << st.coefficients[k].input.coefficient;
  }
}

}  // namespace
}  // namespace ccal::test
