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
  const auto make = [](const OptionSpec<AllocateOptions>& row, const OptionProbe& probe) {
    return options_for_probe(row, probe, &AllocateOptions::verify_trials);
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
