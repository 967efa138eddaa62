// Options that hold other options (core/options.hpp): a held struct's rows lifted into its holder's table reach
// the held fields, keep their names, ranges and order, and are checked as the held table checks them; and
// option_arguments writes back exactly the options that differ from the defaults, as the command line reads them.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/core/options.hpp"
#include "ccal/uncertainty/allocate.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/verbs/design.hpp"
#include "ccal/verbs/force.hpp"
#include "ccal/verbs/history.hpp"
#include "ccal/verbs/identify.hpp"
#include "ccal/verbs/montecarlo.hpp"
#include "ccal/verbs/reduce.hpp"
#include "ccal/verbs/report.hpp"
#include "ccal/verbs/simulate.hpp"
#include "ccal/verbs/statement.hpp"

namespace ccal {
namespace {

struct Held {
  double p = 0.95;
  std::optional<ModelMode> mode;
  std::int64_t trials = 10;
};
constexpr OptionSpec<Held> kHeldRows[] = {
    {"p", &Held::p, "p", "a probability", OptionRange::between(0.5, 1).open_high()},
    {"mode", enum_member<&Held::mode>(kModeNames), "MODE", "kinematics"},
    {"trials", &Held::trials, "N", "trials", OptionRange::between(2, 100)},
};

struct Holder {
  bool on = false;
  std::vector<std::string> targets;
  std::optional<std::vector<std::string>> terms;
  Held held;
};
constexpr auto kHolderRows =
    join_rows(std::to_array<OptionSpec<Holder>>({
                  {"on", &Holder::on, "", "a switch"},
                  {"targets", &Holder::targets, "T", "targets"},
                  {"terms", &Holder::terms, "TERMS", "terms"},
              }),
              lifted_rows<&Holder::held, kHeldRows>());
constexpr auto kHolderWithoutMode =
    join_rows(lifted_rows<&Holder::held, kHeldRows, 0, 1>(), lifted_rows<&Holder::held, kHeldRows, 2>());

std::string held_refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const OptionError& e) {
    return e.field() + " | " + e.what();
  }
  return "";
}

TEST(LiftedRows, KeepTheHeldRowsNamesRangesAndOrder) {
  ASSERT_EQ(kHolderRows.size(), 6u);
  for (std::size_t k = 0; k < 3; ++k) {
    const OptionSpec<Holder>& lifted = kHolderRows[3 + k];
    EXPECT_EQ(lifted.field, kHeldRows[k].field);
    EXPECT_EQ(lifted.help, kHeldRows[k].help);
    EXPECT_EQ(lifted.range.low, kHeldRows[k].range.low);
    EXPECT_EQ(lifted.range.high_open, kHeldRows[k].range.high_open);
  }
  // A slice leaves out the rows around it.
  ASSERT_EQ(kHolderWithoutMode.size(), 2u);
  EXPECT_EQ(kHolderWithoutMode[0].field, "p");
  EXPECT_EQ(kHolderWithoutMode[1].field, "trials");
}

TEST(LiftedRows, ReachTheHeldFields) {
  Holder h;
  const auto& p = std::get<OptionField<Holder, double>>(kHolderRows[3].member);
  EXPECT_EQ(&p.of(h), &h.held.p);
  const auto& trials = std::get<OptionField<Holder, std::int64_t>>(kHolderRows[5].member);
  EXPECT_EQ(&trials.of(h), &h.held.trials);
  const auto& mode = std::get<OptionEnum<Holder>>(kHolderRows[4].member);
  EXPECT_FALSE(mode.get(h).has_value());
  mode.set(h, 1);
  ASSERT_TRUE(h.held.mode.has_value());
  EXPECT_EQ(*h.held.mode, ModelMode(1));
  EXPECT_EQ(mode.get(h), std::optional<std::size_t>(1));
}

TEST(LiftedRows, AreCheckedAsTheHeldTableChecksThem) {
  Holder h;
  h.held.trials = 1;
  const std::string held = held_refusal([&] { check_options(h.held, OptionTable<Held>(kHeldRows)); });
  EXPECT_EQ(held, "trials | trials: 1 is out of range; accepted: 2 to 100");
  EXPECT_EQ(held_refusal([&] { check_options(h, OptionTable<Holder>(kHolderRows)); }), held);
  h.held.trials = 10;
  h.held.p = 1;
  EXPECT_EQ(held_refusal([&] { check_options(h, OptionTable<Holder>(kHolderRows)); }),
            held_refusal([&] { check_options(h.held, OptionTable<Held>(kHeldRows)); }));
  EXPECT_NE(held_refusal([&] { check_options(h, OptionTable<Holder>(kHolderRows)); }), "");
}

// The verbs that state a calibration statement hold its options and show its rows, written once.
TEST(LiftedRows, ReduceAndIdentifyShowTheStatementsRows) {
  verbs::ReduceOptions reduce;
  verbs::IdentifyOptions identify;
  const auto reach = [](const auto& table, auto& options, std::string_view field) -> const void* {
    for (const auto& row : table)
      if (row.field == field)
        return std::visit(
            [&](const auto& member) -> const void* {
              if constexpr (requires { member.of(options); })
                return &member.of(options);
              else
                return nullptr;
            },
            row.member);
    return nullptr;
  };
  const auto reduce_rows = option_table<verbs::ReduceOptions>();
  const auto identify_rows = option_table<verbs::IdentifyOptions>();
  EXPECT_EQ(reach(reduce_rows, reduce, "seed"), &reduce.statement_options.seed);
  EXPECT_EQ(reach(reduce_rows, reduce, "coverage_probability"), &reduce.statement_options.coverage_probability);
  EXPECT_EQ(reach(identify_rows, identify, "statement_trials"), &identify.statement_options.statement_trials);
  // reduce's mode is its own (the regressors' model, which the statement's budget then uses), once.
  EXPECT_EQ(reach(reduce_rows, reduce, "mode"), nullptr);  // an enumeration: reached by name, below
  int modes = 0;
  for (const auto& row : reduce_rows) modes += row.field == "mode";
  EXPECT_EQ(modes, 1);
  for (const auto& row : reduce_rows)
    if (const auto* e = std::get_if<OptionEnum<verbs::ReduceOptions>>(&row.member); e && row.field == "mode") {
      e->set(reduce, 1);
      EXPECT_TRUE(reduce.mode.has_value());
      EXPECT_FALSE(reduce.statement_options.mode.has_value());
    }
}

TEST(OptionArguments, NameEveryOptionThatIsNotTheDefault) {
  Holder h;
  EXPECT_TRUE(option_arguments(h, OptionTable<Holder>(kHolderRows)).empty());
  h.on = true;
  h.targets = {"K3=1e-3", "K2=2e-7 deg/s/g^2"};
  h.terms = std::vector<std::string>{"K0", "K2", "K3"};
  h.held.p = 0.9;
  h.held.mode = ModelMode(1);
  h.held.trials = 20;
  const std::vector<std::string> expected = {
      "--on",    "--target", "K3=1e-3",  "--target", "K2=2e-7 deg/s/g^2", "--terms", "K0,K2,K3", "--p", "0.9",
      "--mode", std::string(kModeNames[1]), "--trials", "20"};
  EXPECT_EQ(option_arguments(h, OptionTable<Holder>(kHolderRows)), expected);
  // Against other defaults: only what differs from them.
  Holder defaults = h;
  defaults.held.trials = 10;
  EXPECT_EQ(option_arguments(h, OptionTable<Holder>(kHolderRows), defaults),
            (std::vector<std::string>{"--trials", "20"}));
}

TEST(OptionFlags, AreTheFieldsWithTheListSpellings) {
  EXPECT_EQ(option_flag("coverage_probability"), "--coverage-probability");
  EXPECT_EQ(option_flag("targets"), "--target");
  EXPECT_EQ(option_flag("logs"), "--log");
  EXPECT_EQ(option_flag("targets", "allocate_"), "--allocate-target");
  EXPECT_EQ(option_flag("design_targets"), "--design-target");
}

TEST(OptionHelp, StatesTheRowsRange) {
  const OptionRange p = OptionRange::between(0.5, 1).open_high();
  EXPECT_EQ(option_help("Coverage probability, in {range}", p), "Coverage probability, in [0.5, 1)");
  EXPECT_EQ(option_help("{range} or {range}", OptionRange::between(1, 6)), "[1, 6] or [1, 6]");
  EXPECT_EQ(option_help("no range here", p), "no range here");
  EXPECT_EQ(option_help("{range}", OptionRange::at_least(0).open_low()), "> 0");
  // The coverage probability's help, in every table that has one, states the shared row's range.
  const auto p_help = [](auto table) {
    for (const auto& row : table)
      if (row.field == "coverage_probability") return option_help(row.help, row.range);
    return std::string("(no coverage_probability row)");
  };
  for (const std::string& help :
       {p_help(option_table<verbs::MonteCarloOptions>()), p_help(option_table<AllocateOptions>()),
        p_help(option_table<BudgetOptions>()), p_help(option_table<verbs::DesignOptions>()),
        p_help(option_table<verbs::ReduceOptions>()), p_help(option_table<verbs::ReportOptions>())})
    EXPECT_NE(help.find(rows::kCoverageProbability.interval()), std::string::npos) << help;
}

// A help line that states its range takes it from the row ({range}), never typed out: typed, it would stay
// behind when the row's range changes.
template <class Options>
void expect_no_typed_range(std::string_view table_name) {
  for (const OptionSpec<Options>& row : option_table<Options>()) {
    if (row.range.low <= -1e308 && row.range.high >= 1e308) continue;
    EXPECT_EQ(std::string_view(row.help).find(row.range.interval()), std::string_view::npos)
        << table_name << "." << row.field << ": " << row.help;
  }
}

TEST(OptionHelp, NoHelpLineTypesItsRangeOut) {
  expect_no_typed_range<PropagationOptions>("PropagationOptions");
  expect_no_typed_range<verbs::MonteCarloOptions>("MonteCarloOptions");
  expect_no_typed_range<AllocateOptions>("AllocateOptions");
  expect_no_typed_range<BudgetOptions>("BudgetOptions");
  expect_no_typed_range<verbs::DesignOptions>("DesignOptions");
  expect_no_typed_range<verbs::ForceOptions>("ForceOptions");
  expect_no_typed_range<verbs::IdentifyOptions>("IdentifyOptions");
  expect_no_typed_range<verbs::ReduceOptions>("ReduceOptions");
  expect_no_typed_range<verbs::ReportOptions>("ReportOptions");
  expect_no_typed_range<verbs::SimulateOptions>("SimulateOptions");
  expect_no_typed_range<verbs::StatementOptions>("StatementOptions");
}

}  // namespace
}  // namespace ccal
