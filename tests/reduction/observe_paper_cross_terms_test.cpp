// Paper mode with cross terms and Earth rotation on (docs/model.md §5.1, "Cross terms"): the instrument
// polynomial is evaluated at the paper's first-order a_i, the constant Coriolis term −C included, in the
// truth and in the model's regressors alike. Every expectation is a closed form evaluated here, independently
// of the library's quadrature and least squares: the run means of trigonometric polynomials of degree ≤ 3
// from an 8-point DFT integrated harmonic by harmonic over the run's phase sweep, the fit by Eigen's QR.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <functional>
#include <numbers>

#include "ccal/uncertainty/budget.hpp"
#include "experiment_support.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

using ccal::test::kPi;

// One run of a plan in the closed forms: A [g], Ω [rad/s], γ = φ0 − sweep·s, s ∈ [0, 1].
struct RunPhase {
  double A = 0, omega = 0, phi0 = 0, sweep = 0;
};

RunPhase run_phase(const Experiment& ex, const ccal::Run& run) {
  RunPhase r;
  r.A = run.g_level;
  r.omega = std::sqrt(run.g_level * ex.site.g / ex.geometry.R0);  // model.md §6
  const bool fixed = run.mode == PlatformMode::fixed;
  r.sweep = fixed ? 0.0 : r.omega * run.duration;
  // model.md §6.1: φ0 = (ψ + ΩT) mod 2π on a counter-rotating platform.
  r.phi0 = run.initial_phase ? *run.initial_phase : std::fmod(*run.terminal_phase + r.sweep, 2 * kPi);
  return r;
}

// ⟨f(γ)⟩ over the run for a trigonometric polynomial f of degree ≤ 3 (exact: 8 samples resolve the
// harmonics 0…3, and each harmonic is integrated in closed form over γ ∈ [φ0 − sweep, φ0]).
double run_mean(const std::function<double(double)>& f, const RunPhase& r) {
  if (r.sweep == 0.0) return f(r.phi0);
  constexpr int N = 8;
  double mean = 0, a[4] = {}, b[4] = {};
  for (int m = 0; m < N; ++m) {
    const double x = 2 * kPi * m / N, v = f(x);
    mean += v / N;
    for (int k = 1; k <= 3; ++k) {
      a[k] += 2 * v * std::cos(k * x) / N;
      b[k] += 2 * v * std::sin(k * x) / N;
    }
  }
  const double g1 = r.phi0, g0 = r.phi0 - r.sweep;
  for (int k = 1; k <= 3; ++k)
    mean += (a[k] * (std::sin(k * g1) - std::sin(k * g0)) - b[k] * (std::cos(k * g1) - std::cos(k * g0))) /
            (k * r.sweep);
  return mean;
}

// The paper's constant Coriolis term of a_i is −C, C = 2 ω_e R0 Ω sin φ / g [g] (model.md §5.1).
double coriolis(const Experiment& ex, const RunPhase& r) {
  return 2 * ex.site.earth_rate * ex.geometry.R0 * r.omega * std::sin(ex.site.latitude) / ex.site.g;
}

using Input = std::function<double(double gamma, const RunPhase&)>;  // a_i [g] at γ

// K̂ − K (K0, K2, K3 free, K1 fixed; °/s/gⁿ) when the instrument sees a_truth and the model's regressors are
// the means of powers of a_model: H_j = (1, ⟨a_m²⟩, ⟨a_m³⟩), b_j = Σ_{n=1..3} K_n (⟨a_tⁿ⟩ − ⟨a_mⁿ⟩).
Eigen::Vector3d closed_form_bias(const Experiment& ex, const Input& truth, const Input& model) {
  const double K[4] = {0, ex.instrument.coefficient("K1").value() / kDeg,
                       ex.instrument.coefficient("K2").value() / kDeg,
                       ex.instrument.coefficient("K3").value() / kDeg};
  const auto n = Eigen::Index(ex.plan.runs.size());
  Eigen::MatrixXd H(n, 3);
  Eigen::VectorXd b(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const RunPhase r = run_phase(ex, ex.plan.runs[std::size_t(j)]);
    auto mean_power = [&](const Input& a, int p) {
      return run_mean([&](double g) { return std::pow(a(g, r), p); }, r);
    };
    H.row(j) << 1.0, mean_power(model, 2), mean_power(model, 3);
    b[j] = 0;
    for (int p = 1; p <= 3; ++p) b[j] += K[p] * (mean_power(truth, p) - mean_power(model, p));
  }
  return H.colPivHouseholderQr().solve(b);
}

const Input kNominal = [](double g, const RunPhase& r) { return -r.A * std::cos(g); };

Eigen::VectorXd coriolis_row(const Experiment& ex, ModelMode mode, bool cross_terms) {
  IdentificationSpec spec = paper_spec();
  spec.paper_cross_terms = cross_terms;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const auto rows = compensation_choices(ex, spec, zero, zero, mode, false);
  EXPECT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows.at(1).id, "coriolis");
  return rows.at(1).bias / kDeg;
}

void expect_relative(const Eigen::VectorXd& got, const Eigen::Vector3d& want, double tol, const char* what) {
  const char* names[] = {"K0", "K2", "K3"};
  for (Eigen::Index k = 0; k < 3; ++k)
    EXPECT_NEAR(got[k], want[k], tol * std::abs(want[k])) << what << ", " << names[k];
}

// The budget's Coriolis row (the paper's constant Coriolis term left out of the model), on the paper's plan.
// With cross terms the instrument sees a0 − C in every term: b_j = Σ K_n (⟨(a0 − C)ⁿ⟩ − ⟨a0ⁿ⟩) ≈
// −C (K1 + 2K2⟨a0⟩ + 3K3⟨a0²⟩), ΔK = (−6.5639e-2, −2.3267e-4, −6.7495e-3). Without them, the paper's K1-only
// rule b_j = −K1 C, ΔK = (−6.5673e-2, −2.3022e-4, −6.7777e-3): the two differ by 5e-4, 1.1e-2 and 4.2e-3
// relative. Tolerance 1e-8 relative: both sides are exact (the library's quadrature integrates these
// trigonometric polynomials exactly), what is left is round-off of outputs of size K1·A ≈ 1.5e4 °/s
// against biases of 1e-4…1e-1, amplified by the conditioning of the design (K3's column is the partial
// revolution's ⟨cos³γ⟩ ≈ 1e-4).
TEST(PaperCoriolis, RowEqualsTheClosedFormOnThePapersPlan) {
  const Experiment ex = paper_experiment(true);
  const Input with = [&](double g, const RunPhase& r) { return kNominal(g, r) - coriolis(ex, r); };
  const Eigen::Vector3d cross = closed_form_bias(ex, with, kNominal);
  expect_relative(coriolis_row(ex, ModelMode::paper, true), cross, 1e-8, "cross terms");
  EXPECT_NEAR(cross[0], -6.5639e-2, 1e-4 * 6.5639e-2);
  EXPECT_NEAR(cross[1], -2.3267e-4, 1e-4 * 2.3267e-4);
  EXPECT_NEAR(cross[2], -6.7495e-3, 1e-4 * 6.7495e-3);

  // K1-only: the truth's −K1 C with the same design.
  const auto n = Eigen::Index(ex.plan.runs.size());
  Eigen::MatrixXd H(n, 3);
  Eigen::VectorXd b(n);
  const double K1 = ex.instrument.coefficient("K1").value() / kDeg;
  for (Eigen::Index j = 0; j < n; ++j) {
    const RunPhase r = run_phase(ex, ex.plan.runs[std::size_t(j)]);
    auto mean_power = [&](int p) {
      return run_mean([&](double g) { return std::pow(kNominal(g, r), p); }, r);
    };
    H.row(j) << 1.0, mean_power(2), mean_power(3);
    b[j] = -K1 * coriolis(ex, r);
  }
  const Eigen::Vector3d k1_only = H.colPivHouseholderQr().solve(b);
  expect_relative(coriolis_row(ex, ModelMode::paper, false), k1_only, 1e-8, "K1 only");
  EXPECT_NEAR(k1_only[0], -6.5673e-2, 1e-4 * 6.5673e-2);
  EXPECT_GT(std::abs(cross[1] - k1_only[1]), 1e-2 * std::abs(cross[1]));  // the rows must be told apart
}

// Where the paper's constant is the physical Coriolis term: a fixed platform with the IA radially outward
// (γ = 0). 2 ω_ie × v with v = Ω R0 y1 has the radial component −2 ω_e Ω R0 sin φ, constant in the arm
// frame, and the IA is the radial: the exact chain's a_i is −A − C exactly, so the exact pipeline's Coriolis
// row must equal paper mode's with cross terms, both equal to the closed form with ⟨a0ⁿ⟩ = (−A)ⁿ.
// Tolerance 1e-8 relative: round-off, as above (the exact chain's mean of a constant is exact too). The
// K1-only row misses 2K2 A C − 3K3 A² C per run, 0.1…1.4 % of K1 C between 10 and 30 g.
TEST(PaperCoriolis, ExactChainAgreesOnAFixedRadialPlatform) {
  Experiment ex = paper_experiment(true);
  for (auto& run : ex.plan.runs) {
    run.mode = PlatformMode::fixed;
    run.terminal_phase.reset();
    run.initial_phase = 0.0;
  }
  const Input with = [&](double g, const RunPhase& r) { return kNominal(g, r) - coriolis(ex, r); };
  const Eigen::Vector3d closed = closed_form_bias(ex, with, kNominal);
  expect_relative(coriolis_row(ex, ModelMode::exact, false), closed, 1e-8, "exact chain");
  expect_relative(coriolis_row(ex, ModelMode::paper, true), closed, 1e-8, "paper, cross terms");
  const Eigen::VectorXd k1_only = coriolis_row(ex, ModelMode::paper, false);
  EXPECT_GT((k1_only - closed).cwiseQuotient(closed).cwiseAbs().maxCoeff(), 1e-3);
}

// With no pose error the cross-term regressors are the means of the powers of a0 − C (closed form), and
// Z1 is the plain one's (the Coriolis term is in the K1 term in both). With Earth rotation off the two forms
// agree to round-off: the nodes' Coriolis term is then −a_i − A cos γ with A evaluated in two orders of
// operations, a few ulp of A (tolerance 1e-14 of Aⁿ, of the output's K1·A).
TEST(PaperCrossTermsEarth, ErrorFreeRegressorsAreThePowersOfThePapersInput) {
  std::vector<TermSpec> terms;
  for (const char* id : {"K0", "K1", "K2", "K3"}) terms.push_back(parse_term(id).value());
  for (bool earth : {false, true}) {
    const Experiment ex = paper_experiment(earth);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
    for (const auto& run : ex.plan.runs) {
      SCOPED_TRACE(run.name + (earth ? ", Earth on" : ", Earth off"));
      const auto plain = paper_average<double>(ex, zero, run, &ex.instrument, terms, false);
      const auto cross = paper_average<double>(ex, zero, run, &ex.instrument, terms, true);
      EXPECT_EQ(cross.regressors[1], plain.regressors[1]);
      const RunPhase r = run_phase(ex, run);
      if (!earth) {
        for (Eigen::Index k = 0; k < 4; ++k)
          EXPECT_NEAR(cross.regressors[k], plain.regressors[k], 1e-14 * std::pow(r.A, double(k))) << k;
        EXPECT_NEAR(cross.output, plain.output, 1e-14 * 505.2097 * kDeg * r.A);
        continue;
      }
      const double C = coriolis(ex, r);
      // Z2 to 1e-12 of A², Z3 to 1e-12 of A³: round-off of the quadrature's weighted sums.
      for (int p = 2; p <= 3; ++p)
        EXPECT_NEAR(cross.regressors[p],
                    run_mean([&](double g) { return std::pow(kNominal(g, r) - C, p); }, r),
                    1e-12 * std::pow(r.A, p))
            << "Z" << p;
    }
  }
}

// Δθz5 = 1e-5 rad with cross terms. Earth off: model.md V3 gives ΔK0 = −1.9171e-5, ΔK2 = +2.1254e-8,
// ΔK3 = +9.1580e-6 °/s/gⁿ (tolerance 5e-4 relative for the linear-with-cross-terms model, as in
// test_simulate). Earth on: a_i = a0 − C + A δ sin γ in the truth and a0 − C in the model (no Earth-rate
// term: the paper's IA rate has no Δθz5 row), ΔK from the closed form, exact in δ: tolerance 1e-6 relative.
// ΔK is K̂ − K, and K̂ carries round-off of ≈ 1e-13 of K (6e-11 for the ill-conditioned K3), while these
// biases are 1e-6 (K2) to 3e-3 (K3) of K: measured 1e-8 … 8e-8 relative. The product C·δ moves K2
// by a third: K3's column ⟨a_i³⟩ is the partial revolution's −A³⟨cos³γ⟩ plus the 3C⟨a0²⟩ = 3CA²/2 of the
// constant Coriolis term, comparable in size (model.md §5.1).
TEST(PaperCrossTermsEarth, AzimuthErrorMatchesTheClosedForm) {
  IdentificationSpec cross = paper_spec();
  cross.paper_cross_terms = true;
  const Eigen::Vector3d truth(0.061973, 0.02, 0.003);
  auto bias = [&](const Experiment& ex) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(ex.layout.size());
    e[ch::dthz5] = 1e-5;
    return Eigen::Vector3d(identified_deg(ex, e, cross, ModelMode::paper) - truth);
  };
  const Eigen::Vector3d off = bias(paper_experiment(false));
  EXPECT_NEAR(off[0], -1.9171e-5, 5e-4 * 1.9171e-5);
  EXPECT_NEAR(off[1], 2.1254e-8, 5e-4 * 2.1254e-8);
  EXPECT_NEAR(off[2], 9.1580e-6, 5e-4 * 9.1580e-6);

  const Experiment ex = paper_experiment(true);
  const Input model = [&](double g, const RunPhase& r) { return kNominal(g, r) - coriolis(ex, r); };
  const Input truth_input = [&](double g, const RunPhase& r) {
    return model(g, r) + r.A * 1e-5 * std::sin(g);
  };
  const Eigen::Vector3d closed = closed_form_bias(ex, truth_input, model);
  expect_relative(bias(ex), closed, 1e-6, "Earth on");
  EXPECT_GT(std::abs(closed[1] - off[1]), 0.1 * std::abs(off[1]));  // C·δ is seen
}

}  // namespace
}  // namespace ccal::test
