// `ccal design` of the bundled example: the candidate cache (regressor, sensitivity and noise rows of every
// candidate run, by the budget's code) and the whole design (cache, exchange search from the configured plan
// and six random starts, local refinement, the full budgets before and after).
//   build/bench/bench_design
//   OMP_NUM_THREADS=2 build/bench/bench_design --benchmark_filter=WholeDesign
//   CCAL_BENCH_CONFIG=tests/data/golden/second.toml build/bench/bench_design   (another configuration)
#include <benchmark/benchmark.h>

#include <cstdlib>

#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/design_candidates.hpp"
#include "ccal/verbs/design.hpp"

namespace {

using namespace ccal;

Config bench_config() {
  const char* path = std::getenv("CCAL_BENCH_CONFIG");
  return path && *path ? load_config(path) : bundled_example();
}

// The rows of the default design space's candidates (26 g-levels × 8 cuts of the last turn × 12 terminal
// phases × 4 arm azimuths = 9984, plus the six configured runs: 9990), as `ccal design` caches them.
void CandidateCache(benchmark::State& state) {
  const Config cfg = bench_config();
  const std::vector<DesignRun> runs = candidate_runs(resolve_design_space(cfg), cfg);
  for (auto _ : state) {
    const CandidateRows rows = candidate_rows(cfg, runs);
    benchmark::DoNotOptimize(rows.leaks.data());
  }
  state.counters["candidates"] = double(runs.size());
  state.counters["candidates/s"] =
      benchmark::Counter(double(runs.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(CandidateCache)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

// The whole `ccal design` of the bundled example with its defaults: the first time (its candidate rows
// computed, as `--fresh-candidates` does: the figure of a configuration not designed before), and again with
// the rows from the cache file (arg 1).
void WholeDesign(benchmark::State& state) {
  const Config cfg = bench_config();
  verbs::DesignOptions options;
  options.fresh_candidates = state.range(0) == 0;
  if (!options.fresh_candidates) (void)verbs::design(cfg, options);  // the cache file written
  std::size_t candidates = 0;
  for (auto _ : state) {
    const verbs::DesignResult r = verbs::design(cfg, options);
    candidates = r.candidates;
    benchmark::DoNotOptimize(r.after.budget.expanded_uncertainty.data());
  }
  state.counters["candidates"] = double(candidates);
  state.SetLabel(options.fresh_candidates ? "candidate rows computed" : "candidate rows from the cache");
}
BENCHMARK(WholeDesign)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
