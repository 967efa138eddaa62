// One wild value of a log's output or count (run_log_spread.hpp).
#include "run_log_spread.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "run_log_reducer.hpp"

namespace ccal::detail {

std::optional<WildValue> SampleSpread::departs(const Extreme& e, double extra_floor) const {
  if (n_ < 3 || !std::isfinite(e.value)) return std::nullopt;
  // The others: Welford's sums with the extreme taken out.
  const double k = double(n_ - 1);
  const double others_mean = (double(n_) * mean_ - e.value) / k;
  const double others_m2 = std::max(0.0, m2_ - (e.value - mean_) * (e.value - others_mean));
  const double others_sd = std::sqrt(others_m2 / (k - 1));
  const double departure = std::abs(e.value - others_mean);
  if (!(departure > kWildSpread * others_sd && departure > e.floor && departure > extra_floor)) return std::nullopt;
  return WildValue{e.value, e.line, others_mean, others_sd, departure};
}

std::optional<WildValue> SampleSpread::wild(double extra_floor) const {
  const std::optional<WildValue> high = departs(high_, extra_floor), low = departs(low_, extra_floor);
  if (high && low) return high->departure >= low->departure ? high : low;
  return high ? high : low;
}

// A step against the count's direction by more than ten times its mean step is no pulse count (a PIGA's count
// per sample is steady to a few per cent). Alone it is a counter that wraps; undone by the step after it or
// before it (to within ten mean steps), it is one wild count, in the line between the two steps.
namespace {
std::string wild_count(double from, double steps, double back_to) {
  return fmt::format(
      "is a wild count: it steps from {} by {:.3g} times the count's mean step, and the next line "
      "steps back to {}; accepted: a count that steps steadily (a wild count: a glitch, a lost "
      "digit, a cell edited by hand)",
      from, steps, back_to);
}
}  // namespace

void LogReducer::check_count_step(double step, double value, int line) {
  const double mean_step = count_travel_ / double(count_steps_);
  const bool large = std::abs(step) > 10 * mean_step;
  const CountStep before = last_count_step_;
  last_count_step_ = {step, value, line};
  if (held_wrap_) {
    settle_count_wrap(step);
    return;
  }
  const double travel = output_previous_ - output_first_;
  if (!(large && step * travel < 0)) return;
  const bool undoes_before =
      std::abs(before.step) > 10 * mean_step && std::abs(step + before.step) <= 10 * mean_step;
  if (undoes_before && before.line > 0)
    defer_count(before.line, before.value,
                wild_count(before.value - before.step, std::abs(before.step) / mean_step, value));
  else
    held_wrap_ = CountStep{step, value, line};
}

void LogReducer::settle_count_wrap(std::optional<double> next_step) {
  if (!held_wrap_) return;
  const CountStep held = *held_wrap_;
  held_wrap_.reset();
  const double mean_step = count_travel_ / double(std::max<std::size_t>(count_steps_, 1));
  if (next_step && std::abs(*next_step + held.step) <= 10 * mean_step)
    defer_count(held.line, held.value,
                wild_count(held.value - held.step, std::abs(held.step) / mean_step, held.value + *next_step));
  else
    defer_count(
        held.line, held.value,
        fmt::format("follows {} against the count's direction, by {:.3g} times its mean step: a counter "
                    "that wraps; accepted: its width declared (the manifest's columns.counter_bits, e.g. "
                    "16), or a count that does not wrap",
                    held.value - held.step, std::abs(held.step) / mean_step));
}

// A sampled output's floor is ten times its resolution (the least change between two samples: a DAQ's
// rounding), a count's ten counts over its step; the check is stated in docs/model.md §13.
void LogReducer::throw_wild_output() const {
  if (!output_) return;
  const std::optional<WildValue> w = spread_.wild(pulses_ ? 0.0 : 10 * output_resolution_);
  if (!w) return;
  const double scale = pulses_ ? 1.0 : options_.output_scale;
  // The others' spread, or that they are all one value (a steady count's steps).
  const std::string others =
      w->others_sd > 0 ? fmt::format("{:.6g}, standard deviation {:.3g}) by {:.3g} of their standard deviations",
                                     w->others_mean / scale, w->others_sd / scale, w->departure / w->others_sd)
                       : fmt::format("all {:.6g}) by {:.3g}", w->others_mean / scale, w->departure / scale);
  if (pulses_)
    throw cell_error(*output_, w->line,
                     fmt::format("the count's step to this line, {:.6g} counts/s, departs from the log's other "
                                 "steps (in counts/s: {}; accepted: within {:g} of their standard deviations or 10 "
                                 "counts (a wild count in this line or the one before: a glitch, a lost digit, a "
                                 "cell edited by hand)",
                                 w->value, others, kWildSpread));
  throw cell_error(*output_, w->line,
                   fmt::format("{:.6g} departs from the log's other samples ({}; accepted: within {:g} of their "
                               "standard deviations (a wild reading: a glitch, a lost digit, a cell edited by hand)",
                               w->value / scale, others, kWildSpread));
}

void LogReducer::defer_time_order(int line, double t) {
  // Timestamps as written, with the time from the log's first to the ns (ns·1e-9, whose shortest text can
  // have 17 digits, written with 9 decimals and no trailing zeros); other times as read, in seconds.
  const auto ns_text = [](double seconds) {
    std::string text = fmt::format("{:.9f}", seconds);
    text.erase(text.find_last_not_of('0') + 1);
    if (text.back() == '.') text.pop_back();
    return text;
  };
  const std::string what =
      options_.columns.iso_time
          ? fmt::format("'{}' ({} s from the log's first sample) does not follow the sample before it ({} s "
                        "from the first)",
                        iso_field_, ns_text(t - t_first_), ns_text(t_previous_ - t_first_))
          : fmt::format("time {} s does not follow {} s", t, t_previous_);
  defer(Problem::time_order,
        cell_error(time_, line, fmt::format("{}; accepted: strictly increasing times", what)));
}

}  // namespace ccal::detail
