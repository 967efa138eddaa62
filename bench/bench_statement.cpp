// The calibration statement's Monte Carlo check (src/verbs/statement_montecarlo.hpp; every `ccal reduce
// --statement`, `ccal identify --statement` and certificate runs it) on the lab's example: examples/lab.toml
// and its simulated observations (as `ccal simulate examples/lab.toml --observations-out` writes them), with
// the requested statement_trials (arg 0) and threads (arg 1). The time of the check is the statement's time less
// that of the same statement without the check (statement_trials = 0, measured before the loop, the least of
// five); us_per_trial is that time per trial of the M the check ended with (it grows M while a verdict is within
// the sampling error, so M may exceed the requested).
//   build/bench/bench_statement --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>

#include "ccal/io/config_file.hpp"
#include "ccal/verbs/simulate.hpp"
#include "ccal/verbs/statement.hpp"

namespace {

using namespace ccal;
using Clock = std::chrono::steady_clock;

double seconds_of(const Config& config, const verbs::Identification& id, const verbs::StatementOptions& o,
                  std::uint64_t* trials = nullptr) {
  const auto start = Clock::now();
  const verbs::CalibrationStatement s = verbs::calibration_statement(config, id, o, "statement");
  const double t = std::chrono::duration<double>(Clock::now() - start).count();
  benchmark::DoNotOptimize(s.coefficients.data());
  if (trials) *trials = s.monte_carlo_trials;
  return t;
}

void StatementCheck(benchmark::State& state) {
  const Config config = load_config(CCAL_SOURCE_DIR "/examples/lab.toml");
  const verbs::Identification id = verbs::simulate(config).identification;
  verbs::StatementOptions o;
  o.threads = int(state.range(1));
  o.statement_trials = 0;
  double baseline = 1e300;
  for (int k = 0; k < 5; ++k) baseline = std::min(baseline, seconds_of(config, id, o));
  o.statement_trials = state.range(0);
  std::uint64_t trials = 0, last = 0;
  for (auto _ : state) {
    state.SetIterationTime(std::max(0.0, seconds_of(config, id, o, &last) - baseline));
    trials += last;
  }
  state.SetItemsProcessed(std::int64_t(trials));
  // Seconds per 10⁻⁶ trials: µs per trial.
  state.counters["us_per_trial"] =
      benchmark::Counter(double(trials) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["M"] = double(last);
}
BENCHMARK(StatementCheck)
    ->Args({100000, 1})
    ->Args({100000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseManualTime()
    ->Iterations(1);

}  // namespace
