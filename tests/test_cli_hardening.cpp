// Regression tests of issue-12 hardening at the command line: inputs that used to crash, end with an internal
// error or print a wrong answer as success now give exit code 2 and a one-line message with the accepted range.
#include <gtest/gtest.h>

#include <span>
#include <string>

#include "ccal/allocate.hpp"
#include "ccal/config.hpp"
#include "ccal/errors.hpp"
#include "ccal/montecarlo.hpp"
#include "cli_support.hpp"

namespace ccal::test {
namespace {

using Hardening = Cli;

// Tens of thousands of threads exhausted the OpenMP runtime's stacks (a segmentation fault); the accepted
// range is now 0 (default) or 1…1024, stated in the message.
TEST_F(Hardening, ThreadCountsBeyondTheAcceptedRangeAreRefused) {
  for (const char* command : {"montecarlo --trials 100", "allocate --target K3=1e-6 --verify-trials 100"})
    for (const char* threads : {"70000", "1025", "-1"}) {
      SCOPED_TRACE(std::string(command) + " --threads " + threads);
      expect_bad_input(run(std::string(command) + " --threads " + threads), {"--threads", "1 to 1024"});
    }
  EXPECT_EQ(run("montecarlo --trials 100 --threads 1024").code, 0);  // the limit itself is accepted
}

TEST(HardeningLibrary, ThreadCountsBeyondTheAcceptedRangeAreInputErrors) {
  const Config cfg = bundled_example();
  MonteCarloOptions mo;
  mo.trials = 10;
  mo.threads = kMaxThreads + 1;
  auto trial = [](std::span<const double>, std::span<double> out) { out[0] = 1.0; };
  EXPECT_THROW(run_monte_carlo(cfg.tolerances, 1, {}, trial, mo, nullptr), InputError);
  AllocateOptions ao;
  ao.threads = 100000;
  EXPECT_THROW(allocate_tolerances(cfg, {{"K3", 1e-9}}, ao), InputError);
}

}  // namespace
}  // namespace ccal::test
