#include "ccal/uncertainty/montecarlo.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/uncertainty/gaussian_copula.hpp"
#include "montecarlo_batch.hpp"
#include "montecarlo_draws.hpp"
#include "progress_bar.hpp"
#include "sample_statistics.hpp"

#ifdef _OPENMP
#include <omp.h>
#else
#pragma GCC diagnostic ignored "-Wunknown-pragmas"  // without OpenMP the loops simply run serially
#endif

namespace ccal {
namespace {

using namespace sample_stats;
using progress_bar::Progress;

using Clock = std::chrono::steady_clock;

using mc_draws::BatchDrawer;
using mc_draws::mix64;
using mc_draws::plan_slots;
using mc_draws::SlotPlan;

// Trials drawn together (montecarlo_draws.hpp): enough for full lanes of normal quantiles, few enough that a
// batch's draws stay in the first-level cache.
constexpr std::int64_t kBatch = 32;

int default_threads() {
#ifdef _OPENMP
  return std::min(omp_get_max_threads(), kMaxThreads);  // OMP_NUM_THREADS may ask for more
#else
  return 1;
#endif
}

// ---- The trial loop --------------------------------------------------------------------------------------

// The first failure of a stage (the one with the lowest trial index among those that failed before the others
// stopped).
struct Failure {
  std::mutex mutex;
  std::atomic<bool> failed{false};
  std::uint64_t trial = std::numeric_limits<std::uint64_t>::max();
  std::exception_ptr error;

  void record(std::uint64_t i, std::exception_ptr e) {
    const std::lock_guard lock(mutex);
    if (i < trial) {
      trial = i;
      error = std::move(e);
    }
    failed.store(true, std::memory_order_relaxed);
  }
};

struct Engine {
  const std::vector<Tolerance>& sources;
  const SlotPlan& plan;
  const GaussianCopula* copula;  // partly correlated sources: the scores' factor L; null: independent slots
  const TrialFunction& trial;
  const std::vector<std::string>& names;
  std::uint64_t key;
  int threads;
  std::vector<std::vector<double>>& samples;  // per output, by trial index
  Progress& progress;

  // Trials [begin, end): samples[o][i] for every output o.
  void run(std::uint64_t begin, std::uint64_t end) const {
    const auto n_sources = sources.size();
    const auto n_outputs = samples.size();
    const auto count = std::int64_t(end - begin);
    // Trials in batches of kBatch (the last one shorter), drawn together: their normal quantiles in lanes.
    const std::int64_t batches = (count + kBatch - 1) / kBatch;
    const std::int64_t chunk = std::clamp<std::int64_t>(batches / (std::int64_t(threads) * 64), 1, 16);
    Failure failure;
#pragma omp parallel num_threads(threads)
    {
      std::vector<double> draws, out(n_outputs), batch_out(std::size_t(kBatch) * n_outputs);
      BatchDrawer drawer(sources, plan, copula);
      TrialFunction own_trial = trial;  // this thread's copy: its scratch buffers are its own
      // A model that takes whole batches (montecarlo_batch.hpp): each trial's outputs the bits it has alone.
      mc_batch::BatchCallable* batch_trial = own_trial.target<mc_batch::BatchCallable>();
#pragma omp for schedule(dynamic, chunk)
      for (std::int64_t b = 0; b < batches; ++b) {
        if (failure.failed.load(std::memory_order_relaxed)) continue;
        const std::uint64_t first = begin + std::uint64_t(b * kBatch);
        const auto n = std::size_t(std::min<std::int64_t>(kBatch, count - b * kBatch));
        drawer.draw(key, first, n, draws);
        bool batched = false;
        if (batch_trial) try {
            batch_trial->trial().many(std::span<const double>(draws.data(), n * n_sources), n,
                                      std::span<double>(batch_out.data(), n * n_outputs));
            batched = true;
          } catch (...) {  // the trials one by one below find the first that fails
          }
        for (std::size_t t = 0; t < n; ++t) {
          const std::uint64_t i = first + t;
          try {
            const std::span<const double> drawn(draws.data() + t * n_sources, n_sources);
            const std::span<double> y = batched
                                            ? std::span<double>(batch_out.data() + t * n_outputs, n_outputs)
                                            : std::span<double>(out);
            if (!batched) own_trial(drawn, y);
            for (std::size_t o = 0; o < n_outputs; ++o) {
              if (!std::isfinite(y[o]))
                throw InputError(
                    fmt::format("Monte Carlo trial {}: output '{}' is {}; the model cannot be evaluated at "
                                "these draws (are the tolerances too wide for it?)",
                                i + 1, names[o], y[o]));
              samples[o][i] = y[o];
            }
            if (progress.on()) progress.tick();  // a Cancelled from the callback stops the loop
          } catch (...) {
            failure.record(i, std::current_exception());
            break;
          }
        }
      }
    }
    if (failure.failed.load()) std::rethrow_exception(failure.error);
  }
};

struct StageValues {
  std::vector<double> mean, std_dev, low, high;
  std::vector<double> m2;  // Σ (y − stage mean)², to pool u(y) over the stages
};

// u(y) of all h·M values from the stage means and sums of squares (Chan, Golub & LeVeque, "Algorithms for
// computing the sample variance", Am. Stat. 37, 1983): Σ M2_s + M Σ (m_s − m)², all stages of M values.
double pooled_std(const StageValues& s, std::uint64_t M) {
  const double m = mean_of(s.mean);
  Sum within, between;
  for (std::size_t k = 0; k < s.mean.size(); ++k) {
    within.add(s.m2[k]);
    between.add((s.mean[k] - m) * (s.mean[k] - m));
  }
  const double n = double(M) * double(s.mean.size());
  return std::sqrt((within.value() + double(M) * between.value()) / (n - 1));
}

std::string format_count(std::uint64_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t k = 0; k < digits.size(); ++k) {
    if (k > 0 && (digits.size() - k) % 3 == 0) out += ' ';
    out += digits[k];
  }
  return out;
}

}  // namespace

namespace {
// Every output value of every trial is kept (8 bytes each): refused before it is allocated if that exceeds
// half the machine's memory or 16 GiB, rather than ending in an allocation failure hours into the run.
void check_sample_memory(std::uint64_t trials, std::size_t n_outputs, bool adaptive) {
  constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
  const double physical = double(::sysconf(_SC_PHYS_PAGES)) * double(::sysconf(_SC_PAGESIZE));
  const double limit = std::min(physical > 0 ? physical / 2 : 16 * kGiB, 16 * kGiB);
  const double need = 8.0 * double(trials) * double(n_outputs);
  if (need <= limit) return;
  throw InputError(fmt::format(
      "Monte Carlo: {} trials of {} outputs need {:.3g} GiB for the kept values, beyond the limit of {:.3g} "
      "GiB (half the memory, at most 16 GiB); accepted: at most {} trials{}",
      trials, n_outputs, need / kGiB, limit / kGiB, std::uint64_t(limit / (8.0 * double(n_outputs))),
      adaptive ? " (the adaptive procedure: fewer digits or a lower max_trials)" : ""));
}
}  // namespace

namespace {

// The arguments of run_monte_carlo, each refused with what is accepted.
void check_arguments(const std::vector<Tolerance>& sources, int n_outputs,
                     std::vector<std::string>& output_names, const TrialFunction& trial,
                     const PropagationOptions& options, const Eigen::VectorXd* lpu_std) {
  if (n_outputs < 1) throw InputError("Monte Carlo: the model must have at least one output");
  if (output_names.empty())
    for (int o = 0; o < n_outputs; ++o) output_names.push_back(fmt::format("y{}", o + 1));
  if (int(output_names.size()) != n_outputs)
    throw InputError(
        fmt::format("Monte Carlo: {} output names for {} outputs", output_names.size(), n_outputs));
  check_propagation_options(options);  // the rows' ranges, the threads, the coverage interval's ends
  if (lpu_std && lpu_std->size() != n_outputs)
    throw InputError(
        fmt::format("Monte Carlo: {} LPU uncertainties for {} outputs", lpu_std->size(), n_outputs));
  if (!trial) throw InputError("Monte Carlo: no trial function");
  check_source_bounds(sources);
  if (const Eigen::MatrixXd* earlier = options.earlier_samples) {
    const std::uint64_t M = options.trials.value_or(kDefaultMonteCarloTrials);
    if (options.digits > 0 || earlier->cols() != n_outputs || std::uint64_t(earlier->rows()) > M)
      throw InputError(fmt::format("Monte Carlo: {} earlier samples of {} outputs for {} trials of {} outputs{}; "
                                   "accepted: at most M rows of the outputs, for a run of fixed M",
                                   earlier->rows(), earlier->cols(), M, n_outputs,
                                   options.digits > 0 ? " (adaptive)" : ""));
  }
}

// The earlier run's values of its trials (PropagationOptions::earlier_samples) taken: the trial to start at.
std::uint64_t take_earlier(const Eigen::MatrixXd* earlier, std::vector<std::vector<double>>& samples,
                           Progress& progress) {
  if (!earlier || earlier->rows() == 0) return 0;
  for (std::size_t o = 0; o < samples.size(); ++o)
    std::copy_n(earlier->col(Eigen::Index(o)).data(), earlier->rows(), samples[o].begin());
  if (progress.on()) progress.set_done(std::uint64_t(earlier->rows()));
  return std::uint64_t(earlier->rows());
}

// The LPU estimate: the model at the expectations of the sources (all zero).
Eigen::VectorXd model_at_zero(const std::vector<Tolerance>& sources, std::size_t n_out,
                              const std::vector<std::string>& output_names, const TrialFunction& trial) {
  Eigen::VectorXd estimate(static_cast<Eigen::Index>(n_out));
  {
    const std::vector<double> zero(sources.size(), 0.0);
    std::vector<double> out(n_out);
    trial(zero, out);
    for (std::size_t o = 0; o < n_out; ++o) {
      if (!std::isfinite(out[o]))
        throw InputError(
            fmt::format("Monte Carlo: output '{}' is {} with every source at zero", output_names[o], out[o]));
      estimate[Eigen::Index(o)] = out[o];
    }
  }
  return estimate;
}

// §7.9.4 d): the stage's own estimate, standard uncertainty and symmetric interval, per output.
void record_stage(const std::vector<std::vector<double>>& samples, std::uint64_t begin, std::uint64_t block,
                  std::uint64_t q_block, int threads, std::vector<StageValues>& stage) {
  const std::size_t n_out = samples.size();
#pragma omp parallel num_threads(threads) if (n_out > 1)
  {
    std::vector<double> sorted(block);
#pragma omp for schedule(static)
    for (std::int64_t oi = 0; oi < std::int64_t(n_out); ++oi) {
      const auto o = std::size_t(oi);
      const std::span<const double> values(samples[o].data() + begin, block);
      const double m = mean_of(values);
      std::copy(values.begin(), values.end(), sorted.begin());
      sort_tails(sorted, q_block);
      const Interval iv = symmetric_interval(sorted, q_block);
      const double m2 = co_moment(values, m, values, m);
      stage[o].mean.push_back(m);
      stage[o].m2.push_back(m2);
      stage[o].std_dev.push_back(std::sqrt(m2 / double(block - 1)));
      stage[o].low.push_back(iv.low);
      stage[o].high.push_back(iv.high);
    }
  }
}

// f)–i): the spreads of the stage averages against δ of u(y) from all h·M values.
bool stages_stable(const std::vector<StageValues>& stage, std::uint64_t block, int n_dig,
                   MonteCarloDetail& result) {
  bool stable = true;
  for (std::size_t o = 0; o < stage.size(); ++o) {
    OutputSummary& s = result.outputs[o];
    s.delta = tolerance_of(pooled_std(stage[o], block), n_dig);
    s.s_mean = spread_of_average(stage[o].mean);
    s.s_std_dev = spread_of_average(stage[o].std_dev);
    s.s_low = spread_of_average(stage[o].low);
    s.s_high = spread_of_average(stage[o].high);
    if (2 * std::max({s.s_mean, s.s_std_dev, s.s_low, s.s_high}) > s.delta) stable = false;
  }
  return stable;
}

// Means, covariance and correlation of the outputs from all M values, each in a fixed order.
std::vector<double> sample_moments(const std::vector<std::vector<double>>& samples, std::uint64_t M,
                                   int threads, MonteCarloDetail& result) {
  const std::size_t n_out = samples.size();
  const auto n_outputs = Eigen::Index(n_out);
  std::vector<double> means(n_out);
  for (std::size_t o = 0; o < n_out; ++o) means[o] = mean_of(samples[o]);
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t a = 0; a < n_out; ++a)
    for (std::size_t b = a; b < n_out; ++b) pairs.emplace_back(a, b);
  result.covariance.resize(n_outputs, n_outputs);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (pairs.size() > 1)
  for (std::int64_t k = 0; k < std::int64_t(pairs.size()); ++k) {
    const auto [a, b] = pairs[std::size_t(k)];
    const double c = co_moment(samples[a], means[a], samples[b], means[b]) / double(M - 1);
    result.covariance(Eigen::Index(a), Eigen::Index(b)) = c;
    result.covariance(Eigen::Index(b), Eigen::Index(a)) = c;
  }
  result.correlation = result.covariance;
  for (Eigen::Index a = 0; a < n_outputs; ++a)
    for (Eigen::Index b = 0; b < n_outputs; ++b) {
      const double d = std::sqrt(result.covariance(a, a) * result.covariance(b, b));
      result.correlation(a, b) = d > 0 ? result.covariance(a, b) / d : 0.0;
    }
  return means;
}

// Each output's summary: intervals from the sorted values and, with the LPU's u, the validation of §8.
void summarise_outputs(std::vector<std::vector<double>>& samples, const std::vector<double>& means,
                       const Eigen::VectorXd& estimate, const std::vector<std::string>& output_names,
                       const Eigen::VectorXd* lpu_std, std::uint64_t q, double k_p, int n_dig,
                       int histogram_bins, int threads, MonteCarloDetail& result) {
  const std::size_t n_out = samples.size();
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (n_out > 1)
  for (std::int64_t oi = 0; oi < std::int64_t(n_out); ++oi) {
    const auto o = std::size_t(oi);
    std::vector<double>& v = samples[o];
    sort_tails(v, q);  // the order of the trials is no longer needed
    OutputSummary& s = result.outputs[o];
    const std::uint64_t M = v.size(), r = (M - q + 1) / 2;  // the symmetric interval is [y_(r), y_(r+q)]
    s.histogram.lowest = v.front();  // the tails are sorted: the extremes are at the ends
    s.histogram.highest = v.back();
    s.histogram.counts = histogram_counts(v, v.front(), v.back(), histogram_bins);
    s.interval_end_std_error =
        std::max(order_statistic_std_error(v, r, 1, M - q), order_statistic_std_error(v, r + q, q + 1, M));
    s.name = output_names[o];
    s.mean = means[o];
    s.std_dev = std::sqrt(result.covariance(Eigen::Index(o), Eigen::Index(o)));
    const Interval sym = symmetric_interval(v, q);
    const Interval shortest = shortest_interval(v, q);
    s.low_symmetric = sym.low;
    s.high_symmetric = sym.high;
    s.low_shortest = shortest.low;
    s.high_shortest = shortest.high;
    s.estimate = estimate[Eigen::Index(o)];
    if (lpu_std) {
      s.has_lpu = true;
      s.lpu_std = (*lpu_std)[Eigen::Index(o)];
      s.lpu_expanded = k_p * s.lpu_std;
      s.validation_delta = tolerance_of(s.lpu_std, n_dig);
      s.d_low = std::abs(s.estimate - s.lpu_expanded - s.low_symmetric);
      s.d_high = std::abs(s.estimate + s.lpu_expanded - s.high_symmetric);
      s.validated = s.d_low <= s.validation_delta && s.d_high <= s.validation_delta;
    }
  }
}

// What a report needs to say about how the numbers were obtained.
void describe(const std::vector<Tolerance>& sources, const SlotPlan& plan, const GaussianCopula* copula,
              const PropagationOptions& options, std::uint64_t block, std::uint64_t J, int n_dig, double k_p,
              bool has_lpu, int n_outputs, MonteCarloDetail& result) {
  const std::uint64_t M = result.trials, q = result.interval_points;
  const double p = result.coverage_probability;
  const bool adaptive = result.adaptive, converged = result.converged;
  const int threads = result.threads;
  std::string& n = result.notes;
  n += fmt::format(
      "Propagation of distributions by the Monte Carlo method of JCGM 101:2008: M = {} trials, seed {}, "
      "{} thread{}, {:.3g} s.\n",
      format_count(M), options.seed, threads, threads == 1 ? "" : "s", result.seconds);
  if (adaptive)
    n += fmt::format("Adaptive procedure (§7.9.4), n_dig = {}: {} stages of {} trials; {}.\n", n_dig,
                     result.stages, format_count(block),
                     converged
                         ? "every output stable (twice the standard deviation of the stage averages of y, "
                           "u(y) and the interval ends within δ)"
                         : fmt::format("NOT converged: another stage would exceed max_trials = {}",
                                       format_count(options.max_trials.value_or(kDefaultMaxTrials))));
  else
    n += fmt::format("Fixed M (no adaptive check of the numerical accuracy, §7.9 not applied){}.\n",
                     M < J ? fmt::format("; fewer than the {} trials JCGM 101 §7.2 recommends for p = {}",
                                         format_count(J), p)
                           : std::string());
  n += fmt::format(
      "Sources: {} ({} {}draw{}, {} fully correlated group{} sharing one draw: rank correlation 1, same "
      "sign).\n",
      sources.size(), plan.slots - plan.groups, copula ? "" : "independent ",
      plan.slots - plan.groups == 1 ? "" : "s", plan.groups, plan.groups == 1 ? "" : "s");
  if (copula)
    n += fmt::format(
        "Partly correlated draws ([[correlations]]): a Gaussian copula, the {} draws' normal scores "
        "correlated so that each configured Pearson r holds with the two inputs' distributions, which every "
        "input keeps.\n",
        plan.slots);
  n += fmt::format(
      "Coverage intervals (§7.7.2): p = {}, q = {} of the M sorted values; probabilistically "
      "symmetric from r = {}, shortest: the narrowest such window.\n",
      p, format_count(q), format_count((M - q + 1) / 2));
  if (has_lpu)
    n += fmt::format(
        "LPU validation (§8): y = model at the sources' expectations, U_p = {:.4f}·u_c, δ from u_c "
        "with n_dig = {}.\n",
        k_p, n_dig);
  n += fmt::format("Stored outputs: 8·M·{} = {:.3g} MB.\n", n_outputs, double(result.sample_bytes) / 1e6);
}

}  // namespace

namespace {

// The trials of a stage (§7.9.4: at least J, so that an interval has 100 values outside it), or of the whole
// run without stages; two stages must fit within max_trials.
std::uint64_t stage_trials(const PropagationOptions& options, bool adaptive, std::uint64_t J) {
  const std::uint64_t block =
      adaptive ? std::max({options.trials.value_or(kDefaultMonteCarloStage), J, kDefaultMonteCarloStage})
               : options.trials.value_or(kDefaultMonteCarloTrials);
  if (adaptive && options.max_trials.value_or(kDefaultMaxTrials) < 2 * block)
    throw OptionError("max_trials", std::to_string(*options.max_trials),
                      fmt::format("leaves fewer than the 2 stages of {} trials the adaptive procedure needs; "
                                  "accepted: at least {} (or fewer trials a stage)",
                                  block, 2 * block));
  return block;
}

// Each output's sample grown to M values, in steps of 2^20 values, asking the callback between them (it may
// cancel): zero-filling gigabytes takes seconds.
void grow_samples(std::vector<std::vector<double>>& samples, std::uint64_t M, Progress& progress) {
  for (auto& s : samples)
    while (s.size() < M) {
      s.resize(std::min<std::uint64_t>(M, s.size() + (std::uint64_t(1) << 20)));
      progress.poll();
    }
}

// What the stages leave: the trials run and whether two stages agreed.
struct StagesRun {
  std::uint64_t trials = 0;
  bool converged = false;
};
// Stages of `block` trials until two agree to n_dig digits or max_trials would be passed (§7.9.4); one stage
// of every trial without digits. Counts the stages into result.stages.
StagesRun run_stages(const Engine& engine, const PropagationOptions& options, std::uint64_t block,
                     std::uint64_t q_block, int n_dig, std::vector<std::vector<double>>& samples,
                     Progress& progress, MonteCarloDetail& result) {
  const bool adaptive = options.digits > 0;
  std::vector<StageValues> stage(samples.size());
  StagesRun run{0, !adaptive};
  for (int h = 1;; ++h) {
    const std::uint64_t begin = run.trials;
    run.trials += block;
    check_sample_memory(run.trials, samples.size(), adaptive);
    progress.set_stage(run.trials, adaptive ? fmt::format("stage {} ", h) : std::string());
    grow_samples(samples, run.trials, progress);
    engine.run(h == 1 ? take_earlier(options.earlier_samples, samples, progress) : begin, run.trials);
    result.stages = h;
    if (!adaptive) return run;
    record_stage(samples, begin, block, q_block, result.threads, stage);
    if (h >= 2 && stages_stable(stage, block, n_dig, result)) {
      run.converged = true;
      return run;
    }
    if (run.trials + block > options.max_trials.value_or(kDefaultMaxTrials)) return run;
  }
}

// The M × outputs sample into result.samples, for a caller that keeps it.
void keep_samples(const std::vector<std::vector<double>>& samples, std::uint64_t M, MonteCarloDetail& result) {
  result.samples.resize(Eigen::Index(M), Eigen::Index(samples.size()));
  for (std::size_t o = 0; o < samples.size(); ++o)
    result.samples.col(Eigen::Index(o)) = Eigen::Map<const Eigen::VectorXd>(samples[o].data(), Eigen::Index(M));
}

}  // namespace

MonteCarloDetail run_monte_carlo(const std::vector<Tolerance>& sources,
                                 const std::vector<Correlation>& correlations, int n_outputs,
                                 std::vector<std::string> output_names, const TrialFunction& trial,
                                 const PropagationOptions& options, const Eigen::VectorXd* lpu_std) {
  const auto start = Clock::now();
  check_arguments(sources, n_outputs, output_names, trial, options, lpu_std);

  const double p = options.coverage_probability.value_or(kDefaultCoverageProbability);
  const bool adaptive = options.digits > 0;
  const int n_dig = adaptive ? options.digits : 2;
  // J of §7.9.4 b): the least M for which the coverage interval has 100 values outside it.
  const auto J = std::uint64_t(std::ceil(100.0 / (1.0 - p) - 1e-9));
  const std::uint64_t block = stage_trials(options, adaptive, J);

  const SlotPlan plan = plan_slots(sources);
  std::optional<GaussianCopula> copula;
  if (!correlations.empty()) copula = gaussian_copula(sources, correlations);
  const GaussianCopula* copula_used = copula ? &*copula : nullptr;
  const auto n_out = std::size_t(n_outputs);
  const int threads = options.threads > 0 ? options.threads : default_threads();
  const Eigen::VectorXd estimate = model_at_zero(sources, n_out, output_names, trial);

  std::vector<std::vector<double>> samples(n_out);
  Progress progress(options.progress, options.on_progress);
  const Engine engine{sources, plan,    copula_used, trial, output_names, mix64(options.seed),
                      threads, samples, progress};
  MonteCarloDetail result;
  result.adaptive = adaptive;
  result.seed = options.seed;
  result.threads = threads;
  result.coverage_probability = p;
  result.digits = n_dig;
  result.stage_trials = block;
  result.outputs.resize(n_out);
  const StagesRun run =
      run_stages(engine, options, block, interval_points(block, p), n_dig, samples, progress, result);
  progress.finish();

  // Final statistics from all M values, each in a fixed order.
  const std::uint64_t M = run.trials, q = interval_points(M, p);
  result.trials = M;
  result.converged = run.converged;
  result.interval_points = q;
  result.sample_bytes = 8 * M * n_out;
  const std::vector<double> means = sample_moments(samples, M, threads, result);
  const double k_p = normal_erf_quantile(p);
  result.coverage_factor = k_p;
  if (options.keep_samples) keep_samples(samples, M, result);
  summarise_outputs(samples, means, estimate, output_names, lpu_std, q, k_p, n_dig, options.histogram_bins,
                    threads, result);
  samples.clear();
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  describe(sources, plan, copula_used, options, block, J, n_dig, k_p, lpu_std != nullptr, n_outputs, result);
  return result;
}

std::vector<double> draw_sources(const std::vector<Tolerance>& sources,
                                 const std::vector<Correlation>& correlations, std::uint64_t seed,
                                 std::uint64_t trial) {
  check_source_bounds(sources);
  const SlotPlan plan = plan_slots(sources);
  std::optional<GaussianCopula> copula;
  if (!correlations.empty()) copula = gaussian_copula(sources, correlations);
  std::vector<double> draws;
  BatchDrawer(sources, plan, copula ? &*copula : nullptr).draw(mix64(seed), trial, 1, draws);
  return draws;
}

}  // namespace ccal
