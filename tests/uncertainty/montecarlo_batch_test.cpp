// Models that take the engine's batches of trials (src/uncertainty/montecarlo_batch.hpp): a run through the
// batches gives, bit for bit, the run that evaluates its trials one by one, for any thread count and however
// the trials fall into batches; a batch that fails is evaluated again trial by trial, so that the error names
// the first trial that fails, as one by one.
#include "../../src/uncertainty/montecarlo_batch.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "monte_carlo_support.hpp"

namespace ccal {
namespace {

using ccal::test::source;

MonteCarloDetail run_kept(const std::vector<Tolerance>& sources, int outputs, const TrialFunction& trial,
                          int threads, std::uint64_t trials, const Eigen::MatrixXd* earlier = nullptr) {
  PropagationOptions o;
  o.trials = trials;
  o.seed = 11;
  o.threads = threads;
  o.keep_samples = true;
  o.earlier_samples = earlier;
  return run_monte_carlo(sources, {}, outputs, {}, trial, o);
}

TEST(MonteCarloBatch, CalibrationTrialsInBatchesAreTheTrialsOneByOne) {
  // The bundled example (its tolerances and the drives' rate noise): 1000 trials through the calibration
  // model's batches (the run means in the kernel's lanes) on 1 and 2 threads, and one by one (the same trial
  // function behind a lambda, which the engine cannot give batches), and a run that takes the first 77
  // trials' values from the one before (its batches start at trial 77, not at a multiple of 32): all the same
  // bits.
  const Config cfg = bundled_example();
  const CalibrationModel model = calibration_model(cfg);
  const std::vector<Tolerance> sources = monte_carlo_sources(cfg);
  const TrialFunction batched = calibration_trial(model);
  ASSERT_NE(batched.target<mc_batch::BatchCallable>(), nullptr);
  const TrialFunction one_by_one = [trial = calibration_trial(model)](std::span<const double> draws,
                                                                      std::span<double> outputs) mutable {
    trial(draws, outputs);
  };
  const int n = model.n_outputs();
  const MonteCarloDetail alone = run_kept(sources, n, one_by_one, 1, 1000);
  for (int threads : {1, 2}) {
    const MonteCarloDetail mc = run_kept(sources, n, batched, threads, 1000);
    ASSERT_TRUE(mc.samples == alone.samples) << threads << " threads";
  }
  const Eigen::MatrixXd earlier = alone.samples.topRows(77);
  const MonteCarloDetail extended = run_kept(sources, n, batched, 2, 1000, &earlier);
  ASSERT_TRUE(extended.samples == alone.samples);
  EXPECT_GT((alone.samples.row(0) - alone.samples.row(1)).norm(), 0.0);  // trials differ: the checks can fail
}

TEST(MonteCarloBatch, ATrialGivenTooFewDrawsIsRefused) {
  // The model reads each source's draw by its index: the bundled example's model has a source per tolerance and
  // two per run (the drives' rate noise), so the tolerances' draws alone would be read past their end.
  const Config cfg = bundled_example();
  const CalibrationModel model = calibration_model(cfg);
  TrialFunction trial = calibration_trial(model);
  std::vector<double> outputs(std::size_t(model.n_outputs()));
  const std::vector<double> tolerances_only(cfg.tolerances.size(), 0.0), all(model.parameters().size(), 0.0);
  ASSERT_LT(tolerances_only.size(), all.size());
  EXPECT_THROW(trial(tolerances_only, outputs), std::invalid_argument);
  EXPECT_NO_THROW(trial(all, outputs));
  std::vector<double> too_few_outputs(outputs.size() - 1);
  EXPECT_THROW(trial(all, too_few_outputs), std::invalid_argument);
}

// A model whose batch always throws and whose single trial fails beyond 2.5 in its first draw (2.5σ of a
// normal): the first trial beyond it is the one an error must name.
class FailingBatch final : public mc_batch::BatchTrial {
 public:
  std::unique_ptr<mc_batch::BatchTrial> fresh_copy() const override {
    return std::make_unique<FailingBatch>();
  }
  void one(std::span<const double> draws, std::span<double> outputs) override {
    if (draws[0] > 2.5) throw std::runtime_error("beyond 2.5: " + std::to_string(draws[0]));
    outputs[0] = draws[0];
  }
  void many(std::span<const double>, std::size_t, std::span<double>) override {
    throw std::runtime_error("the batch");
  }
};

TEST(MonteCarloBatch, AFailingBatchNamesTheFirstTrialThatFails) {
  const std::vector<Tolerance> sources = {source("n", 1.0, Distribution::normal)};
  const TrialFunction batched = mc_batch::BatchCallable(std::make_unique<FailingBatch>());
  const TrialFunction one_by_one = [trial = FailingBatch()](std::span<const double> draws,
                                                            std::span<double> outputs) mutable {
    trial.one(draws, outputs);
  };
  std::string want;
  try {
    run_kept(sources, 1, one_by_one, 1, 2000);
    FAIL() << "2000 normal draws all below 2.5σ";
  } catch (const std::runtime_error& e) {
    want = e.what();
  }
  for (int threads : {1, 2}) {
    try {
      run_kept(sources, 1, batched, threads, 2000);
      FAIL() << "the run did not fail";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), want) << threads << " threads";  // not "the batch"
    }
  }
}

}  // namespace
}  // namespace ccal
