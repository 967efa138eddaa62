// Reduce + fit of the 6-run paper plan in exact mode (target < 1 ms): observe<double> (truth and model means
// of every run through the exact chain) and fit(fit_problem) of K0, K2, K3 with K1 fixed, on the bundled
// example's experiment. The truth's errors are zero, or every tolerance bound taken as the error's value:
// static parameters only (the factored static chain), or with the first-harmonic dynamic ones too (the
// general recursion).
//   build/bench/bench_reduce --benchmark_min_time=1 --benchmark_filter=ReduceAndFit
//
// Streaming reduction of a recorded run log (run_log.hpp): a 2 kHz log of time, cumulative pulses and both
// encoders (the main axis at 8.86 rad/s with a 10 ppm once-per-revolution ripple, the platform
// counter-rotating), generated once into a temporary file of CCAL_BENCH_LOG_MB megabytes (default 1024),
// reduced in one pass with the encoder fits of harmonic order 1 and hashed (SHA-256) as it is read (target:
// ≥ 600 MB/s on one core). The in-memory path (read the whole table, then reduce it) runs on a 100 MB log for
// comparison.
//   CCAL_BENCH_LOG_MB=1024 build/bench/bench_reduce --benchmark_filter=Log --benchmark_min_time=1
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "../src/intake/plain_decimal_row.hpp"
#include "ccal/intake/run_log.hpp"
#include "ccal/reduction/observe.hpp"

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

namespace {

namespace fs = std::filesystem;
constexpr double kRate = 8.86, kPi = std::numbers::pi;

// Rows of a log at 2 kHz, as a logger writes them: time to 0.1 µs, whole pulses, angles wrapped to [0, 2π)
// to 1e-9 rad (a 32-bit encoder's step).
void write_log(const fs::path& path, std::size_t bytes) {
  std::FILE* f = std::fopen(path.string().c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + path.string());
  std::string block = "time,pulses,theta1,gamma\n";
  std::size_t written = 0;
  for (long k = 0; written < bytes; ++k) {
    const double t = 5e-4 * double(k);
    const double theta = kRate * t + 1e-5 * std::sin(kRate * t);  // δ1 = c1 sin θ1 for c1 = 10 ppm
    const double gamma = 1.0 - kRate * t;
    fmt::format_to(std::back_inserter(block), "{:.7f},{},{:.9f},{:.9f}\n", t, std::llround(1.6e5 * t),
                   std::fmod(theta, 2 * kPi), std::fmod(gamma, 2 * kPi) + 2 * kPi);
    if (block.size() > (1u << 20)) {
      written += std::fwrite(block.data(), 1, block.size(), f);
      block.clear();
    }
  }
  written += std::fwrite(block.data(), 1, block.size(), f);
  std::fclose(f);
}

struct Log {
  fs::path path;
  std::size_t bytes = 0;
  Log(const char* name, std::size_t megabytes) : path(fs::temp_directory_path() / name) {
    write_log(path, megabytes << 20);
    bytes = fs::file_size(path);
  }
  ~Log() {
    std::error_code ec;
    fs::remove(path, ec);
  }
};

std::size_t log_megabytes() {
  const char* env = std::getenv("CCAL_BENCH_LOG_MB");
  return env ? std::size_t(std::strtoull(env, nullptr, 10)) : 1024;
}

ccal::RunLogOptions options() {
  ccal::RunLogOptions o;
  o.pulse_weight = 1e-5;
  o.harmonic_order = 1;
  return o;
}

void StreamedLog(benchmark::State& state) {
  static const Log log("ccal_bench_reduce_stream.csv", log_megabytes());
  for (auto _ : state) {
    const ccal::ReducedLog r = ccal::reduce_run_log_file(log.path, options(), kRate);
    benchmark::DoNotOptimize(r.theta1_rate);
  }
  state.SetBytesProcessed(std::int64_t(state.iterations()) * std::int64_t(log.bytes));
  state.SetLabel(fmt::format("{} MB log, both encoders, harmonic order 1", log.bytes >> 20));
}
BENCHMARK(StreamedLog)->Unit(benchmark::kMillisecond)->UseRealTime();

void InMemoryLog(benchmark::State& state) {
  static const Log log("ccal_bench_reduce_table.csv", 100);
  for (auto _ : state) {
    const ccal::ReducedLog r = ccal::reduce_run_log(ccal::read_csv_file(log.path), options(), kRate);
    benchmark::DoNotOptimize(r.theta1_rate);
  }
  state.SetBytesProcessed(std::int64_t(state.iterations()) * std::int64_t(log.bytes));
  state.SetLabel(fmt::format("{} MB log read whole, then reduced", log.bytes >> 20));
}
BENCHMARK(InMemoryLog)->Unit(benchmark::kMillisecond)->UseRealTime();

// The rows' numbers alone: 10⁵ rows of the log above (16 MB of lines held in memory), read cell by cell
// (Arg 0), by the vector reading (Arg 1, where the processor has SSE4.1), or by a log's reader, which reads
// rows laid out alike by their layout (Arg 2, where the processor has AVX-512 VBMI).
void RowScan(benchmark::State& state) {
  std::vector<std::string> lines;
  std::size_t bytes = 0;
  for (long k = 0; k < 100000; ++k) {
    const double t = 5e-4 * double(k), theta = kRate * t + 1e-5 * std::sin(kRate * t),
                 gamma = 1.0 - kRate * t;
    lines.push_back(fmt::format("{:.7f},{},{:.9f},{:.9f}", t, std::llround(1.6e5 * t),
                                std::fmod(theta, 2 * kPi), std::fmod(gamma, 2 * kPi) + 2 * kPi));
    bytes += lines.back().size() + 1;
  }
  const auto way = state.range(0);
  if (way == 1 && !ccal::detail::vector_row_scan_available()) state.SkipWithError("no SSE4.1");
  if (way == 2 && !ccal::detail::row_layout_reading_available()) state.SkipWithError("no AVX-512 VBMI");
  std::vector<double> values(4);
  ccal::PlainDecimalRowReader reader;
  for (auto _ : state)
    for (const std::string& line : lines) {
      const bool ok = way == 2   ? reader.read(line, values)
                      : way == 1 ? ccal::detail::scan_plain_decimal_row_vector(line, values)
                                 : ccal::detail::scan_plain_decimal_row_portable(line, values);
      benchmark::DoNotOptimize(ok);
      benchmark::DoNotOptimize(values.data());
    }
  state.SetBytesProcessed(std::int64_t(state.iterations()) * std::int64_t(bytes));
  state.SetLabel(way == 2 ? "by layout" : way == 1 ? "vector" : "cell by cell");
}
BENCHMARK(RowScan)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);

}  // namespace
