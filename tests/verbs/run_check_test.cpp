// Each logged run's mean against the nominal instrument's reading at that run (src/verbs/run_check.hpp): the
// model's own logs read as the nominal instrument does; two runs' means swapped are each well beyond
// kRunCheckLimit u, and each finding names the run the mean belongs to; reduce warns, and with strict_runs
// refuses, naming the option's place and both runs.
#include "../../src/verbs/run_check.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/core/units.hpp"
#include "ccal/verbs/reduce.hpp"
#include "simulated_logs.hpp"

namespace ccal::test {
namespace {

// The bundled example with its known errors compensated, simulated, its logs written with their pulse (or
// output) column only: no encoder to tell one run's log from another's (simulated_logs.hpp).
class RunCheckVerb : public SimulatedLogs {
 protected:
  RunCheckVerb() : SimulatedLogs("ccal-run-check", 2) {}
  static long nominal_warnings(const verbs::ReduceResult& r) {
    return std::count_if(r.warnings.begin(), r.warnings.end(),
                         [](const std::string& w) { return w.find("nominal instrument") != std::string::npos; });
  }
};

TEST_F(RunCheckVerb, TheModelsOwnLogsReadAsTheNominalInstrument) {
  const verbs::ReduceResult r = verbs::reduce(config_, options_);
  EXPECT_EQ(nominal_warnings(r), 0);
  const std::vector<verbs::RunCheck> checks = verbs::check_runs(config_, r.logs, r.mode);
  ASSERT_EQ(checks.size(), config_.plan.runs.size());
  const double unit = output_unit_si(config_.instrument.output_unit);
  for (const verbs::RunCheck& c : checks) {
    // The nominal reading is the simulation's run mean (its truth is the configured errors and terms), to the
    // logs' 17 digits; the logged mean is that of the pulses written from it (a quantum of 1e-10 of it).
    EXPECT_NEAR(c.nominal, sim_.observations.output[Eigen::Index(c.index)] / unit, 1e-12 * std::abs(c.nominal));
    EXPECT_TRUE(c.logged);
    EXPECT_GT(c.u, 0);  // the tolerances' effect on the run's mean (the example's instrument has no noise)
    EXPECT_LT(std::abs(c.mean - c.nominal), c.u) << c.index;
    EXPECT_FALSE(c.beyond);
  }
}

TEST_F(RunCheckVerb, TwoSwappedLogsAreEachFoundAndNamed) {
  std::swap(options_.logs[0].path, options_.logs[1].path);
  const verbs::ReduceResult r = verbs::reduce(config_, options_);
  ASSERT_EQ(nominal_warnings(r), 2);
  const std::string &a = config_.plan.runs[0].name, &b = config_.plan.runs[1].name;
  const auto warning_of = [&](const std::string& run) {
    return *std::find_if(r.warnings.begin(), r.warnings.end(),
                         [&](const std::string& w) { return w.starts_with("run '" + run + "': the log's mean"); });
  };
  EXPECT_NE(warning_of(a).find("it is what run '" + b + "' reads"), std::string::npos) << warning_of(a);
  EXPECT_NE(warning_of(b).find("it is what run '" + a + "' reads"), std::string::npos) << warning_of(b);
  const std::vector<verbs::RunCheck> checks = verbs::check_runs(config_, r.logs, r.mode);
  // 5 g against 10 g: 72 u off on this example, whose 10 ppm rate-ripple tolerance dominates u (a pulse log
  // has no encoder to measure the ripple).
  EXPECT_GT(std::abs(checks[0].mean - checks[0].nominal), 5 * verbs::kRunCheckLimit * checks[0].u);
  EXPECT_TRUE(checks[0].beyond && checks[1].beyond);
  // With strict_runs: refused, naming the option's place (the logs), the first run and the other.
  verbs::ReduceOptions strict = options_;
  strict.strict_runs = true;
  try {
    verbs::reduce(config_, strict);
    FAIL() << "swapped logs accepted with strict_runs";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "logs");
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("logs: run '" + a + "': the log's mean", 0), 0u) << what;
    EXPECT_NE(what.find("; so are runs '" + b + "'"), std::string::npos) << what;
    EXPECT_NE(what.find("accepted: each run's own log"), std::string::npos) << what;
  }
}

// The limit has one home, kRunCheckLimit: the strict_runs option's help (the program's --strict-runs, Python's
// strict_runs) is written from it.
TEST(RunCheckLimit, TheStrictRunsHelpStatesTheConstant) {
  const OptionTable<verbs::ReduceOptions> table = option_table<verbs::ReduceOptions>();
  const auto row = std::find_if(table.begin(), table.end(), [](const auto& r) { return r.field == "strict_runs"; });
  ASSERT_NE(row, table.end());
  EXPECT_EQ(std::string(row->help),
            fmt::format("Refuse a run whose log's mean is more than {:g} standard uncertainties from what the "
                        "nominal instrument reads at that run (a swapped or mislabelled log), instead of warning",
                        verbs::kRunCheckLimit));
}

}  // namespace
}  // namespace ccal::test
