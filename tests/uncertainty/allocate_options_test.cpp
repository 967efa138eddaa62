// The allocation's options (uncertainty/allocate.hpp AllocateOptions and its table): allocate_tolerances
// refuses exactly what the table's rows refuse, naming the field, on both sides of every end of every range;
// `ccal allocate`, Python's allocate() and the report's allocation section take this one struct.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/allocate.hpp"
#include "option_probes.hpp"

namespace ccal::test {
namespace {

// The field allocate_tolerances refuses first. The target names no coefficient of the configuration, and the
// targets are read after every option's row and cross-check, so an allocation whose options pass is refused
// for its target (and does no work).
std::string allocation_refusal(const Config& config, AllocateOptions options) {
  options.targets = {"K9=1"};
  try {
    allocate_tolerances(config, options);
  } catch (const OptionError& e) {
    return e.field();
  }
  return "(accepted)";
}

TEST(AllocateOptions, TheEngineRefusesExactlyWhatEachRowRefuses) {
  const Config config = bundled_example();
  const auto make = [](const OptionSpec<AllocateOptions>& row,
                       const OptionProbe& probe) -> std::optional<AllocateOptions> {
    AllocateOptions o;
    // p = ½ lets M = 2 trials give the interval's ends (q = round(pM) = 1 ≤ M − 1); probing p, 10⁶ trials
    // give them for p up to 1 − 5·10⁻⁷, above which the rule for M refuses what the row accepts.
    o.coverage_probability = 0.5;
    if (row.field == "coverage_probability") {
      o.verify_trials = 1000000;
      if (probe.accepted && probe.value > 1 - 5e-7) return std::nullopt;
    }
    return o;
  };
  const auto refusal = [&](const AllocateOptions& o) { return allocation_refusal(config, o); };
  const int probed = probe_every_numeric_row<AllocateOptions>(make, refusal, "targets");
  EXPECT_GE(probed, 18);  // p, max_scale, verify_trials and threads, each on both sides of both ends
}

TEST(AllocateOptions, AnEmptyListOfTargetsIsRefusedByItsRow) {
  AllocateOptions o;
  try {
    allocate_tolerances(bundled_example(), o);
    ADD_FAILURE() << "accepted";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "targets");
    EXPECT_NE(std::string(e.what()).find("accepted: at least one"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ccal::test
