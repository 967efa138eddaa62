// Observability of each term (ccal/reduction/observability.hpp, docs/model.md §14): the whole-revolution plan
// that hides K3, the paper's plan that does not, the measure against closed forms of ⟨a_iⁿ⟩, and its scaling
// with noise and duration.
#include "ccal/reduction/observability.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "experiment_support.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

using ccal::test::kPi;

IdentificationSpec k0_k2_k3() { return paper_spec(); }

// The paper's experiment (Earth rotation off, so that a_i = −A cos γ exactly) with each run lasting
// n_j + turn_fraction platform revolutions, n_j the whole number nearest 450 s, and the initial phase π.
Experiment plan_with_turns(double turn_fraction) {
  Experiment ex = paper_experiment(false);
  for (ccal::Run& run : ex.plan.runs) {
    const double omega = std::sqrt(run.g_level * ex.site.g / ex.geometry.R0);
    const double n = std::round(450.0 * omega / (2 * kPi));
    run.duration = (n + turn_fraction) * 2 * kPi / omega;
    run.terminal_phase.reset();
    run.initial_phase = kPi;
  }
  return ex;
}

Observations<double> error_free_observations(const Experiment& ex) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  return observe<double>(ex, zero, zero, k0_k2_k3());
}

// The problem of the free columns K0, K2, K3 with each run's duration and platform turns; noise N [SI/√Hz].
ObservabilityProblem problem_of(const Experiment& ex, const Observations<double>& obs, double noise) {
  ObservabilityProblem p;
  p.terms = {"K0", "K2", "K3"};
  p.H = obs.regressors.leftCols(3);
  p.other_terms = {"K1"};
  p.others = obs.regressors.rightCols(1);
  for (const ccal::Run& run : ex.plan.runs) {
    RunResolutionInfo r;
    r.duration = run.duration;
    r.input_scale = std::hypot(run.g_level, 1.0);
    r.counter_rotating = true;
    const double omega = std::sqrt(run.g_level * ex.site.g / ex.geometry.R0);
    r.platform_turns = omega * run.duration / (2 * kPi);
    p.runs.push_back(r);
  }
  p.noise_density = noise;
  return p;
}

// Closed forms over a counter-rotating run, γ(t) = φ0 − Ωt, t ∈ [0, T], γT = φ0 − ΩT:
//   ⟨cos²γ⟩ = 1/2 + (sin 2φ0 − sin 2γT) / (4ΩT)
//   ⟨cos³γ⟩ = [F(φ0) − F(γT)] / (ΩT),  F(x) = ∫cos³ = sin x − sin³x / 3
// so ⟨a_i²⟩ = A²⟨cos²γ⟩ and ⟨a_i³⟩ = −A³⟨cos³γ⟩ for a_i = −A cos γ.
struct ClosedForm {
  Eigen::VectorXd h0, h2, h3;
};

ClosedForm closed_form(const Experiment& ex) {
  const auto n = Eigen::Index(ex.plan.runs.size());
  ClosedForm c{Eigen::VectorXd::Ones(n), Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (Eigen::Index j = 0; j < n; ++j) {
    const ccal::Run& run = ex.plan.runs[std::size_t(j)];
    const double A = run.g_level;
    const double omega = std::sqrt(A * ex.site.g / ex.geometry.R0);
    const double wT = omega * run.duration;
    const double phi0 = run.initial_phase ? *run.initial_phase : std::fmod(kPi + wT, 2 * kPi);
    const double gT = phi0 - wT;
    const auto F = [](double x) { return std::sin(x) - std::pow(std::sin(x), 3) / 3; };
    c.h2(j) = A * A * (0.5 + (std::sin(2 * phi0) - std::sin(2 * gT)) / (4 * wT));
    c.h3(j) = -A * A * A * (F(phi0) - F(gT)) / wT;
  }
  return c;
}

// ‖h − (projection of h on the span of a and b)‖, by the 2×2 normal equations in long double (the columns
// here are well conditioned; this is an independent computation, not the library's).
double projected_norm(const Eigen::VectorXd& h, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  long double aa = 0, ab = 0, bb = 0, ah = 0, bh = 0;
  for (Eigen::Index j = 0; j < h.size(); ++j) {
    aa += (long double)a(j) * a(j);
    ab += (long double)a(j) * b(j);
    bb += (long double)b(j) * b(j);
    ah += (long double)a(j) * h(j);
    bh += (long double)b(j) * h(j);
  }
  const long double det = aa * bb - ab * ab;
  const long double ca = (bb * ah - ab * bh) / det, cb = (aa * bh - ab * ah) / det;
  long double sum = 0;
  for (Eigen::Index j = 0; j < h.size(); ++j) {
    const long double r = h(j) - ca * a(j) - cb * b(j);
    sum += r * r;
  }
  return double(std::sqrt(sum));
}

TEST(Observability, WholeRevolutionsHideK3AndSayWhy) {
  // Whole revolutions with a fixed initial phase: ⟨cos³γ⟩ = [F(φ0) − F(φ0 − 2πn)]/ΩT = 0, so the K3 column is
  // round-off (≈ 1e-12 g³ against A³ = 2.7e4 g³) and the plan cannot see K3 at all.
  const Experiment ex = plan_with_turns(0.0);
  const auto obs = error_free_observations(ex);
  const ObservabilityResult r = assess_observability(problem_of(ex, obs, 0.0));
  ASSERT_EQ(r.terms.size(), 3u);
  EXPECT_TRUE(r.whole_revolutions);
  EXPECT_EQ(r.terms[0].status, TermStatus::ok);
  EXPECT_EQ(r.terms[1].status, TermStatus::ok);
  const TermObservability& k3 = r.terms[2];
  EXPECT_EQ(k3.status, TermStatus::unobservable);
  EXPECT_LT(k3.fraction, 1e3 * 2.2e-16);  // the criterion (header: ρ = 1e3 ε)
  EXPECT_NE(k3.reason.find("<a_i^3> averages to round-off in every run"), std::string::npos) << k3.reason;
  EXPECT_NE(k3.reason.find("whole number of platform revolutions"), std::string::npos) << k3.reason;
  EXPECT_NE(k3.fix.find("part-way through a revolution"), std::string::npos) << k3.fix;
  EXPECT_NE(k3.fix.find("fix K3"), std::string::npos) << k3.fix;
  EXPECT_EQ(unobservable_message(k3).rfind("the test plan cannot observe K3: ", 0), 0u);
  ASSERT_NE(r.first(TermStatus::unobservable), nullptr);
  EXPECT_EQ(r.first(TermStatus::unobservable)->term, "K3");

  // Without the runs' turns ccal cannot say why, but still refuses: the column criterion needs no plan.
  ObservabilityProblem bare = problem_of(ex, obs, 0.0);
  bare.runs.clear();
  const ObservabilityResult b = assess_observability(bare);
  EXPECT_EQ(b.terms[2].status, TermStatus::unobservable);
  EXPECT_EQ(b.terms[2].reason.find("whole number"), std::string::npos) << b.terms[2].reason;
  EXPECT_NE(b.terms[2].fix.find("fix K3"), std::string::npos);
}

TEST(Observability, SensitivityEqualsTheClosedFormsIncludingPartialRevolutions) {
  // The paper's T = 450 s (partial last revolutions) and a plan ending a quarter revolution past whole ones:
  // the projected norms of the simulated columns equal those of the closed-form columns. The spectral rule
  // reproduces ⟨cosᵏγ⟩ to 1e-12·Aᵏ (model.md §8), i.e. ~1e-9 of the K3 entries, which are ~1e-3·A³: 1e-8
  // relative on each norm.
  for (const bool quarter : {false, true}) {
    const Experiment ex = quarter ? plan_with_turns(0.25) : paper_experiment(false);
    const auto obs = error_free_observations(ex);
    const ObservabilityResult r = assess_observability(problem_of(ex, obs, 0.0));
    const ClosedForm c = closed_form(ex);
    const double s0 = projected_norm(c.h0, c.h2, c.h3);
    const double s2 = projected_norm(c.h2, c.h0, c.h3);
    const double s3 = projected_norm(c.h3, c.h0, c.h2);
    SCOPED_TRACE(quarter ? "quarter revolution" : "paper plan");
    EXPECT_NEAR(r.terms[0].sensitivity, s0, 1e-8 * s0);
    EXPECT_NEAR(r.terms[1].sensitivity, s2, 1e-8 * s2);
    EXPECT_NEAR(r.terms[2].sensitivity, s3, 1e-8 * s3);
    EXPECT_GT(s3, 0.1);  // a partial revolution leaves a small but non-zero ⟨a_i³⟩ (≈ 1e-4 of A³)
    for (const auto& t : r.terms) EXPECT_EQ(t.status, TermStatus::ok) << t.term;
    // Natural size of K3: ‖((A² + 1)^{3/2})_j‖, and the fraction is the ratio.
    double n3 = 0;
    for (const auto& run : ex.plan.runs) n3 += std::pow(run.g_level * run.g_level + 1, 3);
    EXPECT_NEAR(r.terms[2].natural_norm, std::sqrt(n3), 1e-14 * std::sqrt(n3));
    EXPECT_NEAR(r.terms[2].fraction, s3 / std::sqrt(n3), 1e-8 * s3 / std::sqrt(n3));
  }
}

TEST(Observability, StandardErrorIsNoiseOverSensitivityAndScalesWithNoiseAndDuration) {
  // Equal durations and noise only (no output magnitude given, so no floating-point term): σ = N/√T in every
  // run and u_k = σ/s_k exactly; δK = 3u. Same design with every T × 4: u halves; N × 2: u doubles. Relative
  // 1e-12: a few roundings in the projections.
  const Experiment ex = paper_experiment(false);
  const auto obs = error_free_observations(ex);
  const double N = 1e-3;  // rad/s/√Hz
  const ObservabilityProblem p = problem_of(ex, obs, N);
  const ObservabilityResult r = assess_observability(p);
  const ClosedForm c = closed_form(ex);
  const double sigma = N / std::sqrt(450.0);
  for (Eigen::Index j = 0; j < r.resolution.size(); ++j) EXPECT_NEAR(r.resolution(j), sigma, 1e-15 * sigma);
  const double u3 = sigma / projected_norm(c.h3, c.h0, c.h2);
  EXPECT_NEAR(r.terms[2].standard_error, u3, 1e-8 * u3);  // the closed forms' 1e-8, as above
  EXPECT_NEAR(r.terms[2].min_detectable, 3 * r.terms[2].standard_error, 1e-15 * u3);

  ObservabilityProblem longer = p;
  for (auto& run : longer.runs) run.duration *= 4;
  ObservabilityProblem noisier = p;
  noisier.noise_density = 2 * N;
  const ObservabilityResult rl = assess_observability(longer), rn = assess_observability(noisier);
  for (std::size_t k = 0; k < 3; ++k) {
    const double u = r.terms[k].standard_error;
    EXPECT_NEAR(rl.terms[k].standard_error, u / 2, 1e-12 * u) << r.terms[k].term;
    EXPECT_NEAR(rn.terms[k].standard_error, 2 * u, 1e-12 * u) << r.terms[k].term;
    EXPECT_EQ(rl.terms[k].sensitivity, r.terms[k].sensitivity);  // the sensitivity is the design's alone
  }

  // A quantum q alone: the mean of a count of whole steps errs uniformly over a width q/T, σ = q/(T√12).
  ObservabilityProblem quantised = p;
  quantised.noise_density = 0;
  quantised.quantum = 1e-4;
  const double sq = 1e-4 / (450.0 * std::sqrt(12.0));
  EXPECT_NEAR(assess_observability(quantised).resolution(0), sq, 1e-15 * sq);

  // The floating-point resolution: rounding_ulps·ε·magnitude, here 4·ε·1e4.
  ObservabilityProblem rounded = p;
  rounded.noise_density = 0;
  for (auto& run : rounded.runs) run.output_magnitude = 1e4;
  EXPECT_NEAR(assess_observability(rounded).resolution(0), 4 * 2.220446049250313e-16 * 1e4, 1e-27);
}

TEST(Observability, AWeakTermIsOneTheNoiseHides) {
  // With a reference value below the detection limit the term is weak (warned), above it ok.
  const Experiment ex = paper_experiment(false);
  const auto obs = error_free_observations(ex);
  ObservabilityProblem p = problem_of(ex, obs, 1e-3);
  const double limit = assess_observability(p).terms[2].min_detectable;
  p.reference = Eigen::Vector3d(1.0, 1.0, 0.5 * limit);
  const ObservabilityResult weak = assess_observability(p);
  EXPECT_EQ(weak.terms[2].status, TermStatus::weak);
  EXPECT_FALSE(weak.terms[2].fix.empty());
  EXPECT_EQ(weak.terms[0].status, TermStatus::ok);
  p.reference(2) = -2 * limit;
  EXPECT_EQ(assess_observability(p).terms[2].status, TermStatus::ok);
}

TEST(Observability, AnAliasedColumnNamesItsPartner) {
  // IA horizontal, OA vertical: ⟨a_o²⟩ = 1 in every run, the column of K0: what only K_oo explains is
  // round-off.
  Eigen::MatrixXd h(4, 3);
  h << 1, 12.5, 1, 1, 50, 1, 1, 112.5, 1, 1, 200, 1;
  ObservabilityProblem p;
  p.terms = {"K0", "K2", "K_oo"};
  p.H = h;
  const ObservabilityResult r = assess_observability(p);
  const TermObservability& oo = r.terms[2];
  EXPECT_EQ(oo.status, TermStatus::unobservable);
  EXPECT_EQ(oo.aliased_with, std::vector<std::string>{"K0"});
  EXPECT_NE(oo.reason.find("combination of those of K0"), std::string::npos) << oo.reason;
  EXPECT_NE(oo.fix.find("fix K_oo"), std::string::npos) << oo.fix;
  EXPECT_EQ(r.terms[1].status, TermStatus::ok);
}

TEST(Observability, InconsistentInputIsRejected) {
  ObservabilityProblem p;
  p.terms = {"K0", "K2"};
  p.H = Eigen::MatrixXd::Ones(3, 1);
  EXPECT_THROW(assess_observability(p), std::invalid_argument);
  p.H = Eigen::MatrixXd::Ones(3, 2);
  p.terms = {"K0", "K99"};
  EXPECT_THROW(assess_observability(p), std::invalid_argument);
  p.terms = {"K0", "K2"};
  p.noise_density = -1;
  EXPECT_THROW(assess_observability(p), std::invalid_argument);
  p.noise_density = 0;
  p.runs.resize(2);
  EXPECT_THROW(assess_observability(p), std::invalid_argument);
}

}  // namespace
}  // namespace ccal::test
