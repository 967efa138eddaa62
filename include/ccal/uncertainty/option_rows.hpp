#pragma once
// The options that several verbs and their engines take, worded once: the same name, range, default meaning and
// help in every verb that has them (core/options.hpp). A verb's table is made of these rows and its own, and an
// engine checks its options against the same rows, so it refuses exactly what the verb refuses.

#include <cstdint>
#include <optional>

#include "ccal/core/model_mode.hpp"
#include "ccal/core/options.hpp"
#include "ccal/uncertainty/coverage.hpp"

namespace ccal {

// The accepted thread counts: 0 (the OpenMP default) or 1…kMaxThreads. Far more threads than cores only
// costs memory, and tens of thousands exhaust the OpenMP runtime's stacks (a crash, not an error).
inline constexpr int kMaxThreads = 1024;

// The trial outputs are stored (8 bytes per trial and coefficient): 10⁹ trials of three coefficients are
// 24 GB, the most accepted.
inline constexpr std::int64_t kMaxMonteCarloTrials = 1000000000;

// The Monte Carlo check of a calibration statement (verbs/statement.hpp): 10⁵ trials scatter the interval ends
// by about 0.01 u_c, well inside the §8 tolerance δ of a two-digit u_c (0.005 to 0.05 u_c), at about a second for
// the bundled lab example on two cores.
inline constexpr std::int64_t kDefaultStatementTrials = 100000;
inline constexpr std::string_view kDefaultStatementTrialsText = "100000";
// The seed of a Monte Carlo left unset.
inline constexpr std::uint64_t kDefaultSeed = 1;

namespace rows {

inline constexpr OptionRange kTrials = OptionRange::between(2, double(kMaxMonteCarloTrials));
inline constexpr OptionRange kVerifyTrials = kTrials.or_value(0, "none");
inline constexpr OptionRange kThreads = OptionRange::between(1, kMaxThreads).or_value(0, "the OpenMP default");
// At least ½: an interval that more likely misses the value than holds it is no coverage interval (and p → 0
// takes q = round(pM) = 0 of the M sorted values, an interval of one point).
inline constexpr OptionRange kCoverageProbability = OptionRange::between(0.5, 1)
                                                       .open_high()
                                                       .e_g(kDefaultCoverageProbabilityText)
                                                       .unset_means(kDefaultCoverageProbabilityText);

// mode<&Options::mode>(): the kinematics (an optional ModelMode: unset, the configuration's).
template <auto Member, class O = typename member_class<decltype(Member)>::type>
constexpr OptionSpec<O> mode(std::string_view help = "Kinematics: exact (full chain) or paper (Wang & Ren "
                                                     "first-order rules); default: the configuration's "
                                                     "[identification] mode") {
  return {"mode", enum_member<Member>(kModeNames), "MODE", help};
}

// A field p of a verb that also takes a stated coverage factor is a std::optional<double> (unset:
// kDefaultCoverageProbability, applied where it is used), so that a p given beside a k is refused even when it is
// the default's value; a verb without a coverage factor holds a double.
template <class O, class P>
constexpr OptionSpec<O> coverage_probability(P O::*member, std::string_view help) {
  return {"coverage_probability", member, "p", help, kCoverageProbability};
}

// A stated coverage factor k, used instead of the k of the coverage probability (uncertainty/coverage.hpp).
// k < 1 would make the "expanded" uncertainty smaller than u: a probability given for a factor; k > 10 (a normal
// p of 1 − 1.5e-23) is no contract's, but a typing error (1e308 gave U = 1.8e306 with exit 0).
inline constexpr double kMaxCoverageFactor = 10;
template <class O>
constexpr OptionSpec<O> coverage_factor(std::optional<double> O::*member) {
  return {"coverage_factor", member, "K",
          "A stated coverage factor k instead of the coverage probability's (e.g. 2 by contract); p is then "
          "that of a normal quantity",
          OptionRange::between(1, kMaxCoverageFactor).e_g("2 (U = k u)").noting(
              "a coverage probability is given as "
              "\x1f" "coverage_probability" "\x1f")};  // OptionError::name's marks: worded by each front end
}

// A stated coverage factor and a coverage probability, both given (the default's value too), are two answers to
// one question: refused, naming both.
inline void check_coverage_choice(const std::optional<double>& p, const std::optional<double>& k) {
  if (k && p)
    throw OptionError(
        "coverage_factor", option_number_text(*k),
        "and " + OptionError::name("coverage_probability") + " " + option_number_text(*p) +
            " are two coverages; accepted: one of them (a stated coverage factor, or a coverage "
            "probability)");
}

// The seed and the threads of a Monte Carlo: a plain field, or an optional one where an option that serves
// another (the statement's check) must be told given from left out even at its default (unset: kDefaultSeed, 0).
template <class O, class Seed>
constexpr OptionSpec<O> seed(Seed O::*member, std::string_view help) {
  return {"seed", member, "S", help, OptionRange{}.unset_means("1")};
}

template <class O, class Threads>
constexpr OptionSpec<O> threads(Threads O::*member, std::string_view help = "Threads (0: the OpenMP default); "
                                                                            "the results do not depend on it") {
  return {"threads", member, "K", help, kThreads.unset_means("0")};
}

template <class O, class Count>
constexpr OptionSpec<O> verify_trials(Count O::*member, std::string_view help) {
  return {"verify_trials", member, "N", help, kVerifyTrials};
}

// Optional: given at its default (kDefaultStatementTrials) it is still refused where no statement is checked.
template <class O>
constexpr OptionSpec<O> statement_trials(std::optional<std::int64_t> O::*member) {
  return {"statement_trials", member, "N",
          "Trials of the statement's Monte Carlo check (JCGM 101 §8), whose interval is stated where the "
          "Student-t one fails it; 0: no check",
          kVerifyTrials.unset_means(kDefaultStatementTrialsText)};
}

}  // namespace rows
}  // namespace ccal
