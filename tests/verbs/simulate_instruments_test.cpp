// verbs::simulate of a test of several instruments (examples/daq/two_short.toml: two PIGAs on the lab's machine,
// B off the platform axis and turned): one machine for all (the shared errors one draw, the drives' rate noise
// one stream), each instrument's own inputs and output noise its own; the logs of the test hold every
// instrument's column, and reduce reads them back to each instrument's own run means and coefficients.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/intake/log_manifest.hpp"
#include "ccal/verbs/instrument_covariance.hpp"
#include "ccal/verbs/reduce.hpp"
#include "ccal/verbs/simulate.hpp"
#include "test_paths.hpp"

namespace ccal::test {
namespace {

namespace fs = std::filesystem;

Config two_short() { return load_config(source_dir() + "/examples/daq/two_short.toml"); }

// The first instrument's simulation is its simulation alone (the same machine, the same noise seed), bit for bit;
// the second's noise is its own, so its run means are not the first's.
TEST(SimulateInstruments, TheFirstInstrumentIsItsSimulationAlone) {
  const Config c = two_short();
  const verbs::SimulateResult r = verbs::simulate(c);
  ASSERT_EQ(r.instruments.size(), 2u);
  EXPECT_EQ(r.config.instruments.size(), 2u);
  const verbs::SimulateResult a = verbs::simulate(select_instrument(c, "A"));
  EXPECT_TRUE(a.instruments.empty());
  EXPECT_EQ(r.instruments[0].observations.output, a.observations.output);
  EXPECT_EQ(r.instruments[0].identification.fit.value, a.identification.fit.value);
  EXPECT_EQ(r.instruments[1].config.instrument_id, "B");
  EXPECT_NE(r.instruments[1].observations.output, verbs::simulate(select_instrument(c, "B")).observations.output);
}

// A drawn machine: each shared input one draw for both instruments, each own input (the mounting, the fixed terms,
// the output chain) a draw of each instrument's own.
TEST(SimulateInstruments, TheSharedInputsAreOneDrawAndTheOwnInputsEachTheirs) {
  const Config c = two_short();
  verbs::SimulateOptions o;
  o.draw_truth = true;
  o.seed = 7;
  const verbs::SimulateResult r = verbs::simulate(c, o);
  const std::vector<double>&a = r.instruments[0].drawn, &b = r.instruments[1].drawn;
  ASSERT_EQ(a.size(), c.tolerances.size());
  ASSERT_EQ(b.size(), a.size());
  int shared = 0, own = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    SCOPED_TRACE(c.tolerances[k].id);
    if (verbs::instrument_own_input(c.tolerances[k].parameter)) {
      ++own;
      EXPECT_NE(a[k], b[k]);  // independent draws of a continuous distribution: equal with probability 0
    } else {
      ++shared;
      EXPECT_EQ(a[k], b[k]);
    }
  }
  EXPECT_GT(own, 4);  // at least the mounting's dx5 … dthz5
  EXPECT_GT(shared, 20);
  // The same seed, the same machine: reproducible.
  EXPECT_EQ(verbs::simulate(c, o).instruments[1].observations.output, r.instruments[1].observations.output);
  // A truth file holds one configuration's errors: refused for a test of several, naming the choice.
  o.draw_truth = false;
  o.truth = SimulationTruth{};
  o.truth->source = "truth.toml";
  try {
    verbs::simulate(c, o);
    FAIL() << "accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "truth");
    EXPECT_NE(std::string(e.what()).find("a test of 2 instruments"), std::string::npos) << e.what();
  }
}

class SimulatedTestLogs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("ccal-simulate-instruments-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const std::vector<RunLogFile>& files) const {
    for (const RunLogFile& f : files) std::ofstream(dir_ / f.name) << f.text;
  }

  fs::path dir_;
};

// One folder for the test: each log holds both instruments' counts (pulses_A, pulses_B), the manifest maps them,
// and reduce reads each instrument's run means back to within its counting quantum: a count ⌊m t / w⌋ read over
// T gives m to w/T (1e-4 deg over 30 s: 3.3e-6 deg/s), and the clock and encoders are the same for both.
TEST_F(SimulatedTestLogs, OneFolderHoldsEveryInstrumentAndReducesToEach) {
  const Config c = two_short();
  verbs::SimulateOptions so;
  so.draw_truth = true;
  so.seed = 7;
  const verbs::SimulateResult sim = verbs::simulate(c, so);
  const std::vector<RunLogFile> files = verbs::simulation_logs(sim, {});
  ASSERT_EQ(files.size(), c.plan.runs.size() + 1);
  EXPECT_EQ(files.front().text.substr(0, files.front().text.find('\n')), "time,pulses_A,pulses_B,theta1,gamma");
  EXPECT_EQ(files.front().text.find("-0,"), std::string::npos);  // a count of none is 0
  EXPECT_NE(files.back().text.find("[instruments]"), std::string::npos);
  EXPECT_EQ(files.back().text.find("pulses = 'pulses'"), std::string::npos);  // no column of nobody's
  EXPECT_NE(files.back().text.find("B = { pulses = 'pulses_B' }"), std::string::npos) << files.back().text;
  write(files);
  const LogManifest m = read_log_manifest(dir_);
  verbs::ReduceOptions o;
  o.layout = m.layout;
  o.logs = verbs::manifest_logs(m);
  const verbs::ReduceResult r = verbs::reduce(c, o);
  ASSERT_EQ(r.instruments.size(), 2u);
  for (std::size_t a = 0; a < 2; ++a) {
    const double w = c.instruments[a].instrument.quantum;
    for (std::size_t j = 0; j < c.plan.runs.size(); ++j) {
      SCOPED_TRACE(c.instruments[a].instrument_id + " " + c.plan.runs[j].name);
      const double T = c.plan.runs[j].duration;
      EXPECT_NEAR(r.instruments[a].logs.runs[j].log.mean_output,
                  sim.instruments[a].observations.output[Eigen::Index(j)], 1.5 * w / T);
    }
  }
  // B alone, chosen from the test, reads its own column of the same folder: the same numbers as its part.
  const verbs::ReduceResult b = verbs::reduce(select_instrument(c, "B"), o);
  EXPECT_TRUE(b.instruments.empty());
  EXPECT_EQ(b.identification.id.fit.value, r.instruments[1].identification.id.fit.value);
}

// The layout's [instruments] names the columns; one that misses an instrument or states its output wrongly is
// refused, saying what it would accept.
TEST_F(SimulatedTestLogs, ALayoutNamesEachInstrumentsColumn) {
  const Config c = two_short();
  const verbs::SimulateResult sim = verbs::simulate(c);
  LogLayout layout;
  layout.instruments = {{"A", "piga_a", true, 3}, {"B", "piga_b", true, 4}};
  const std::vector<RunLogFile> files = verbs::simulation_logs(sim, layout);
  EXPECT_EQ(files.front().text.substr(0, files.front().text.find('\n')), "time,piga_a,piga_b,theta1,gamma");
  layout.instruments.pop_back();
  try {
    verbs::simulation_logs(sim, layout);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no column for instrument 'B'; accepted: B = { pulses = \"…\" }"),
              std::string::npos)
        << e.what();
  }
  layout.instruments = {{"A", "piga_a", true, 3}, {"B", "piga_b", false, 4}};
  try {
    verbs::simulation_logs(sim, layout);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(line 4): instrument 'B' has a quantum"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ccal::test
