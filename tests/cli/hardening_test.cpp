// Regression tests of issue-12 hardening at the command line: inputs that used to crash, end with an internal
// error or print a wrong answer as success now give exit code 2 and a one-line message with the accepted
// range.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <span>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/allocate.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
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

// A thread count in range that the system cannot start ended in "libgomp: Thread creation failed", exit
// code 1. Here the limit is the stacks' memory: under ulimit -v 1 GB, with 8 MiB stacks, about a hundred
// threads can start, not 600. The count is refused before any work, naming how many can start; a count the
// system gives runs as before under the same limit.
TEST_F(Hardening, ThreadCountsTheSystemCannotStartAreRefused) {
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer reserves terabytes of shadow memory at start, which `ulimit -v` (the limit that makes
  // thread stacks unobtainable here) forbids: the program could not start at all.
  GTEST_SKIP() << "needs ulimit -v, which AddressSanitizer cannot run under";
#endif
  const std::string limits = "ulimit -s 8192 && ulimit -v 1000000 && ";
  const std::string err = (dir_ / "err.txt").string();
  for (const char* command : {"montecarlo --trials 100", "allocate --target K3=1e-6 --verify-trials 100"}) {
    SCOPED_TRACE(command);
    const int status = std::system(("cd " + quote(dir_.string()) + " && " + limits + quote(kProgram) + " " +
                                    command + " --threads 600 > /dev/null 2> " + quote(err))
                                       .c_str());
    const std::string message = read(err);
    EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 2) << message;
    EXPECT_NE(message.find("--threads: 600 threads cannot be started here"), std::string::npos) << message;
    EXPECT_NE(message.find("accepted: at most"), std::string::npos) << message;
    EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << message;
  }
  const int status = std::system(("cd " + quote(dir_.string()) + " && " + limits + quote(kProgram) +
                                  " montecarlo --trials 100 --threads 2 > /dev/null 2> " + quote(err))
                                     .c_str());
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 0) << read(err);
}

TEST(HardeningLibrary, ThreadCountsBeyondTheAcceptedRangeAreInputErrors) {
  const Config cfg = bundled_example();
  PropagationOptions mo;
  mo.trials = 10;
  mo.threads = kMaxThreads + 1;
  auto trial = [](std::span<const double>, std::span<double> out) { out[0] = 1.0; };
  EXPECT_THROW(run_monte_carlo(cfg.tolerances, 1, {}, trial, mo, nullptr), InputError);
  AllocateOptions ao;
  ao.threads = 100000;
  ao.targets = {"K3=1e-9"};
  EXPECT_THROW(allocate_tolerances(cfg, ao), InputError);
}

// Wrong answers reported as success: results that are not finite, a target no tolerance can meet, an encoder
// log that contradicts the plan. Each used to exit 0 (or 1, an internal error) and is now exit code 2.
TEST_F(Hardening, NonFiniteBudgetIsRefused) {
  // A tolerance of 1e200 m squares to infinity: the budget printed inf and nan with exit code 0.
  std::string text = read(kExample);
  const std::string from = "dx3_s1 = { bound = \"10 um\"";
  text.replace(text.find(from), from.size(), "dx3_s1 = { bound = \"1e200 m\"");
  write("huge.toml", text);
  expect_bad_input(run("budget huge.toml"), {"huge.toml", "dx3_s1", "not a finite number"});
}

TEST_F(Hardening, AnUnreachableTargetIsRefused) {
  // K3 = 1e-300 deg/s/g^3 set every tolerance to 0 and reported "converged"; refused naming the option and
  // the accepted range of the target.
  expect_bad_input(run("allocate --target K3=1e-300 --verify-trials 0"),
                   {"--target: K3=1e-300", "accepted: a target on K3 from "});
}

TEST_F(Hardening, OverflowingFitsAreInputErrors) {
  // x^2 of 1e200 overflows (was an internal error, exit code 1); σ = 1e200 gives a weight that underflows.
  write("big.csv", "x,y\n1e200,1\n2e200,2\n3e200,3\n4e200,4\n");
  expect_bad_input(run("identify big.csv --input-column x --output-column y --terms K0,K1,K2"),
                   {"big.csv:2:1", "K2"});
  write("w.csv", "x,y,s\n1,1,1e200\n2,2,1e200\n3,3.1,1e200\n");
  expect_bad_input(run("identify w.csv --input-column x --output-column y --terms K0,K1 --weight-column s"),
                   {"w.csv:2:3"});
  // A memory request far beyond the machine: refused up front with the memory it needs (was bad_alloc).
  expect_bad_input(run("montecarlo --trials 1000000000"), {"1000000000 trials", "GiB", "accepted: at most"});
}

// Logs of the bundled example's 5g, 10g and 15g runs (R0 = 2.5 m, g = 9.8 m/s²), the main-axis encoder
// turning at rate_factor × the planned rate, in `scale` units per radian.
std::string encoder_log(double g_level, double rate_factor, double scale) {
  const double rate = std::sqrt(g_level * 9.8 / 2.5);
  std::string text = "time,output,theta1\n";
  for (int k = 0; k <= 400; ++k) {
    const double t = 0.05 * k;
    const double angle = std::fmod(rate_factor * rate * t, 2 * std::numbers::pi) * scale;
    text += std::to_string(t) + ",100," + std::to_string(angle) + "\n";
  }
  return text;
}

TEST_F(Hardening, EncoderRatesThatContradictThePlanAreRefused) {
  write("c.toml", read(kExample));
  write("b.csv", encoder_log(10, 1, 1));
  write("d.csv", encoder_log(15, 1, 1));
  const std::string cmd = "reduce c.toml --log 5g=a.csv --log 10g=b.csv --log 15g=d.csv";
  write("a.csv",
        encoder_log(5, 1, 180 / std::numbers::pi));  // degrees, read as radians: K3 = 33.6 with exit code 0
  expect_bad_input(run(cmd), {"a.csv", "theta1", "readings depart", "angle_unit = deg"});
  EXPECT_EQ(run(cmd + " --angle-unit deg").code, 2);  // only a.csv is in degrees now: b.csv is refused
  write("a.csv", encoder_log(5, -1, 1));              // reversed
  expect_bad_input(run(cmd), {"a.csv", "reversed"});
  write("a.csv", encoder_log(5, 1.0 + 1e-4, 1));  // a 100 ppm speed error is accepted
  EXPECT_EQ(run(cmd).code, 0);
}

}  // namespace
}  // namespace ccal::test
