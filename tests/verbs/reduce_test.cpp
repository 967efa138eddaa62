// verbs::reduce in-process (docs/model.md §13): logs written from the model (intake/run_log_writer.hpp: the
// simulated run means and the encoders of the drives' configured rate errors), reduced and identified, give
// the coefficients verbs::simulate identifies from the same model; the encoders' rate and mismatch are the
// configured Δω and ΔΩ; with `statement` the statement is verbs::calibration_statement of that
// identification; too few logs, a run logged twice or unknown, and a pulse weight that is not positive are
// refused naming their field.
#include "ccal/verbs/reduce.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/intake/measured_inputs.hpp"
#include "ccal/intake/run_log_writer.hpp"
#include "ccal/model/plan.hpp"
#include "ccal/verbs/simulate.hpp"
#include "ccal/verbs/statement.hpp"
#include "simulated_logs.hpp"
#include "verbs_support.hpp"

namespace ccal::test {
namespace {

// The bundled example with known, compensated errors and its logs (simulated_logs.hpp).
class ReduceVerb : public SimulatedLogs {
 protected:
  ReduceVerb() : SimulatedLogs("ccal-reduce-verb") {}
};

TEST_F(ReduceVerb, LogsOfTheModelGiveTheSimulatedIdentification) {
  const verbs::ReduceResult r = verbs::reduce(config_, options_);
  ASSERT_EQ(r.logs.runs.size(), config_.plan.runs.size());
  // The encoders' line fits give the configured drive errors: Ω + Δω with Δω = 2e-6 rad/s and ΔΩ = −1e-6
  // rad/s, to 1e-12 rad/s (angles of 17 digits, ~1e-13 rad, over 450 s of samples).
  for (const LoggedRun& run : r.logs.runs) {
    EXPECT_NEAR(run.rate - run.planned_rate, 2e-6, 1e-12) << run.index;
    EXPECT_NEAR(run.mismatch, -1e-6, 1e-12) << run.index;
  }
  // The model of each run is then the simulated one up to the line fits' round-off (~1e-13 rad in the
  // phases), and the run means are the simulated ones written with 17 digits: the same coefficients to
  // 1e-9 of their values (K3's effect is ~1e-5 of the outputs).
  const FitResult& fit = r.identification.id.fit;
  ASSERT_EQ(fit.names, sim_.identification.fit.names);
  for (Eigen::Index k = 0; k < fit.value.size(); ++k) {
    const double expected = sim_.identification.fit.value[k];
    EXPECT_NEAR(fit.value[k], expected, 1e-9 * std::abs(expected)) << fit.names[std::size_t(k)];
  }
  EXPECT_FALSE(r.statement.has_value());
}

TEST_F(ReduceVerb, StatementIsThatOfTheIdentificationWithTheBudget) {
  verbs::ReduceOptions o = options_;
  o.statement = true;
  o.statement_options.coverage_probability = 0.9;
  const verbs::ReduceResult r = verbs::reduce(config_, o);
  ASSERT_TRUE(r.statement.has_value());
  verbs::StatementOptions so;
  so.coverage_probability = 0.9;
  // With what the logs measured (the encoders: the drives' rates and ripple) and the logged spans.
  std::vector<double> durations;
  for (const LoggedRun& lr : r.logs.runs) durations.push_back(lr.log.duration);
  const verbs::CalibrationStatement s = verbs::calibration_statement(
      config_, r.identification.id, so, "statement", measured_inputs(config_, r.logs), durations);
  ASSERT_EQ(r.statement->coefficients.size(), s.coefficients.size());
  for (std::size_t k = 0; k < s.coefficients.size(); ++k) {
    EXPECT_EQ(r.statement->coefficients[k].expanded, s.coefficients[k].expanded) << k;
    EXPECT_EQ(r.statement->coefficients[k].corrected, s.coefficients[k].corrected) << k;
  }
}

TEST_F(ReduceVerb, TooFewOrRepeatedLogsAreRefusedNamingTheOption) {
  // OptionErrors naming the field `logs` (the command line words it --log, Python logs).
  auto message = [&](const verbs::ReduceOptions& o) -> std::string {
    try {
      verbs::reduce(config_, o);
    } catch (const OptionError& e) {
      return e.field() == "logs" ? e.what() : "another field: " + e.field();
    }
    return "no error";
  };
  verbs::ReduceOptions few, twice = options_, unknown = options_, weight = options_;
  few.logs = {options_.logs[0], options_.logs[1]};  // 2 logs for 3 free terms
  twice.logs[1].run = twice.logs[0].run;
  unknown.logs[0].run = "21g";
  EXPECT_EQ(message(few),
            "logs: 2 logged run(s) cannot determine 3 free terms (K0, K2, K3); accepted: at least 3 "
            "logs, of runs at different g-levels");
  EXPECT_EQ(message(twice),
            "logs: run '" + twice.logs[0].run + "' is logged twice; accepted: one log per run");
  EXPECT_EQ(message(unknown).rfind("logs: '21g' is no run; accepted: a run name (", 0), 0u)
      << message(unknown);
  // One file given for two runs (the same bytes): one mean at two g-levels would make a curvature (K3 = 10.6
  // for 0.003 on examples/lab.toml), so it is refused, naming both runs and both files.
  verbs::ReduceOptions same = options_;
  same.logs[1].path = same.logs[0].path;
  const std::string repeated = message(same);
  EXPECT_EQ(repeated.rfind("logs: run '" + same.logs[1].run + "' has the same log as run '" + same.logs[0].run +
                               "' (",
                           0),
            0u)
      << repeated;
  EXPECT_NE(repeated.find("accepted: each run's own log"), std::string::npos) << repeated;
  // The pulse weight: positive, in the output unit × s.
  weight.pulse_weight = -1.0;
  try {
    verbs::reduce(config_, weight);
    ADD_FAILURE() << "a negative pulse weight was accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(std::string(e.what()),
              "pulse_weight: -1 is not a positive weight; accepted: the integrated output per pulse, a "
              "positive number in deg/s·s or with a unit of that kind, e.g. 2.5e-5");
  }
}

TEST_F(ReduceVerb, ALogShorterThanItsRunIsReported) {
  // The first run's log cut after its first half (rows by time): reduced over the span logged, and reported,
  // with the span and the planned duration; the whole logs give no such warning.
  auto short_warnings = [](const verbs::ReduceResult& r) {
    return std::count_if(r.warnings.begin(), r.warnings.end(),
                         [](const std::string& w) { return w.find("of the planned") != std::string::npos; });
  };
  EXPECT_EQ(short_warnings(verbs::reduce(config_, options_)), 0);
  std::ifstream in(options_.logs[0].path);
  std::string line, kept;
  const double planned = config_.plan.runs[0].duration;
  while (std::getline(in, line)) {
    const bool data = !line.empty() && (std::isdigit(static_cast<unsigned char>(line[0])) != 0);
    if (data && std::stod(line.substr(0, line.find(','))) > planned / 2) break;
    kept += line + "\n";
  }
  in.close();
  std::ofstream(options_.logs[0].path) << kept;
  const verbs::ReduceResult r = verbs::reduce(config_, options_);
  ASSERT_EQ(short_warnings(r), 1);
  const std::string expected = fmt::format("run '{}': the log spans ", config_.plan.runs[0].name);
  const auto w = std::find_if(r.warnings.begin(), r.warnings.end(),
                              [](const std::string& x) { return x.find("of the planned") != std::string::npos; });
  EXPECT_EQ(w->rfind(expected, 0), 0u) << *w;
  EXPECT_NE(w->find(fmt::format("of the planned {:.6g} s", planned)), std::string::npos) << *w;
}

TEST_F(ReduceVerb, PulseWeightFromTextTakesTheOutputUnitTimesSeconds) {
  // The example's output is in deg/s: a bare number is in deg, a quantity is converted to deg (3.6 arcsec =
  // 1e-3 deg, to rounding), and a unit of another dimension names the option, the unit and the accepted ones.
  EXPECT_EQ(verbs::pulse_weight_from_text(config_, "2.5e-5"), 2.5e-5);
  EXPECT_NEAR(verbs::pulse_weight_from_text(config_, "3.6 arcsec"), 1e-3, 1e-18);
  try {
    verbs::pulse_weight_from_text(config_, "1 m");
    ADD_FAILURE() << "a length taken as a pulse weight";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "pulse_weight");
    EXPECT_EQ(std::string(e.what()).rfind("pulse_weight: '1 m': unit 'm' is a length, expected an angle "
                                          "(accepted: rad,",
                                          0),
              0u)
        << e.what();
  }
}

}  // namespace
}  // namespace ccal::test
