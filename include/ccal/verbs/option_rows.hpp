#pragma once
// The options that several verbs take, worded once: the same name, range, default meaning and help in every
// verb that has them (core/options.hpp). A verb's table is made of these rows and its own.

#include <cstdint>
#include <optional>

#include "ccal/core/model_mode.hpp"
#include "ccal/core/options.hpp"
#include "ccal/uncertainty/montecarlo.hpp"

namespace ccal::verbs {

// The trial outputs are stored (8 bytes per trial and coefficient): 10⁹ trials of three coefficients are
// 24 GB, the most accepted.
inline constexpr std::int64_t kMaxMonteCarloTrials = 1000000000;

namespace rows {

inline constexpr OptionRange kTrials = OptionRange::between(2, double(kMaxMonteCarloTrials));
inline constexpr OptionRange kVerifyTrials = kTrials.or_value(0, "none");
inline constexpr OptionRange kThreads = OptionRange::between(1, kMaxThreads).or_value(0, "the OpenMP default");
inline constexpr OptionRange kCoverageProbability = OptionRange::between(0, 1).open_low().open_high().e_g("0.95");

// mode<&Options::mode>(): the kinematics (an optional ModelMode: unset, the configuration's).
template <auto Member, class O = typename member_class<decltype(Member)>::type>
constexpr OptionSpec<O> mode(std::string_view help = "Kinematics: exact (full chain) or paper (Wang & Ren "
                                                     "first-order rules); default: the configuration's "
                                                     "[identification] mode") {
  return {"mode", enum_member<Member>(kModeNames), "MODE", help};
}

template <class O>
constexpr OptionSpec<O> coverage_probability(double O::*member, std::string_view help) {
  return {"coverage_probability", member, "p", help, kCoverageProbability};
}

template <class O>
constexpr OptionSpec<O> seed(std::uint64_t O::*member, std::string_view help) {
  return {"seed", member, "S", help};
}

template <class O>
constexpr OptionSpec<O> threads(int O::*member, std::string_view help = "Threads (0: the OpenMP default); "
                                                                        "the results do not depend on it") {
  return {"threads", member, "K", help, kThreads};
}

template <class O>
constexpr OptionSpec<O> verify_trials(std::int64_t O::*member, std::string_view help) {
  return {"verify_trials", member, "N", help, kVerifyTrials};
}

}  // namespace rows
}  // namespace ccal::verbs
