// The propagation's options (uncertainty/propagation_options.hpp): run_monte_carlo refuses exactly what the
// table's rows refuse, naming the field, on both sides of every end of every range; and `ccal montecarlo`'s
// table is the engine's rows and the kinematics.
#include "ccal/uncertainty/propagation_options.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <span>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "ccal/verbs/montecarlo.hpp"
#include "option_probes.hpp"

namespace ccal::test {
namespace {

// Thrown by the trial: the engine evaluates the model once before any trial, after all its checks, so a
// run that gets this far has accepted its options (and does no work).
struct PassedTheChecks {};

// The field run_monte_carlo refuses (an OptionError's field), or "" when it gets past its checks.
std::string refused_field(const PropagationOptions& options) {
  Tolerance source;
  source.id = "a";
  source.bound = 1.0;
  const std::vector<Tolerance> sources = {source};
  auto trial = [](std::span<const double>, std::span<double>) { throw PassedTheChecks{}; };
  try {
    run_monte_carlo(sources, 1, {}, trial, options);
  } catch (const PassedTheChecks&) {
    return "";
  } catch (const OptionError& e) {
    return e.field();
  }
  return "(no refusal and no trial)";
}

TEST(PropagationOptions, TheEngineRefusesExactlyWhatEachRowRefuses) {
  const auto make = [](const OptionSpec<PropagationOptions>& row,
                       const OptionProbe& probe) -> std::optional<PropagationOptions> {
    // Starting a thousand threads is the system probe's work (check_thread_count), not the row's.
    if (row.field == "threads" && probe.accepted && probe.value > 64) return std::nullopt;
    // max_trials bounds the adaptive procedure only (refused beside a fixed M): its values in range are probed
    // with digits 1, where one below two stages of 10000 trials is the stage check's to refuse, not the row's.
    if (row.field == "max_trials" && probe.accepted) {
      if (probe.value < 20000) return std::nullopt;
      std::optional<PropagationOptions> o = options_for_probe(row, probe, &PropagationOptions::trials);
      if (o) o->digits = 1;
      return o;
    }
    return options_for_probe(row, probe, &PropagationOptions::trials);
  };
  const int probed = probe_every_numeric_row<PropagationOptions>(make, refused_field, "");
  EXPECT_GE(probed, 19);  // trials, threads, digits, max_trials and p, each on both sides of both ends
}

TEST(PropagationOptions, TheVerbsTableIsTheEnginesRowsAndTheKinematics) {
  const auto engine = option_table<PropagationOptions>();
  const auto verb = option_table<verbs::MonteCarloOptions>();
  ASSERT_EQ(verb.size(), engine.size() + 1);
  for (std::size_t k = 0; k < engine.size(); ++k) {
    EXPECT_EQ(verb[k].field, engine[k].field);
    EXPECT_EQ(verb[k].help, engine[k].help);
    EXPECT_EQ(verb[k].range.low, engine[k].range.low);
    EXPECT_EQ(verb[k].range.high, engine[k].range.high);
  }
  EXPECT_EQ(verb.back().field, "mode");
  // A value set through the verb's row lands in the engine's field.
  verbs::MonteCarloOptions o;
  ASSERT_TRUE(set_numeric_option(o, verb[0], 1234));
  EXPECT_EQ(o.propagation.trials, 1234u);
}

}  // namespace
}  // namespace ccal::test
