// Reduce + fit of the 6-run paper plan in exact mode (target < 1 ms): observe<double> (truth and model means
// of every run through the exact chain) and fit(fit_problem) of K0, K2, K3 with K1 fixed, on the bundled
// example's experiment. The truth's errors are zero, or every tolerance bound taken as the error's value:
// static parameters only (the factored static chain), or with the first-harmonic dynamic ones too (the
// general recursion).
//   build/bench/bench_reduce --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include "ccal/config.hpp"
#include "ccal/simulate.hpp"

namespace {

using namespace ccal;

enum class Errors { zero = 0, static_tolerances = 1, all_tolerances = 2 };

Eigen::VectorXd truth(const Config& cfg, Errors which) {
  Eigen::VectorXd e = Eigen::VectorXd::Zero(cfg.centrifuge.layout.size());
  if (which == Errors::zero) return e;
  for (const Tolerance& t : cfg.tolerances) {
    const bool dynamic =
        channels()[cfg.centrifuge.layout.parameter_channel(t.parameter)].joint != Joint::none;
    if (dynamic && which == Errors::static_tolerances) continue;
    e[t.parameter] = t.bound;
  }
  return e;
}

void ReduceAndFitPaperPlan(benchmark::State& state) {
  const Config cfg = bundled_example();
  const Experiment ex = cfg.experiment();
  const IdentificationSpec& spec = cfg.identification;
  const Eigen::VectorXd e = truth(cfg, static_cast<Errors>(state.range(0)));
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  for (auto _ : state) {
    const Observations<double> obs = observe<double>(ex, e, zero, spec, ModelMode::exact);
    const FitResult r = fit(fit_problem(obs, spec));
    benchmark::DoNotOptimize(r.value.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(ex.plan.runs.size()));
  state.SetLabel(state.range(0) == 0   ? "zero errors"
                 : state.range(0) == 1 ? "static tolerances as errors"
                                       : "static + first-harmonic dynamic tolerances as errors");
}
BENCHMARK(ReduceAndFitPaperPlan)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

}  // namespace
