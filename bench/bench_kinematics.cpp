// Exact specific-force + angular-rate evaluations per second (issue: ≥ 1e7/s per core with static errors).
//   build/bench/bench_kinematics --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "ccal/model/kinematics.hpp"

namespace {

using namespace ccal;

Eigen::VectorXd errors(const ErrorLayout& layout, bool dynamic) {
  std::mt19937 rng(1);
  std::normal_distribution<double> n(0.0, 1e-5);
  Eigen::VectorXd e(layout.size());
  for (int i = 0; i < layout.size(); ++i) {
    const bool is_dynamic = channels()[layout.parameter_channel(i)].joint != Joint::none;
    e[i] = (is_dynamic && !dynamic) ? 0.0 : n(rng);
  }
  return e;
}

struct Setup {
  Geometry geo{2.5, 0.2, 0.05, 0.0};
  Site site{};
  double rate = std::sqrt(20.0 * 9.8 / 2.5);
};

// The factored chain: two sin/cos pairs and a few 3×3 products per evaluation.
void StaticErrorsFactored(benchmark::State& state) {
  Setup s;
  const ErrorLayout layout(1);
  const Eigen::VectorXd e = errors(layout, false);
  const StaticChain<double> chain(s.geo, layout, e, s.site, s.rate, 0.0);
  double t = 0.0, sum = 0.0;
  for (auto _ : state) {
    const auto in = chain(0.1 + s.rate * t, 2.0 - s.rate * t, s.rate, -s.rate);
    sum += in.specific_force[0] + in.angular_rate[0];
    t += 1e-3;
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(StaticErrorsFactored);

// The general link-by-link recursion, static errors only.
void StaticErrorsGeneral(benchmark::State& state) {
  Setup s;
  const ErrorLayout layout(1);
  const Eigen::VectorXd e = errors(layout, false);
  double t = 0.0, sum = 0.0;
  for (auto _ : state) {
    const JointState<double> j{0.1 + s.rate * t, s.rate, 0.0, 0.0, 2.0 - s.rate * t, -s.rate};
    const auto st = exact_state<double>(s.geo, layout, e, s.site, j);
    sum += st.specific_force[0] + st.angular_rate[0];
    t += 1e-3;
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(StaticErrorsGeneral);

// Every dynamic error with harmonics up to the given order.
void DynamicErrors(benchmark::State& state) {
  Setup s;
  const ErrorLayout layout(static_cast<int>(state.range(0)));
  const Eigen::VectorXd e = errors(layout, true);
  double t = 0.0, sum = 0.0;
  for (auto _ : state) {
    const JointState<double> j{0.1 + s.rate * t, s.rate, 0.0, 0.0, 2.0 - s.rate * t, -s.rate};
    const auto st = exact_state<double>(s.geo, layout, e, s.site, j);
    sum += st.specific_force[0] + st.angular_rate[0];
    t += 1e-3;
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(DynamicErrors)->Arg(1)->Arg(3);

// The precomposed chain with every dynamic error (what run means and Monte Carlo trials use).
void DynamicErrorsPrecomposed(benchmark::State& state) {
  Setup s;
  const ErrorLayout layout(static_cast<int>(state.range(0)));
  const Eigen::VectorXd e = errors(layout, true);
  const DynamicChain<double> chain(s.geo, layout, e, s.site, s.rate, 0.0);
  double t = 0.0, sum = 0.0;
  for (auto _ : state) {
    const JointState<double> j{0.1 + s.rate * t, s.rate, 0.0, 0.0, 2.0 - s.rate * t, -s.rate};
    const auto in = chain(j);
    sum += in.specific_force[0] + in.angular_rate[0];
    t += 1e-3;
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(DynamicErrorsPrecomposed)->Arg(1)->Arg(3);

}  // namespace
