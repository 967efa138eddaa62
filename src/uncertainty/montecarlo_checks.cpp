// The checks of a Monte Carlo run made before any work starts: the sources' bounds, the thread count against
// the range and against what the system can start, and the trial count against the coverage probability.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <system_error>
#include <thread>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "ccal/uncertainty/option_rows.hpp"
#include "sample_statistics.hpp"

namespace ccal {
namespace {

// The threads the process has now (the entries of /proc/self/task; 1 where that cannot be read).
int threads_of_process() {
  std::error_code ec;
  int n = 0;
  for (std::filesystem::directory_iterator it("/proc/self/task", ec), end; !ec && it != end; it.increment(ec))
    ++n;
  return n > 0 ? n : 1;
}

// How many of `wanted` new threads the system starts now: each is started and kept waiting until all are, then
// all end. The OpenMP runtime ends the process (exit 1, "Thread creation failed") when it cannot create a
// thread of a team, so a count beyond the limits (ulimit -u, the cgroup's pids.max, the memory for the
// stacks under ulimit -v) must be found here first. Threads are created with the default attributes, as
// the runtime's are.
int startable_threads(int wanted) {
  std::atomic<bool> release{false};
  std::vector<std::thread> started;
  started.reserve(std::size_t(wanted));
  for (int k = 0; k < wanted; ++k) {
    try {
      started.emplace_back([&release] {
        release.wait(false);  // blocked, not spinning, while the others start
      });
    } catch (const std::system_error&) {
      break;
    }
  }
  release.store(true);
  release.notify_all();
  for (auto& t : started) t.join();
  return int(started.size());
}

}  // namespace

void check_source_bounds(const std::vector<Tolerance>& sources) {
  for (std::size_t j = 0; j < sources.size(); ++j) {
    const Tolerance& t = sources[j];
    if (!std::isfinite(t.bound) || t.bound < 0)
      throw InputError(
          fmt::format("Monte Carlo source {} ('{}'): the bound must be a finite number ≥ 0, not {}", j + 1,
                      t.id, t.bound));
  }
}

void check_thread_count(int threads, const char* what) {
  // The threads row's range (option_rows.hpp), for a caller whose table has no threads row.
  check_option_value(what, double(threads), std::to_string(threads), rows::kThreads);
  // A team of `threads` takes the calling thread and threads − 1 others; threads the process already has
  // (an idle team of an earlier run among them) are counted as available.
  // A count once shown startable is not probed again in this process: a verb checks before its work starts,
  // and each run of the engine after it (the statement's check runs it up to four times) checks again.
  static std::atomic<int> shown_startable{1};
  if (threads <= shown_startable.load()) return;
  const int present = threads_of_process();
  const int needed = threads - present;
  int started = 0;
  if (needed <= 0 || (started = startable_threads(needed)) == needed) {
    int known = shown_startable.load();
    while (known < threads && !shown_startable.compare_exchange_weak(known, threads)) {
    }
    return;
  }
  // An OptionError naming the field, so that each front end words it with its own name of the option.
  throw OptionError(what, std::to_string(threads),
                    fmt::format("threads cannot be started here: the system started only {} more besides the {} "
                                "the process has (limits: ulimit -u, the cgroup's pids.max, the stacks' memory "
                                "under ulimit -v); accepted: at most {}, or 0 (the OpenMP default)",
                                started, present, present + started));
}

std::uint64_t least_trials_for_coverage(double p) {
  if (!(p > 0 && p < 1)) throw InputError(fmt::format("the coverage probability must be in (0, 1), not {}", p));
  // M − 1 − q(M) grows by 0 or 1 with M, and q ≤ M − 1 first holds near M = 1/(2(1 − p)).
  auto M = std::max<std::uint64_t>(2, std::uint64_t(std::max(0.0, std::floor(0.5 / (1 - p)) - 2)));
  while (sample_stats::rounded_points(M, p) > M - 1) ++M;
  return M;
}

void check_coverage_interval(std::uint64_t trials, double p, std::string_view trials_field) {
  if (trials < 2 || !(p > 0 && p < 1)) return;  // refused elsewhere, with their own messages
  const std::uint64_t q = sample_stats::rounded_points(trials, p);
  if (q <= trials - 1) return;
  const std::string trials_name = OptionError::name(std::string(trials_field));
  throw OptionError(
      "coverage_probability", option_number_text(p),
      fmt::format("with {} = {}: the coverage interval [y_(r), y_(r+q)] takes q = round(pM) = {} of the M sorted "
                  "values, so with q = M its ends do not exist (JCGM 101 §7.7.2); accepted: {} at least {} for "
                  "this p (§7.2 recommends M ≥ 10⁴/(1 − p) = {:.3g}), or a coverage probability below "
                  "1 − 1/(2M) = {} for this M",
                  trials_name, trials, q, trials_name, least_trials_for_coverage(p), 1e4 / (1 - p),
                  1 - 0.5 / double(trials)));
}

}  // namespace ccal
