// Monte Carlo trials per second for the bundled example (all its tolerances and the drives' rate noise, the
// six-run plan, K0, K2, K3 identified), with 1 and 2 threads, independent or densely correlated; the engine's
// own cost per trial (sampling, storage and statistics around a model that only sums the draws); and the
// truth's six run means of one trial through the Monte Carlo's kernel (alone, and in a batch of 32 as the
// engine gives it) and through the general average_run.
//   build/bench/bench_montecarlo --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include <numeric>

#include "../src/uncertainty/calibration_cache.hpp"
#include "../src/uncertainty/draw_quantiles.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/reduction/run_average.hpp"
#include "ccal/reduction/run_means.hpp"
#include "ccal/uncertainty/montecarlo.hpp"

namespace {

using namespace ccal;

// Arg 1 of the benchmarks below: a dense [[correlations]] matrix, r = 0.3 between every pair of tolerances
// (equicorrelation is positive definite), drawn through the Gaussian copula: the cost of the scores' L z and
// of each source's G_D(y) beside the independent draws'.
Config with_dense_correlations(Config cfg, bool dense) {
  if (dense)
    for (std::size_t a = 0; a < cfg.tolerances.size(); ++a)
      for (std::size_t b = a + 1; b < cfg.tolerances.size(); ++b)
        cfg.correlations.push_back({cfg.tolerances[a].id, cfg.tolerances[b].id, 0.3});
  return cfg;
}

// The calibration pipeline: simulate → identify → deviations of K0, K2, K3. Arg 0: threads.
void Pipeline(benchmark::State& state) {
  const Config cfg = with_dense_correlations(bundled_example(), state.range(1) == 1);
  const CalibrationModel model = calibration_model(cfg);
  const TrialFunction trial = calibration_trial(model);
  // Built once, as `ccal montecarlo` builds them once for all its trials (the drives' rate-noise sources
  // take a few derivatives through the chain: a cost per run, not per trial).
  const std::vector<Tolerance> sources = monte_carlo_sources(cfg);
  PropagationOptions options;
  options.trials = 1000;
  options.threads = int(state.range(0));
  std::uint64_t trials = 0;
  for (auto _ : state) {
    const MonteCarloDetail r =
        run_monte_carlo(sources, cfg.correlations, model.n_outputs(), model.output_names(), trial, options);
    benchmark::DoNotOptimize(r.outputs[2].std_dev);
    trials += r.trials;
    ++options.seed;
  }
  state.SetItemsProcessed(std::int64_t(trials));
  state.counters["sources"] = double(sources.size());
  state.SetLabel(state.range(1) == 1 ? "dense correlations" : "independent sources");
}
BENCHMARK(Pipeline)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The engine alone: the tolerances drawn (independent or densely correlated), a trivial model with 3 outputs,
// 10⁵ trials per run (the statistics included).
void EngineOnly(benchmark::State& state) {
  const Config cfg = with_dense_correlations(bundled_example(), state.range(1) == 1);
  const TrialFunction trial = [](std::span<const double> x, std::span<double> y) {
    const double s = std::accumulate(x.begin(), x.end(), 0.0);
    y[0] = s;
    y[1] = x[0] - s;
    y[2] = x[1] * s;
  };
  PropagationOptions options;
  options.trials = 100000;
  options.threads = int(state.range(0));
  std::uint64_t trials = 0;
  for (auto _ : state) {
    const MonteCarloDetail r = run_monte_carlo(cfg.tolerances, cfg.correlations, 3, {}, trial, options);
    benchmark::DoNotOptimize(r.outputs[0].std_dev);
    trials += r.trials;
  }
  state.SetItemsProcessed(std::int64_t(trials));
  state.counters["sources"] = double(cfg.tolerances.size());
  state.SetLabel(state.range(1) == 1 ? "dense correlations" : "independent sources");
}
BENCHMARK(EngineOnly)
    ->Args({1, 0})
    ->Args({2, 0})
    ->Args({1, 1})
    ->Args({2, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Errors at +1 tolerance of every bundled source: dynamic errors and ΔΩ ≠ 0, so two slow nodes.
Eigen::VectorXd one_sigma_errors(const Config& cfg) {
  Eigen::VectorXd e = cfg.centrifuge.errors;
  for (const Tolerance& t : cfg.tolerances) e[t.parameter] += t.bound;
  return e;
}

void RunMeansKernel(benchmark::State& state) {
  const Config cfg = bundled_example();
  const CalibrationModel model = calibration_model(cfg);
  const Eigen::VectorXd e = one_sigma_errors(cfg);
  std::vector<double> means(cfg.plan.runs.size());
  RunMeanKernel::Workspace workspace;  // as a trial holds one
  for (auto _ : state) {
    model.trial_cache().run_means->means(std::span<const double>(e.data(), std::size_t(e.size())), means,
                                         workspace);
    benchmark::DoNotOptimize(means.data());
  }
}
BENCHMARK(RunMeansKernel)->Unit(benchmark::kMicrosecond);

// The same trial's means in batches of 32 trials (as the Monte Carlo's engine draws them), eight to a SIMD
// pack: the time per trial.
void RunMeansKernelBatch(benchmark::State& state) {
  const Config cfg = bundled_example();
  const CalibrationModel model = calibration_model(cfg);
  const Eigen::VectorXd e = one_sigma_errors(cfg);
  constexpr std::size_t kTrials = 32;
  std::vector<double> errors, means(kTrials * cfg.plan.runs.size());
  for (std::size_t t = 0; t < kTrials; ++t) errors.insert(errors.end(), e.data(), e.data() + e.size());
  RunMeanKernel::Workspace workspace;
  for (auto _ : state) {
    model.trial_cache().run_means->means(errors, kTrials, means, workspace);
    benchmark::DoNotOptimize(means.data());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(kTrials));
  state.counters["us_per_trial"] = benchmark::Counter(
      double(kTrials) * 1e-6, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(RunMeansKernelBatch)->Unit(benchmark::kMicrosecond);

void RunMeansGeneral(benchmark::State& state) {
  const Config cfg = bundled_example();
  const CalibrationModel model = calibration_model(cfg);
  const Experiment ex = cfg.experiment();
  const Eigen::VectorXd e = one_sigma_errors(cfg);
  for (auto _ : state)
    for (const ccal::Run& run : ex.plan.runs)
      benchmark::DoNotOptimize(
          average_run<double>(ex.geometry, ex.layout, e, ex.site, run, &ex.instrument, {}, model.reduction())
              .output);
}
BENCHMARK(RunMeansGeneral)->Unit(benchmark::kMicrosecond);

// Φ⁻¹ of the draws in lanes (src/uncertainty/draw_quantiles.cpp) per value, at uniforms of the engine's grid.
void NormalQuantiles(benchmark::State& state) {
  std::vector<double> u(4096), x(u.size());
  std::uint64_t k = 12345;
  for (double& v : u) {
    k = k * 6364136223846793005ULL + 1442695040888963407ULL;
    v = (double(k >> 12) + 0.5) * 0x1p-52;
  }
  for (auto _ : state) {
    draws::normal_quantiles(u.data(), x.data(), u.size());
    benchmark::DoNotOptimize(x.data());
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(u.size()));
}
BENCHMARK(NormalQuantiles);

}  // namespace
