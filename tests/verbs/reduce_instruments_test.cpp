// A test of two instruments (examples/two_instruments.toml, the machine of examples/lab_truth.toml) logged in one
// folder, each instrument's pulses in a column of its own: `reduce` gives each instrument's own identification and
// statement, the same as a reduction of that instrument alone, and the covariance of their coefficients.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "ccal/io/config_file.hpp"
#include "ccal/intake/log_manifest.hpp"
#include "ccal/intake/run_log_writer.hpp"
#include "ccal/io/truth_file.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/force.hpp"
#include "ccal/verbs/montecarlo.hpp"
#include "ccal/verbs/reduce.hpp"
#include "ccal/verbs/simulate.hpp"
#include "test_paths.hpp"

namespace ccal::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

class ReduceInstruments : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ccal-reduce-instruments-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    config_ = load_config(source_dir() + "/examples/two_instruments.toml");
    // Each instrument simulated on the same machine: the same time and encoder columns, its own pulses.
    std::vector<std::vector<RunLogFile>> logs;
    for (const Config& one : config_.instruments) {
      verbs::SimulateOptions so;
      so.truth = load_truth(source_dir() + "/examples/lab_truth.toml", one);
      const verbs::SimulateResult sim = verbs::simulate(one, so);
      LogLayout layout;
      layout.columns.pulses = "count_" + one.instrument_id;
      const Eigen::VectorXd& means = sim.observations.output;
      logs.push_back(write_run_logs(sim.config, sim.machine_errors, {means.data(), means.data() + means.size()},
                                    default_log_step(one), layout));
    }
    // One file per run: A's, with B's count column (the second) added at the end.
    std::string manifest = "[instruments]\nA = { pulses = \"count_A\" }\nB = { pulses = \"count_B\" }\n[runs]\n";
    for (std::size_t r = 0; r < logs[0].size(); ++r) {
      const auto a = lines_of(logs[0][r].text), b = lines_of(logs[1][r].text);
      ASSERT_EQ(a.size(), b.size());
      std::ofstream out(dir_ / logs[0][r].name);
      for (std::size_t i = 0; i < a.size(); ++i) {
        const std::size_t first = b[i].find(','), second = b[i].find(',', first + 1);
        out << a[i] << ',' << b[i].substr(first + 1, second - first - 1) << '\n';
      }
      manifest += config_.plan.runs[r].name + " = \"" + logs[0][r].name + "\"\n";
    }
    std::ofstream(dir_ / kLogManifestName) << manifest;
  }
  void TearDown() override { fs::remove_all(dir_); }

  verbs::ReduceOptions options(bool statement) const {
    const LogManifest m = read_log_manifest(dir_);
    verbs::ReduceOptions o;
    o.layout = m.layout;
    o.logs = verbs::manifest_logs(m);
    o.statement = statement;
    if (statement) o.statement_options.statement_trials = 2000;  // a statement's option: refused without one
    return o;
  }

  fs::path dir_;
  Config config_;
};

// Each instrument's statement holds its own true coefficients (its [[instruments]] terms; the machine's errors
// are the truth's, which the statement charges): |y − K| ≤ U at p = 95 %, for every coefficient of both.
TEST_F(ReduceInstruments, EachInstrumentsStatementHoldsItsOwnCoefficients) {
  const verbs::ReduceResult r = verbs::reduce(config_, options(true));
  ASSERT_EQ(r.instruments.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const verbs::ReduceResult& one = r.instruments[k];
    EXPECT_EQ(one.config.instrument_id, config_.instruments[k].instrument_id);
    ASSERT_TRUE(one.statement.has_value());
    for (const CoefficientStatement& s : one.statement->coefficients) {
      const double truth = *config_.instruments[k].instrument.coefficient(s.input.coefficient) /
                           (std::numbers::pi / 180);  // deg/s/gⁿ, the statement's unit
      SCOPED_TRACE(one.config.instrument_id + " " + s.input.coefficient);
      EXPECT_LE(std::abs(s.corrected - truth), s.expanded) << s.corrected << " vs " << truth;
    }
  }
  // The two sets of coefficients differ (B is not A), and the covariance holds both.
  EXPECT_NE(r.instruments[0].identification.id.fit.value[0], r.instruments[1].identification.id.fit.value[0]);
  ASSERT_TRUE(r.covariance.has_value());
  EXPECT_EQ(r.covariance->names.size(), 6u);
  EXPECT_EQ(r.covariance->monte_carlo.rows(), 6);
}

// An instrument's part is its reduction alone: the same logs read through its column with a configuration of it
// alone (one [instrument]) give the same numbers, bit for bit.
TEST_F(ReduceInstruments, EachPartIsThatInstrumentsOwnReduction) {
  const verbs::ReduceResult r = verbs::reduce(config_, options(false));
  verbs::ReduceOptions alone = options(false);
  alone.layout.instruments.clear();
  alone.layout.columns.pulses = "count_B";
  const verbs::ReduceResult b = verbs::reduce(config_.instruments[1], alone);
  EXPECT_EQ(r.instruments[1].identification.id.fit.value, b.identification.id.fit.value);
  EXPECT_FALSE(r.covariance.has_value());  // no statement, no covariance
}

TEST_F(ReduceInstruments, AnInstrumentWithoutAColumnIsRefusedNamingTheManifest) {
  verbs::ReduceOptions o = options(false);
  o.layout.instruments.pop_back();
  try {
    verbs::reduce(config_, o);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("manifest.toml: [instruments]: no output column for instrument 'B'"),
              std::string::npos)
        << e.what();
  }
  o = options(false);
  o.layout.instruments[1].id = "C";
  EXPECT_THROW(verbs::reduce(config_, o), InputError);
}

// The verbs that answer for one instrument refuse a test of several rather than answer for the first alone,
// asking for one of them (budget and design answer for each: tests/verbs/budget_instruments_test.cpp,
// design_instruments_test.cpp).
TEST_F(ReduceInstruments, VerbsOfOneInstrumentRefuseATestOfSeveral) {
  try {
    verbs::force(config_, {});
    FAIL() << "accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "instrument");
    EXPECT_NE(std::string(e.what()).find("a test of 2 instruments (A, B), and force answers for one at a time; "
                                         "accepted: one of A, B"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(verbs::monte_carlo(config_, {}), OptionError);
  EXPECT_NO_THROW(verbs::force(select_instrument(config_, "B"), {}));  // one of them, chosen
  EXPECT_NO_THROW(verbs::budget(config_.instruments[1], {}));  // each instrument's own configuration
  // A configuration of one [[instruments]] entry (B at its place, alone) is one instrument.
  const std::string b_alone = "setup = \"" + source_dir() + "/examples/lab.toml\"\n[[instruments]]\nid = \"B\"\n"
                              "position = [\"0 m\", \"0.12 m\"]\nazimuth = \"90 deg\"\n";
  EXPECT_NO_THROW(verbs::budget(parse_config(b_alone, "b.toml"), {}));
}

}  // namespace
}  // namespace ccal::test
