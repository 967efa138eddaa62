// W1: the exact sensitivity table of the bundled example (48 sources × 3 coefficients, 6 runs), by
// forward-mode AD through kinematics, reduction and least squares.
//   build/bench/bench_budget --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/budget.hpp"

namespace {

using namespace ccal;

struct Setup {
  Config cfg = bundled_example();
  Experiment ex = cfg.experiment();
  std::vector<int> params;
  Eigen::VectorXd zero = Eigen::VectorXd::Zero(cfg.centrifuge.layout.size());
  Setup() {
    for (const auto& t : cfg.tolerances) params.push_back(t.parameter);
  }
};

// The sensitivity table split by path. Arg 0: exact mode, closed-form kinematic Jacobian at zero errors (the
// budget's default); 1: exact mode, AD through everything; 2: paper mode (AD).
void SensitivityTableByPath(benchmark::State& state) {
  Setup s;
  const ModelMode mode = state.range(0) == 2 ? ModelMode::paper : ModelMode::exact;
  const DerivativeMethod method =
      state.range(0) == 0 ? DerivativeMethod::linearised : DerivativeMethod::automatic;
  for (auto _ : state) {
    const SensitivityTable t =
        sensitivities(s.ex, s.cfg.identification, s.params, s.zero, s.zero, mode, {}, method);
    benchmark::DoNotOptimize(t.total.data());
  }
  state.SetLabel(state.range(0) == 0 ? "exact, linearised" : state.range(0) == 1 ? "exact, AD" : "paper, AD");
}
BENCHMARK(SensitivityTableByPath)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

// The whole `ccal budget` computation: both paths, the paper comparison and the compensation rows. Arg 1:
// with a dense [[correlations]] matrix, r = 0.3 between every pair of sources (1326 pairs; equicorrelation is
// positive definite), so that the cost of R, its factor and E F shows beside the sensitivities'.
void WholeBudget(benchmark::State& state) {
  Setup s;
  if (state.range(0) == 1)
    for (std::size_t a = 0; a < s.cfg.tolerances.size(); ++a)
      for (std::size_t b = a + 1; b < s.cfg.tolerances.size(); ++b)
        s.cfg.correlations.push_back({s.cfg.tolerances[a].id, s.cfg.tolerances[b].id, 0.3});
  for (auto _ : state) {
    const BudgetDetail r = compute_budget(s.cfg);
    benchmark::DoNotOptimize(r.standard_uncertainty.data());
  }
  state.SetLabel(state.range(0) == 1 ? "dense correlations" : "independent sources");
}
BENCHMARK(WholeBudget)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
