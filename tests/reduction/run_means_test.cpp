// The Monte Carlo's run-mean kernel against the general reduction (average_run over the DynamicChain, itself
// tested against the link-by-link chain) and against the closed form of the error-free means.
#include "ccal/reduction/run_means.hpp"

#include <gtest/gtest.h>

#include <random>

#include "../src/reduction/run_means_nodes.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/reduction/detail/spectral_weights.hpp"
#include "ccal/reduction/run_average.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "experiment_support.hpp"

namespace ccal::test {
namespace {

// The kernel's means and average_run's, run by run, to `relative` of the swing |K1|·A + |K0| of each run.
void expect_same_means(const Experiment& ex, const Eigen::VectorXd& e, const ReductionOptions& options,
                       double relative, const std::string& label) {
  const RunMeanKernel kernel(ex.geometry, ex.layout, ex.site, ex.plan.runs, ex.instrument, options);
  std::vector<double> means(ex.plan.runs.size());
  kernel.means(std::span<const double>(e.data(), std::size_t(e.size())), means);
  for (std::size_t r = 0; r < ex.plan.runs.size(); ++r) {
    const ccal::Run& run = ex.plan.runs[r];
    const double general =
        average_run<double>(ex.geometry, ex.layout, e, ex.site, run, &ex.instrument, {}, options).output;
    const double swing = std::abs(ex.instrument.coefficient("K1").value_or(1.0)) * run.g_level;
    EXPECT_NEAR(means[r], general, relative * swing) << label << ", run " << run.name;
  }
}

TEST(RunMeanKernel, EqualsTheGeneralReductionOnTheBundledTrials) {
  // Draws of every bundled tolerance at ±3σ (ΔΩ included, so two slow nodes), with the trial rule of the
  // Monte Carlo. Both sides evaluate the same exact chain with the same rule; they differ in the order of
  // the floating-point operations (frame-3t coordinates, joint angles by angle addition), so they agree to
  // a few ulps of the swing K1·A per node, summed over 20 nodes: 1e-14 of the swing.
  const Config cfg = bundled_example();
  const Experiment ex = cfg.experiment();
  const CalibrationModel model = calibration_model(cfg);
  std::mt19937 rng(5);
  for (int draw = 0; draw < 4; ++draw) {
    const Eigen::VectorXd e = corner_draw(cfg, 3.0, rng);
    expect_same_means(ex, e, model.reduction(), 1e-14, "draw " + std::to_string(draw));
  }
}

class GeneralCentrifuge : public ::testing::TestWithParam<std::tuple<int, bool>> {};

TEST_P(GeneralCentrifuge, EqualsTheGeneralReduction) {
  // Every part of the kernel away from the paper's case: lever arms L and l, a tilted horizontal axis,
  // harmonic orders 0, 2 and 3 (compiled and run-time orders), Earth rotation, all four mountings, a
  // fixed-platform run, an instrument with cross terms, a rate term, an IA-rate gain and the |a_i|a_i term
  // (automatic M: 512 nodes on the counter-rotating runs, whose a_i changes sign), and
  // optionally wobble angles above 1e-3 rad (the one-node-at-a-time loops with the library cos/sin branch of
  // cos_sin). Same 1e-14-of-swing tolerance as above, for the same reason.
  const auto [order, large_wobbles] = GetParam();
  const Experiment ex = general_centrifuge(order, {200.0, 237.0, 274.0, 311.0, 348.0});  // 200 + 37 k s
  Eigen::VectorXd e = random_errors(ex.layout, 1e-5, 7);
  e[ch::dOmega] = 2e-7;
  e[ch::dthx1t] = 1.5e-3;
  if (large_wobbles) {
    e[ex.layout.harmonic_index(ch::dthy3, 0, false)] = 2e-3;  // above the series threshold
    e[ex.layout.harmonic_index(ch::dthx1, 0, false)] = -1.2e-3;
  }
  expect_same_means(ex, e, ReductionOptions{}, 1e-14, "order " + std::to_string(order));
}
INSTANTIATE_TEST_SUITE_P(RunMeanKernel, GeneralCentrifuge,
                         ::testing::Combine(::testing::Values(0, 2, 3), ::testing::Bool()));

TEST(RunMeanKernel, SlowMomentsInLanesAreTheScalarOnesBitForBit) {
  // The kernel computes ν of all runs' harmonics m ≥ 1 eight at a time (run_nodes::harmonic_moments_lanes)
  // where each takes J_p's recursion; it must give harmonic_slow_moments' bits, lane by lane, for every
  // number of slow nodes. κ/2 from 4 + Q (the recursion's lower end) to 1e5 rad, both signs.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int Q = 1; Q <= detail::kMaxSlowNodes; ++Q) {
    const Eigen::MatrixXd& a = detail::slow_lagrange_monomials(Q);
    constexpr int kCount = 4 * run_nodes::kPackLanes;
    std::vector<double> kappa(kCount), c(kCount), s(kCount), re(std::size_t(kCount * Q)), im(re.size());
    for (int i = 0; i < kCount; ++i) {
      const double k = (4.0 + Q) * std::pow(1e5 / (4.0 + Q), unit(rng)) * (i % 3 == 0 ? -1 : 1);
      kappa[std::size_t(i)] = k;
      c[std::size_t(i)] = std::cos(k);
      s[std::size_t(i)] = std::sin(k);
    }
    run_nodes::harmonic_moments_lanes(kappa.data(), c.data(), s.data(), kCount, a, re.data(), im.data());
    for (int i = 0; i < kCount; ++i) {
      std::vector<double> want_re(static_cast<std::size_t>(Q)), want_im(static_cast<std::size_t>(Q));
      detail::harmonic_slow_moments<double>(kappa[std::size_t(i)], c[std::size_t(i)], s[std::size_t(i)], a,
                                            want_re.data(), want_im.data());
      for (int q = 0; q < Q; ++q) {
        ASSERT_EQ(re[std::size_t(q * kCount + i)], want_re[std::size_t(q)])
            << "Q " << Q << " κ/2 " << kappa[std::size_t(i)];
        ASSERT_EQ(im[std::size_t(q * kCount + i)], want_im[std::size_t(q)])
            << "Q " << Q << " κ/2 " << kappa[std::size_t(i)];
      }
    }
  }
}

TEST(RunMeanKernel, ShortRunsTakeTheSeriesOfTheirSlowMoments) {
  // Runs of a few radians of the arm (|κ/2| < 4 + Q for the first harmonics) leave the lanes to
  // harmonic_slow_moments' series: still average_run's means (1e-14 of the swing, as above), beside long runs
  // of another group.
  Experiment ex = bundled_example().experiment();
  for (std::size_t r = 0; r < ex.plan.runs.size(); ++r) ex.plan.runs[r].duration = r % 2 == 0 ? 0.7 : 450.0;
  Eigen::VectorXd e = Eigen::VectorXd::Zero(ex.layout.size());
  e[ch::dOmega] = 2e-4;  // two slow nodes or more
  e[ch::domega] = 1e-6;
  ReductionOptions options;
  options.quadrature.fast_nodes = 10;
  expect_same_means(ex, e, options, 1e-14, "short and long runs");
}

TEST(RunMeanKernel, FollowsTheSlowNodesALargeMismatchNeeds) {
  // ΔΩ = 2e-5 rad/s over 450 s: a drift that needs Q = 6 slow nodes at the trial tolerance and 10 at the
  // default one; the kernel chooses Q per call like run_quadrature.
  const Config cfg = bundled_example();
  const Experiment ex = cfg.experiment();
  Eigen::VectorXd e = cfg.centrifuge.errors;
  e[ch::dOmega] = 2e-5;
  ReductionOptions trial = calibration_model(cfg).reduction();
  expect_same_means(ex, e, trial, 1e-14, "trial tolerance");
  expect_same_means(ex, e, ReductionOptions{}, 1e-14, "default tolerance");
}

TEST(RunMeanKernel, AWorkspaceCarriesNothingFromCallToCall) {
  // One workspace serves a call of many slow nodes (ΔΩ = 2e-5 rad/s: Q = 6), then one of two, then the first
  // again, and a copy made after it has grown serves a third: each result equals, bit for bit, the call with
  // a fresh workspace. A buffer that kept a value of the larger rule (a stale weight or node) would differ.
  const Config cfg = bundled_example();
  const Experiment ex = cfg.experiment();
  const RunMeanKernel kernel(ex.geometry, ex.layout, ex.site, ex.plan.runs, ex.instrument,
                             calibration_model(cfg).reduction());
  Eigen::VectorXd wide = cfg.centrifuge.errors, narrow = cfg.centrifuge.errors;
  wide[ch::dOmega] = 2e-5;
  narrow[ch::dOmega] = 1e-9;
  const auto span_of = [](const Eigen::VectorXd& e) {
    return std::span<const double>(e.data(), std::size_t(e.size()));
  };
  const auto fresh = [&](const Eigen::VectorXd& e) {
    std::vector<double> out(ex.plan.runs.size());
    kernel.means(span_of(e), out);
    return out;
  };
  RunMeanKernel::Workspace workspace;
  std::vector<double> out(ex.plan.runs.size());
  kernel.means(span_of(wide), out, workspace);
  EXPECT_EQ(out, fresh(wide));
  kernel.means(span_of(narrow), out, workspace);
  EXPECT_EQ(out, fresh(narrow));
  kernel.means(span_of(wide), out, workspace);
  EXPECT_EQ(out, fresh(wide));
  RunMeanKernel::Workspace copy = workspace;
  kernel.means(span_of(narrow), out, copy);
  EXPECT_EQ(out, fresh(narrow));
  EXPECT_NE(fresh(wide), fresh(narrow));  // the two truths differ, so the checks above can fail
}

TEST(RunMeanKernel, ErrorFreeMeansAreTheClosedForm) {
  // No errors, no Earth rate: a_i = −A cos γ exactly, so ⟨output⟩ = Σ K_n Z_n with Z_n the closed form of
  // model.md §8 (nominal_power_mean); round-off of the swing only.
  const Experiment ex = paper_experiment(false);
  const RunMeanKernel kernel(ex.geometry, ex.layout, ex.site, ex.plan.runs, ex.instrument);
  const Eigen::VectorXd e = Eigen::VectorXd::Zero(ex.layout.size());
  std::vector<double> means(ex.plan.runs.size());
  kernel.means(std::span<const double>(e.data(), std::size_t(e.size())), means);
  for (std::size_t r = 0; r < means.size(); ++r) {
    const ccal::Run& run = ex.plan.runs[r];
    const double rate = nominal_rate(run, ex.geometry, ex.site);
    const double phi0 = initial_phase(run, ex.geometry, ex.site);
    double want = 0;
    for (int n = 0; n <= 3; ++n)
      want += ex.instrument.coefficients[n] * nominal_power_mean(n, run.g_level, phi0, rate * run.duration);
    EXPECT_NEAR(means[r], want, 1e-13 * ex.instrument.coefficients[1] * run.g_level) << run.name;
  }
}

TEST(RunMeanKernel, RejectsWhatItCannotEvaluate) {
  const Config cfg = bundled_example();
  const Experiment ex = cfg.experiment();
  ReductionOptions frozen;
  frozen.chain.frozen_platform = true;
  EXPECT_THROW(RunMeanKernel(ex.geometry, ex.layout, ex.site, ex.plan.runs, ex.instrument, frozen),
               std::invalid_argument);
  ReductionOptions odd;
  odd.quadrature.fast_nodes = 9;
  EXPECT_THROW(RunMeanKernel(ex.geometry, ex.layout, ex.site, ex.plan.runs, ex.instrument, odd),
               std::invalid_argument);
  const RunMeanKernel kernel(ex.geometry, ex.layout, ex.site, ex.plan.runs, ex.instrument);
  std::vector<double> errors(std::size_t(ex.layout.size()) - 1, 0.0), means(ex.plan.runs.size());
  EXPECT_THROW(kernel.means(errors, means), std::invalid_argument);
  errors.push_back(0.0);
  std::vector<double> too_few(1);
  EXPECT_THROW(kernel.means(errors, too_few), std::invalid_argument);
  // The right sizes are accepted and give average_run's means (zero errors; same 1e-14-of-swing tolerance).
  kernel.means(errors, means);
  for (std::size_t r = 0; r < means.size(); ++r) {
    const ccal::Run& run = ex.plan.runs[r];
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
    const double general =
        average_run<double>(ex.geometry, ex.layout, zero, ex.site, run, &ex.instrument, {}, {}).output;
    EXPECT_NEAR(means[r], general, 1e-14 * ex.instrument.coefficient("K1").value() * run.g_level) << run.name;
  }
}

TEST(RunMeanKernel, TopHarmonicOfEveryDynamicChannelAtOrdersTwoAndThree) {
  // Only the highest harmonic (c_N, s_N) of every dynamic channel is non-zero, 1e-4 (rad or m): a kernel that
  // stopped its Fourier sum one order early would see an error-free centrifuge. The kernel's mean against
  // average_run (the general chain, itself checked against the link-by-link recursion): 1e-14 of the swing
  // as above. The top harmonics move the means by far more than that (checked: > 1e-9 of the swing), since
  // a harmonic's mean over a run keeps its partial last revolution and its products with the centripetal
  // term.
  for (int order : {2, 3}) {
    Experiment ex = paper_experiment(true, order);
    ex.plan.runs[1].mode = PlatformMode::fixed;
    ex.plan.runs[1].terminal_phase.reset();
    ex.plan.runs[1].initial_phase = 0.7;
    Eigen::VectorXd e = Eigen::VectorXd::Zero(ex.layout.size());
    for (int p = 0; p < ex.layout.size(); ++p) {
      const std::string id = ex.layout.parameter_id(p);
      const std::string top = std::to_string(order);
      if (id.ends_with("_c" + top) || id.ends_with("_s" + top)) e[p] = (p % 2 ? 1e-4 : -0.7e-4);
    }
    ASSERT_GT(e.cwiseAbs().sum(), 0.0);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
    for (const ccal::Run& run : ex.plan.runs) {
      const double moved =
          average_run<double>(ex.geometry, ex.layout, e, ex.site, run, &ex.instrument, {}, {}).output -
          average_run<double>(ex.geometry, ex.layout, zero, ex.site, run, &ex.instrument, {}, {}).output;
      EXPECT_GT(std::abs(moved), 1e-9 * ex.instrument.coefficient("K1").value() * run.g_level) << run.name;
    }
    expect_same_means(ex, e, ReductionOptions{}, 1e-14, "top harmonic, order " + std::to_string(order));
  }
}

}  // namespace
}  // namespace ccal::test
