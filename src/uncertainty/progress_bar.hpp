#pragma once
// The Monte Carlo's progress bar (private to the library): one line on standard error, only when it is a
// terminal, redrawn at most every 0.1 s and never wider than the terminal (a line that wraps would scroll
// the screen at every redraw); tick() is cheap enough to call once per trial from every thread.
#include <fmt/format.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

#include "ccal/core/progress.hpp"

namespace ccal::progress_bar {

using Clock = std::chrono::steady_clock;

// Columns of standard error's terminal (80 if it cannot tell).
inline std::size_t stderr_columns() {
  winsize size{};
  if (ioctl(fileno(stderr), TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

// The line for a terminal of `columns`: label, bar, figures; the bar (10 to 50 wide) and then the rate and
// counts give way on a narrow terminal, and the line stays one column short of the edge.
// `unit` names what is counted ("trials", "runs", …).
inline std::string progress_line(const std::string& label, double fraction, std::uint64_t done,
                                 std::uint64_t target, double rate, const std::string& eta,
                                 std::size_t columns, const std::string& unit = "trials") {
  const std::size_t room = columns > 1 ? columns - 1 : 0;
  const std::string percent = fmt::format("{:5.1f} %", 100.0 * fraction);
  std::string tail =
      fmt::format("{} {}/{} {}  {:.3g} {}/s  ETA {}", percent, done, target, unit, rate, unit, eta);
  if (label.size() + tail.size() + 13 > room) tail = fmt::format("{} ETA {}", percent, eta);
  std::string line = label;
  if (label.size() + tail.size() + 13 <= room) {
    const std::size_t width = std::min<std::size_t>(50, room - label.size() - tail.size() - 3);
    const auto filled = std::size_t(fraction * double(width));
    line += '[';
    line.append(filled, '#');
    line.append(width - filled, ' ');
    line += "] ";
  }
  line += tail;
  if (line.size() > room) line.resize(room);
  return line;
}

inline std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds > 359999) return "--:--:--";
  const auto s = std::int64_t(seconds + 0.5);
  return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
}

// A one-line bar on stderr, redrawn at most every 0.1 s by whichever thread finishes a trial first after
// that.
class Progress {
 public:
  // The bar when wanted and stderr is a terminal; the callback (if any) at the same moments, whatever stderr.
  explicit Progress(bool wanted, ProgressCallback callback = {})
      : on_(wanted && isatty(fileno(stderr)) != 0), callback_(std::move(callback)), start_(Clock::now()) {}
  ~Progress() { finish(); }
  bool on() const { return on_ || callback_; }

  // The trials of the current stage end at `target`; `label` describes it ("" for a fixed M).
  void set_stage(std::uint64_t target, std::string label) {
    target_ = target;
    label_ = std::move(label);
  }
  void tick() {
    const std::uint64_t done = done_.fetch_add(1, std::memory_order_relaxed) + 1;
    if (done % 8 != 0) return;
    const auto now = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start_).count();
    std::int64_t last = last_ns_.load(std::memory_order_relaxed);
    if (now - last < 100'000'000) return;
    if (!last_ns_.compare_exchange_strong(last, now, std::memory_order_relaxed)) return;
    if (on_) draw(done, double(now) * 1e-9);
    if (callback_) callback_(done, target_);  // may throw Cancelled: the caller records it as the trial's
  }
  // A new stage of other work (`unit` counts it): the count, the clock and the ETA start again.
  void restart(std::uint64_t target, std::string label, std::string unit) {
    const std::lock_guard lock(mutex_);
    target_ = target;
    label_ = std::move(label);
    unit_ = std::move(unit);
    done_.store(0, std::memory_order_relaxed);
    last_ns_.store(0, std::memory_order_relaxed);
    start_ = Clock::now();
  }
  // The work done of a stage that counts in steps (not once per item from many threads): drawn now.
  void set_done(std::uint64_t done) {
    done_.store(done, std::memory_order_relaxed);
    if (on_) draw(done, std::chrono::duration<double>(Clock::now() - start_).count());
  }
  // The callback now, unthrottled (between the steps of a long preparation): it may throw Cancelled.
  void poll() {
    if (callback_) callback_(done_.load(std::memory_order_relaxed), target_);
  }
  void finish() {
    if (!on_ || finished_) return;
    finished_ = true;
    draw(done_.load(), std::chrono::duration<double>(Clock::now() - start_).count());
    std::fputc('\n', stderr);
    std::fflush(stderr);
  }

 private:
  void draw(std::uint64_t done, double seconds) {
    const std::lock_guard lock(mutex_);
    const double fraction = target_ ? std::min(1.0, double(done) / double(target_)) : 0.0;
    const double rate = seconds > 0 ? double(done) / seconds : 0.0;
    const double eta = rate > 0 ? double(target_ > done ? target_ - done : 0) / rate : NAN;
    const std::string line =
        progress_line(label_, fraction, done, target_, rate, clock_text(eta), stderr_columns(), unit_);
    // \r, the line, then erase to the end of the line (what a longer previous line left).
    fmt::print(stderr, "\r{}\x1b[K", line);
    std::fflush(stderr);
  }

  bool on_;
  ProgressCallback callback_;
  bool finished_ = false;
  Clock::time_point start_;
  std::atomic<std::uint64_t> done_{0};
  std::atomic<std::int64_t> last_ns_{0};
  std::uint64_t target_ = 0;
  std::string label_;
  std::string unit_ = "trials";
  std::mutex mutex_;
};

}  // namespace ccal::progress_bar
