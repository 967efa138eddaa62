// The options' tables (core/options.hpp, verbs/*.hpp): the parsers of option text, the ranges and their
// words, the verbs' checks, and that the command line refuses every out-of-range value exactly as the library
// does, but for the option's name (the field's flag).
#include "ccal/core/options.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "ccal/verbs/allocate.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/design.hpp"
#include "ccal/verbs/force.hpp"
#include "ccal/verbs/montecarlo.hpp"
#include "ccal/verbs/simulate.hpp"
#include "cli_support.hpp"

namespace ccal {
namespace {

// The message of the OptionError `f` throws ("" if none).
std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const OptionError& e) {
    return e.what();
  }
  return "";
}

TEST(OptionParsers, WholeNumbersInAnyNotation) {
  EXPECT_EQ(parse_integer_option("trials", "100000", 0, 1e9), 100000);
  EXPECT_EQ(parse_integer_option("trials", "1e5", 0, 1e9), 100000);
  EXPECT_EQ(parse_integer_option("trials", "1E+05", 0, 1e9), 100000);
  EXPECT_EQ(parse_integer_option("trials", "100000.0", 0, 1e9), 100000);
  EXPECT_EQ(parse_integer_option("trials", "+7", 0, 1e9), 7);
  EXPECT_EQ(parse_integer_option("digits", "-3", -5, 5), -3);
  EXPECT_EQ(refusal([] { parse_integer_option("trials", "1.5e0", 0, 1e9); }),
            "trials: 1.5e0 is not a whole number; accepted: a whole number from 0 to 1000000000");
  EXPECT_EQ(refusal([] { parse_integer_option("trials", "lots", 0, 1e9); }),
            "trials: 'lots' is not a number; accepted: a whole number from 0 to 1000000000");
  EXPECT_EQ(refusal([] { parse_integer_option("trials", "", 0, 1e9); }),
            "trials: '' is not a number; accepted: a whole number from 0 to 1000000000");
  // An over-long integer is echoed as typed, not as the nearest 64-bit value.
  constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min(),
                         kMax = std::numeric_limits<std::int64_t>::max();
  EXPECT_EQ(
      refusal([] { parse_integer_option("trials", "99999999999999999999", kMin, kMax); }),
      "trials: 99999999999999999999 is out of range; accepted: a whole number from -9223372036854775808 "
      "to 9223372036854775807");
  EXPECT_EQ(parse_integer_option("trials", "9223372036854775807", kMin, kMax), kMax);
  // 2^63 in float notation is one beyond int64: refused, not converted with undefined behaviour.
  EXPECT_NE(refusal([] { parse_integer_option("trials", "9.223372036854775808e18", kMin, kMax); }), "");
  EXPECT_NE(refusal([] { parse_integer_option("trials", "1e400", 0, 1e9); }), "");
  EXPECT_NE(refusal([] { parse_integer_option("trials", "1e-400", 0, 1e9); }), "");
  EXPECT_NE(refusal([] { parse_integer_option("trials", "inf", 0, 1e9); }), "");
}

TEST(OptionParsers, UnsignedSeeds) {
  EXPECT_EQ(parse_unsigned_option("seed", "18446744073709551615"), 18446744073709551615ull);
  EXPECT_EQ(parse_unsigned_option("seed", "1e19"), 10000000000000000000ull);  // 1e19 is an exact double
  EXPECT_EQ(refusal([] { parse_unsigned_option("seed", "18446744073709551616"); }),
            "seed: 18446744073709551616 is out of range; accepted: a whole number from 0 to "
            "18446744073709551615");
  EXPECT_EQ(refusal([] { parse_unsigned_option("seed", "-1"); }),
            "seed: -1 is out of range; accepted: a whole number from 0 to 18446744073709551615");
  // 2^64 in float notation is the first double beyond the range.
  EXPECT_NE(refusal([] { parse_unsigned_option("seed", "1.8446744073709551616e19"); }), "");
}

TEST(OptionParsers, UnsignedCountsOutOfTheirRangeAreRefusedInTheRangesWords) {
  // An unsigned count (trials) written negative or beyond 2^64 is refused as a signed one would be: with the
  // option's own range, not the type's. Within the type, the parser leaves the range to check_options.
  const OptionRange trials = OptionRange::between(2, 1e9);
  EXPECT_EQ(refusal([&] { parse_unsigned_option("trials", "-5", trials); }),
            "trials: -5 is out of range; accepted: 2 to 1000000000");
  EXPECT_EQ(refusal([&] { parse_unsigned_option("trials", "-1e5", trials); }),
            "trials: -1e5 is out of range; accepted: 2 to 1000000000");
  EXPECT_EQ(refusal([&] { parse_unsigned_option("trials", "1e30", trials); }),
            "trials: 1e30 is out of range; accepted: 2 to 1000000000");
  EXPECT_EQ(parse_unsigned_option("trials", "1", trials), 1u);  // in the type: the table's check speaks
  // Not a whole number, or not a number: the option's range too, not the type's 0 to 2^64 − 1, which would
  // tell the user that 0 or 1e19 trials are accepted.
  EXPECT_EQ(refusal([&] { parse_unsigned_option("trials", "2.5", trials); }),
            "trials: 2.5 is not a whole number; accepted: a whole number from 2 to 1000000000");
  EXPECT_EQ(refusal([&] { parse_unsigned_option("trials", "-2.5", trials); }),
            "trials: -2.5 is not a whole number; accepted: a whole number from 2 to 1000000000");
  EXPECT_EQ(refusal([&] { parse_unsigned_option("trials", "nan", trials); }),
            "trials: 'nan' is not a number; accepted: a whole number from 2 to 1000000000");
  EXPECT_EQ(refusal([&] { parse_unsigned_option("trials", "x", trials); }),
            "trials: 'x' is not a number; accepted: a whole number from 2 to 1000000000");
  // A range with another accepted value is said whole.
  EXPECT_EQ(refusal([&] { parse_unsigned_option("trials", "2.5", trials.or_value(0, "none")); }),
            "trials: 2.5 is not a whole number; accepted: a whole number, 0 (none) or 2 to 1000000000");
  // Without a range (a seed), the type's.
  EXPECT_EQ(refusal([] { parse_unsigned_option("seed", "-1", OptionRange{}); }),
            "seed: -1 is out of range; accepted: a whole number from 0 to 18446744073709551615");
}

TEST(OptionParsers, SignedCountsAreRefusedInTheirRangesWords) {
  // verify_trials is a signed count: 2.5 or 1e30 of it is refused with its range (0: none, or 2 to 10^9), not
  // with int64's limits; without a range, the limits given.
  constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min(),
                         kMax = std::numeric_limits<std::int64_t>::max();
  const OptionRange verify = OptionRange::between(2, 1e9).or_value(0, "none");
  EXPECT_EQ(
      refusal([&] { parse_integer_option("verify_trials", "2.5", kMin, kMax, verify); }),
      "verify_trials: 2.5 is not a whole number; accepted: a whole number, 0 (none) or 2 to 1000000000");
  EXPECT_EQ(refusal([&] { parse_integer_option("verify_trials", "1e30", kMin, kMax, verify); }),
            "verify_trials: 1e30 is out of range; accepted: 0 (none) or 2 to 1000000000");
  EXPECT_EQ(parse_integer_option("verify_trials", "1e4", kMin, kMax, verify), 10000);
  EXPECT_EQ(refusal([&] { parse_integer_option("digits", "x", -5, 5, OptionRange{}); }),
            "digits: 'x' is not a number; accepted: a whole number from -5 to 5");
}

TEST(OptionParsers, RealsAndChoices) {
  EXPECT_EQ(parse_real_option("coverage_probability", " 0.95 "), 0.95);
  EXPECT_EQ(refusal([] { parse_real_option("max_scale", "nan"); }),
            "max_scale: 'nan' is not a finite number; accepted: e.g. 0.5 or 2e-3");
  EXPECT_EQ(parse_choice_option("mode", "paper", kModeNames), 1u);
  EXPECT_EQ(refusal([] { parse_choice_option("mode", "fast", kModeNames); }),
            "mode: 'fast' is not accepted; accepted: 'exact', 'paper'");
}

TEST(OptionRange, WordsWhatItAccepts) {
  EXPECT_EQ(rows::kTrials.text(), "2 to 1000000000");
  EXPECT_EQ(rows::kVerifyTrials.text(), "0 (none) or 2 to 1000000000");
  EXPECT_EQ(rows::kCoverageProbability.text(), "a number in [0.5, 1), e.g. 0.95");
  EXPECT_EQ(OptionRange::at_least(0).open_low().text(), "a number > 0");
  EXPECT_TRUE(rows::kVerifyTrials.accepts(0));
  EXPECT_FALSE(rows::kVerifyTrials.accepts(1));
  EXPECT_FALSE(rows::kCoverageProbability.accepts(1));
  EXPECT_FALSE(rows::kCoverageProbability.accepts(std::nan("")));
  EXPECT_FALSE(OptionRange{}.accepts(INFINITY));
}

TEST(OptionTables, VerbsRefuseOutOfRangeFieldsByName) {
  verbs::MonteCarloOptions mc;
  EXPECT_EQ(refusal([&] { check_options(mc, option_table<verbs::MonteCarloOptions>()); }), "");
  mc.propagation.trials = 0;  // a computed 0 is a mistake, not a request for the default
  EXPECT_EQ(refusal([&] { check_options(mc, option_table<verbs::MonteCarloOptions>()); }),
            "trials: 0 is out of range; accepted: 2 to 1000000000");
  mc = {};
  mc.propagation.coverage_probability = 1.0;
  EXPECT_EQ(refusal([&] { verbs::monte_carlo(bundled_example(), mc); }),
            "coverage_probability: 1 is out of range; accepted: a number in [0.5, 1), e.g. 0.95");
  AllocateOptions allocate;
  EXPECT_EQ(refusal([&] { verbs::allocate(bundled_example(), allocate); }),
            "targets: none given; accepted: at least one COEFF=U");
  allocate.targets = {"K3=1e-3"};
  allocate.verify_trials = 1;
  EXPECT_EQ(refusal([&] { verbs::allocate(bundled_example(), allocate); }),
            "verify_trials: 1 is out of range; accepted: 0 (none) or 2 to 1000000000");
  BudgetOptions budget;
  budget.coverage_factor = 0.95;
  EXPECT_EQ(refusal([&] { verbs::budget(bundled_example(), budget); }),
            "coverage_factor: 0.95 is out of range; accepted: 1 to 10, e.g. 2 (U = k u); a coverage "
            "probability is given as coverage_probability");
  budget.coverage_factor = 2;
  budget.coverage_probability = 0.9;  // two answers to one question
  EXPECT_EQ(
      refusal([&] { verbs::budget(bundled_example(), budget); }),
      "coverage_factor: 2 and coverage_probability 0.9 are two coverages; accepted: one of them (a stated "
      "coverage factor, or a coverage probability)");
  verbs::DesignOptions design;
  design.tradeoff = {0.5, 11};
  EXPECT_EQ(refusal([&] { verbs::design(bundled_example(), design); }),
            "tradeoff: 11 is out of range; accepted: a number in (0, 10], e.g. 0.5,0.75,1");
}

// The number type a field holds (itself, an optional's value, a list's element); void for anything else.
template <class Field>
struct number_of {
  using type = std::conditional_t<std::is_arithmetic_v<Field> && !std::is_same_v<Field, bool>, Field, void>;
};
template <class T>
struct number_of<std::optional<T>> {
  using type = typename number_of<T>::type;
};
template <>
struct number_of<std::vector<double>> {
  using type = double;
};

// A value outside a row's range: below its lower end, or above its upper one, and not its extra value.
std::string out_of_range_value(const OptionRange& r) {
  if (r.low > -1e308) {
    const double below = r.low_open ? r.low : r.low - 1;
    if (!(r.also && *r.also == below)) return option_number_text(below);
    return option_number_text(r.low - 0.5 - (r.low_open ? 0 : 0.5) - 1);
  }
  return option_number_text(r.high + 1);
}

// The same out-of-range value of every numeric option of a verb gives the same words from the command line as
// from the library, with the flag for the field's name.
class SameRefusal : public test::Cli {
 protected:
  template <class Options>
  void check_verb(const std::string& verb, const std::string& extra,
                  const std::function<void(Options&)>& call) {
    for (const OptionSpec<Options>& row : option_table<Options>()) {
      const bool numeric = std::visit(
          [](auto member) {
            if constexpr (std::is_same_v<decltype(member), OptionEnum<Options>>) {
              return false;
            } else {
              using Field = typename decltype(member)::type;
              return !std::is_void_v<typename number_of<Field>::type>;
            }
          },
          row.member);
      if (!numeric || (row.range.low <= -1e308 && row.range.high >= 1e308)) continue;
      if (verb == "force" && row.field == "time") continue;  // --time takes a unit: checked in force's tests
      const std::string value = out_of_range_value(row.range);
      Options options;
      std::visit(
          [&](auto member) {
            if constexpr (!std::is_same_v<decltype(member), OptionEnum<Options>>) {
              using Field = typename decltype(member)::type;
              using Number = typename number_of<Field>::type;
              if constexpr (std::is_same_v<Field, std::vector<double>>)
                member.of(options) = {std::stod(value)};
              else if constexpr (!std::is_void_v<Number>)
                member.of(options) = static_cast<Number>(std::stod(value));
            }
          },
          row.member);
      std::string library;
      try {
        call(options);
      } catch (const OptionError& e) {
        ASSERT_EQ(e.field(), row.field);
        // Every option the message names, worded as the command line spells it.
        library = e.worded(
            [&](std::string_view field) { return cli_flag(OptionSpec<Options>(field, row.member, "", "")); });
      }
      ASSERT_FALSE(library.empty()) << verb << " " << row.field << " = " << value << " was accepted";
      const test::Result r = run(verb + " " + extra + " " + cli_flag(row) + " " + value);
      EXPECT_EQ(r.code, 2) << verb << " " << row.field;
      EXPECT_EQ(r.err, "ccal: error: " + library + "\n") << verb << " " << row.field;
    }
  }
  // The flag of a field as the command line spells it (apps/ccal/option_flags.cpp's rule).
  template <class Options>
  static std::string cli_flag(const OptionSpec<Options>& row) {
    std::string name(row.field == "targets" ? "target" : row.field);
    for (char& c : name)
      if (c == '_') c = '-';
    return "--" + name;
  }
};

TEST_F(SameRefusal, MonteCarlo) {
  check_verb<verbs::MonteCarloOptions>("montecarlo", "",
                                       [](auto& o) { verbs::monte_carlo(bundled_example(), o); });
}
TEST_F(SameRefusal, Allocate) {
  check_verb<AllocateOptions>("allocate", "--target K3=1e-3", [](auto& o) {
    o.targets = {"K3=1e-3"};
    verbs::allocate(bundled_example(), o);
  });
}
TEST_F(SameRefusal, Budget) {
  check_verb<BudgetOptions>("budget", "", [](auto& o) { verbs::budget(bundled_example(), o); });
}
TEST_F(SameRefusal, Design) {
  check_verb<verbs::DesignOptions>("design", "", [](auto& o) { verbs::design(bundled_example(), o); });
}

TEST_F(SameRefusal, ParsersEchoWhatWasTyped) {
  const test::Result seed = run("montecarlo --seed 18446744073709551616");
  EXPECT_EQ(seed.code, 2);
  EXPECT_EQ(seed.err,
            "ccal: error: --seed: 18446744073709551616 is out of range; accepted: a whole number from 0 to "
            "18446744073709551615\n");
  const test::Result trials = run("montecarlo --trials 2.5e0 --format json");
  EXPECT_EQ(trials.code, 2);
  EXPECT_EQ(trials.err.substr(0, 44), "ccal: error: --trials: 2.5e0 is not a whole ");
  // 1.5e3 is a whole number: 1500 trials.
  const test::Result whole = run("montecarlo --trials 1.5e3 --format json");
  EXPECT_EQ(whole.code, 0) << whole.err;
  EXPECT_NE(whole.out.find("\"trials\": 1500"), std::string::npos);
  const test::Result mode = run("simulate --mode fast");
  EXPECT_EQ(mode.err, "ccal: error: --mode: 'fast' is not accepted; accepted: 'exact', 'paper'\n");
}

TEST_F(SameRefusal, UnknownCommandsGetTheNearestName) {
  EXPECT_EQ(
      run("budgte").err,
      "ccal: error: unknown command 'budgte'; did you mean 'budget'? accepted: budget, force, simulate, "
      "identify, reduce, montecarlo, allocate, design, report, history\n");
  EXPECT_EQ(
      run("mont").err,
      "ccal: error: unknown command 'mont'; did you mean 'montecarlo'? accepted: budget, force, simulate, "
      "identify, reduce, montecarlo, allocate, design, report, history\n");
  EXPECT_EQ(
      run("xyz").err,
      "ccal: error: unknown command 'xyz'; accepted: budget, force, simulate, identify, reduce, montecarlo, "
      "allocate, design, report, history\n");
}

TEST_F(SameRefusal, HintsNameTheVerbsOwnHelp) {
  const test::Result r = run("budget --no-such-flag");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("run 'ccal budget --help'"), std::string::npos) << r.err;
}

// The manual page and the completion list every flag of every verb's table, as the program declares them.
TEST_F(SameRefusal, ManPageAndCompletionListEveryFlag) {
  const test::Result man = run("--man-page");
  const test::Result bash = run("--completion bash");
  ASSERT_EQ(man.code, 0) << man.err;
  ASSERT_EQ(bash.code, 0) << bash.err;
  EXPECT_EQ(man.out.rfind(".TH CCAL 1", 0), 0u);
  auto expect_flags = [&]<class Options>(const std::string& verb, std::type_identity<Options>) {
    EXPECT_NE(man.out.find(".SS \"ccal " + verb + "\""), std::string::npos) << verb;
    for (const OptionSpec<Options>& row : option_table<Options>()) {
      if (verb == "force" && row.field == "time") continue;  // declared by hand, with its unit
      std::string flag = cli_flag(row);
      EXPECT_TRUE(bash.out.find(" " + flag + " ") != std::string::npos ||
                  bash.out.find("\"" + flag + " ") != std::string::npos ||
                  bash.out.find(" " + flag + "\"") != std::string::npos)
          << verb << " " << flag;
      std::string roff_flag;  // '-' is written \- in roff
      for (char c : flag) roff_flag += c == '-' ? std::string("\\-") : std::string(1, c);
      EXPECT_NE(man.out.find(roff_flag), std::string::npos) << verb << " " << flag;
    }
  };
  expect_flags("montecarlo", std::type_identity<verbs::MonteCarloOptions>{});
  expect_flags("allocate", std::type_identity<AllocateOptions>{});
  expect_flags("budget", std::type_identity<BudgetOptions>{});
  expect_flags("design", std::type_identity<verbs::DesignOptions>{});
  expect_flags("force", std::type_identity<verbs::ForceOptions>{});
  expect_flags("simulate", std::type_identity<verbs::SimulateOptions>{});
  for (const char* shell : {"zsh", "fish"}) EXPECT_EQ(run(std::string("--completion ") + shell).code, 0) << shell;
  const test::Result other = run("--completion tcsh");
  EXPECT_EQ(other.code, 2);
  EXPECT_EQ(other.err,
            "ccal: error: --completion: 'tcsh' is not a shell ccal completes; accepted: bash, zsh or fish (e.g. "
            "source <(ccal --completion bash))\n");
}

}  // namespace
}  // namespace ccal
