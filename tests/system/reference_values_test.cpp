// Fixed reference values of the bundled example's main outputs (examples/wang_ren_2014.toml, embedded as
// bundled_example()): the run means `ccal simulate` reduces, the coefficients it identifies, the budget's
// standard uncertainties u(K0), u(K2), u(K3) and the Monte Carlo's standard deviations at a fixed seed and
// trial count.
//
// These are pins, not independent references: they record what ccal computed when they were last reviewed,
// so that any change of a headline number is seen. A commit that changes any of them must say in its message
// which value moved, by how much, and why (a physics fix, a new error source or tolerance row in the bundled
// example, a different quadrature or random stream). To update after such a change: run this test, which
// prints every value in the table's format on failure, and paste the new numbers into kPins below.
//
// Tolerance 1e-9 relative for every pin: far above the round-off by which compilers, libm versions or the
// SIMD path could move them (≈ 1e-14 for the budget and run means; the Monte Carlo's trials are seeded per
// trial and summed in a fixed order, so it is bit-identical for any thread count), and far below any change
// of the model (a Coriolis sign moves a run mean by ~1e-4 relative, a new tolerance row moves u by ≥ 1e-6).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/reduction/observe.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "test_constants.hpp"

namespace ccal {
namespace {

struct Pin {
  const char* name;
  double value;  // display units: deg/s, deg/s/g^2, deg/s/g^3
};

// ---- The pinned values (display units), last reviewed with the bundled example of 52 tolerance rows -------
// (48 centrifuge rows and the drives' rate ripple) and the drives' rate noise.
constexpr Pin kPins[] = {
    // Run means of `ccal simulate` (error-free centrifuge, Earth on), deg/s.
    {"mean 5g", 0.8796038729887677},
    {"mean 10g", 2.017806734700501},
    {"mean 15g", 4.344918514720611},
    {"mean 20g", 6.097409216811243},
    {"mean 25g", 6.296002766712433},
    {"mean 30g", 6.336754572036494},
    // Identified coefficients (K1 held at 505.2097 deg/s/g).
    {"identified K0", 0.061973},
    {"identified K2", 0.02},
    {"identified K3", 0.003},
    // Budget (LPU, exact mode, linearised derivatives): standard uncertainties.
    {"budget u(K0)", 0.018359449062132664},
    {"budget u(K2)", 0.00016404382718091572},
    {"budget u(K3)", 0.023509145688946759},
    // Monte Carlo, seed 1, 20 000 trials: standard deviations.
    {"montecarlo u(K0)", 0.018332667387086374},
    {"montecarlo u(K2)", 0.00016393400488296336},
    {"montecarlo u(K3)", 0.023543318065043766},
};
constexpr double kRelativeTolerance = 1e-9;
constexpr std::uint64_t kMonteCarloSeed = 1, kMonteCarloTrials = 20000;
// ------------------------------------------------------------------------------------------------------------

using ccal::test::kDeg;

void expect_pin(const std::string& name, double got_display) {
  for (const Pin& p : kPins)
    if (name == p.name) {
      EXPECT_NEAR(got_display, p.value, kRelativeTolerance * std::abs(p.value))
          << "pin changed; new line: {\"" << name << "\", " << got_display << "},";
      if (std::abs(got_display - p.value) > kRelativeTolerance * std::abs(p.value))
        std::printf("    {\"%s\", %.17g},\n", name.c_str(), got_display);
      return;
    }
  ADD_FAILURE() << "no pin named " << name;
}

TEST(ReferenceValues, SimulatedRunMeansAndIdentifiedCoefficients) {
  const Config cfg = bundled_example();
  const Experiment ex = cfg.experiment();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const Observations<double> obs = observe<double>(ex, cfg.centrifuge.errors, zero, cfg.identification);
  ASSERT_EQ(obs.runs.size(), 6u);
  for (std::size_t j = 0; j < obs.runs.size(); ++j)
    expect_pin("mean " + obs.runs[j], obs.output[Eigen::Index(j)] / kDeg);
  const Eigen::VectorXd k = identify_coefficients<double>(obs, cfg.identification) / kDeg;
  for (std::size_t i = 0; i < cfg.identification.free_terms.size(); ++i)
    expect_pin("identified " + cfg.identification.free_terms[i], k[Eigen::Index(i)]);
}

TEST(ReferenceValues, BudgetStandardUncertainties) {
  const BudgetDetail b = compute_budget(bundled_example());
  for (std::size_t i = 0; i < b.coefficients.size(); ++i)
    expect_pin("budget u(" + b.coefficients[i] + ")", b.standard_uncertainty[Eigen::Index(i)] / kDeg);
}

TEST(ReferenceValues, MonteCarloAtAFixedSeed) {
  const Config cfg = bundled_example();
  const CalibrationModel model = calibration_model(cfg);
  PropagationOptions o;
  o.trials = kMonteCarloTrials;
  o.seed = kMonteCarloSeed;
  const MonteCarloDetail r = run_monte_carlo(monte_carlo_sources(cfg), model.n_outputs(),
                                             model.output_names(), calibration_trial(model), o);
  for (const OutputSummary& out : r.outputs) expect_pin("montecarlo u(" + out.name + ")", out.std_dev / kDeg);
}

}  // namespace
}  // namespace ccal
