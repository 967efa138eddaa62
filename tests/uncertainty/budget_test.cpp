// The error budget: the paper-mode sensitivities of model.md §5.1 (the paper's rows), the exact
// effects the paper omits (§11), AD against finite differences and against nonlinear re-identification.
#include <gtest/gtest.h>

#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "experiment_support.hpp"

namespace ccal::test {
namespace {

// ΔK0, ΔK2, ΔK3 [°/s/gⁿ] per `size` of a parameter, by path.
struct Row {
  std::vector<int> params;  // a group of equivalent parameters: each must give the same numbers
  double size;
  double k0, k2, k3;
};

Eigen::Vector3d effect(const SensitivityTable& t, int column, double size, int path) {
  const Eigen::MatrixXd& m = path == 0 ? t.total : path == 1 ? t.force_path : t.rate_path;
  return m.col(column) * size / kDeg;
}

void expect_rows(const Experiment& ex, const std::vector<Row>& rows, ModelMode mode, int path, double rel,
                 const IdentificationSpec& spec = paper_spec()) {
  std::vector<int> params;
  for (const Row& r : rows) params.insert(params.end(), r.params.begin(), r.params.end());
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const SensitivityTable t = sensitivities(ex, spec, params, zero, zero, mode);
  int column = 0;
  for (const Row& r : rows) {
    for (int p : r.params) {
      const Eigen::Vector3d d = effect(t, column++, r.size, path);
      const std::string what = ex.layout.parameter_id(p);
      // Quoted numbers have 3–5 digits: relative tolerance `rel`; a quoted 0 means round-off (1e-12 of
      // K1·1e-5).
      auto near = [&](double got, double want, const char* k) {
        const double tol = want == 0.0 ? 1e-15 : rel * std::abs(want);
        EXPECT_NEAR(got, want, tol) << what << " " << k;
      };
      near(d[0], r.k0, "K0");
      near(d[1], r.k2, "K2");
      near(d[2], r.k3, "K3");
    }
  }
}

const int c0_dthy2 = 0, c0_dthy3 = 1, c0_dthx3 = 2, c0_dx2 = 3, c0_dx3 = 4, c0_dy2 = 5, c0_dy3 = 6,
          c0_dthz2 = 7;
int c0(const Experiment& ex, int which) {
  const int ch[] = {ch::dthy2, ch::dthy3, ch::dthx3, ch::dx2, ch::dx3, ch::dy2, ch::dy3, ch::dthz2};
  return ex.layout.harmonic_index(ch[which], 0, false);
}

TEST(PaperBudget, Table4ThroughTheSpecificForce) {
  // model.md §5.1: errors of 1e-5 rad and 1e-5·R0 = 25 µm, K1-only paper model, g = 9.8, ψ = π. The table
  // quotes 5 digits: relative tolerance 2e-4 (one unit in the 5th digit plus round-off).
  const Experiment ex = paper_experiment(true);
  const std::vector<Row> rows = {
      {{ch::dthz5, c0(ex, c0_dthz2)}, 1e-5, -1.9151e-5, +2.1402e-8, +9.1287e-6},
      {{ch::dthy2t, c0(ex, c0_dthy2), ch::dthy3t, c0(ex, c0_dthy3)}, 1e-5, +1.2357e-6, -3.0824e-9, +2.3307e-7},
      {{ch::dthx3t, c0(ex, c0_dthx3)}, 1e-5, -1.8261e-6, +4.4847e-9, +4.4955e-7},
      {{ch::dthy4, ch::dthy5}, 1e-5, -5.0521e-3, 0, 0},
      {{ch::dR_s, c0(ex, c0_dx2), c0(ex, c0_dx3)}, 2.5e-5, +9.1840e-6, -1.1065e-8, +9.1870e-6},
      {{ch::dy2t, ch::dy3t, c0(ex, c0_dy2), c0(ex, c0_dy3)}, 2.5e-5, +1.9151e-5, -2.1402e-8, -9.1287e-6},
      {{ch::dx5}, 2.5e-5, -2.8513e-2, -3.2486e-4, -6.6988e-3},
  };
  expect_rows(ex, rows, ModelMode::paper, 1, 2e-4);
}

TEST(PaperBudget, Equation19MainAxisRateError) {
  // model.md §5.2, the recommended paper reference: Δω = 0.5e-6 rad/s in the amplitude of every power term:
  // ΔK = (+2.711e-7, +3.454e-9, +1.236e-7), 4 digits: relative 5e-4.
  const Experiment ex = paper_experiment(true);
  expect_rows(ex, {{{ch::domega}, 0.5e-6, +2.711e-7, +3.454e-9, +1.236e-7}}, ModelMode::paper, 0, 5e-4);
}

TEST(PaperBudget, Table5ThroughTheAngularRate) {
  // model.md §5.1: pose errors through ω_IA = Ω(θx sin γ − θy cos γ), 1e-5 rad, 5 digits (2e-4), and the
  // paper's additive −ΔΩ (ΔΩ = 0.5e-6 rad/s → ΔK0 = −2.8648e-5 °/s).
  const Experiment ex = paper_experiment(true);
  const std::vector<Row> rows = {
      {{ch::dthx3t, c0(ex, c0_dthx3)}, 1e-5, -1.3125e-6, +2.5057e-9, +4.3180e-7},
      {{ch::dthy2t, c0(ex, c0_dthy2), ch::dthy3t, c0(ex, c0_dthy3)}, 1e-5, +7.5144e-7, -1.4296e-9, +3.6491e-7},
      {{ch::dOmega}, 0.5e-6, -2.8648e-5, 0, 0},
  };
  expect_rows(ex, rows, ModelMode::paper, 2, 2e-4);
}

TEST(PaperBudget, OtherValueOfG) {
  // model.md §5.1 note: with g = 9.80665 the same rules give Δθz5 → ΔK3 = −6.32e-6 and ΔR → ΔK3 = +9.90e-6
  // (3 digits: relative 2e-3).
  Experiment ex = paper_experiment(true);
  ex.site.g = 9.80665;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const SensitivityTable t = sensitivities(ex, paper_spec(), {ch::dthz5, ch::dR_s}, zero, zero, ModelMode::paper);
  EXPECT_NEAR(effect(t, 0, 1e-5, 1)[2], -6.32e-6, 2e-3 * 6.32e-6);
  EXPECT_NEAR(effect(t, 1, 2.5e-5, 1)[2], +9.90e-6, 2e-3 * 9.90e-6);
}

TEST(ExactBudget, EffectsThePaperOmits) {
  // Main-axis levelling leaks a per-run constant c0_j = Δθx1t sin ψ_j − Δθy1t cos ψ_j (exact kinematics,
  // Earth on, arm on x0 at t = 0, so ψ_j = φ0_j) that hits K3 through the tiny Z3. The paper's K1-only rows
  // are (−2.98e-3, +5.67e-6, −1.45e-3) and (−1.56e-4, +9.94e-6, +1.71e-3): those are K1·c0 only. The exact
  // pipeline evaluates the whole instrument polynomial, so the run means also carry the cross terms
  // (2K2⟨a_i⟩ + 3K3⟨a_i²⟩)·c0_j; an independent least-squares evaluation of (K1 + 2K2 Z1 + 3K3 Z2)·c0 on the
  // runs' Z_n (tests/reduction/run_average_test.cpp) gives the numbers below (its inputs are rounded to 7
  // digits: relative tolerance 1e-3). Δθy1t's K0 moves by 4 % from the K1-only value; the other entries by
  // less than 1 %.
  const Experiment ex = paper_experiment(true);
  const std::vector<Row> rows = {
      {{ch::dthx1t}, 1e-5, -2.98266e-3, +5.67175e-6, -1.45826e-3},
      {{ch::dthy1t}, 1e-5, -1.62433e-4, +1.00092e-5, +1.72409e-3},
  };
  expect_rows(ex, rows, ModelMode::exact, 0, 1e-3);
}

TEST(ExactBudget, ArmStretchWithCrossTerms) {
  // ΔR = c Ω² with 10 µm at 30 g (c = 1e-5/Ω30²): ΔK = (−2.12e-6, +1.41e-7, +7.0e-8) (model.md §11, 2–3
  // digits: relative 2e-2).
  const Experiment ex = paper_experiment(true);
  const double w30 = rate_for(30.0, 2.5, 9.8);
  expect_rows(ex, {{{ch::arm_stretch}, 1e-5 / (w30 * w30), -2.12e-6, +1.41e-7, +7.0e-8}}, ModelMode::exact, 0,
              2e-2);
}

TEST(ExactBudget, PlatformRunoutBiasesK2AndK3WithoutDc) {
  // model.md E4: first-harmonic platform runouts of 10 µm bias K2 by ≈ ∓9.7e-7 and K3 by ≈ ±2.2e-5 (°/s
  // units), through 3K3⟨a_i² δa_i⟩ although δa_i has no DC term. Two digits: relative 5e-2. The sign depends
  // on the harmonic (cos vs sin) and axis; we check magnitudes and that K2 and K3 move in opposite
  // directions.
  const Experiment ex = paper_experiment(true);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const int p = ex.layout.harmonic_index(ch::dx3, 1, false);
  const SensitivityTable t = sensitivities(ex, paper_spec(), {p}, zero, zero, ModelMode::exact);
  const Eigen::Vector3d d = effect(t, 0, 1e-5, 0);
  EXPECT_NEAR(std::abs(d[1]), 9.7e-7, 5e-2 * 9.7e-7);
  EXPECT_NEAR(std::abs(d[2]), 2.2e-5, 5e-2 * 2.2e-5);
  EXPECT_LT(d[1] * d[2], 0.0);
}

TEST(ExactBudget, AutomaticDerivativesMatchCentralDifferencesOfThePipeline) {
  // Every kind of source (pose, length, dynamic harmonic, drive): AD through the pipeline against central
  // differences of the full nonlinear re-identification with step h = 1e-5 of the natural scale.
  // Truncation: O(h² f‴/f′) with f‴/f′ ≲ A² ≈ 1e3: ≈ 1e-7 relative. Round-off: each run mean carries
  // ≈ 1e-16 of the output's swing K1·A ≈ 1.5e4 °/s, i.e. 1.5e-12 °/s, and H⁺ has entries up to ≈ 3, so a
  // difference quotient is off by up to ≈ 3·1.5e-12/h. Tolerance: 1e-6 relative plus 5e-12/h (per unit).
  const Experiment ex = paper_experiment(true);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const std::vector<int> params = {ch::dthz5,
                                   ch::dthx1t,
                                   ch::dR_s,
                                   ex.layout.harmonic_index(ch::dthy3, 1, true),
                                   ex.layout.harmonic_index(ch::dy1, 1, false),
                                   ch::domega,
                                   ch::dOmega,
                                   ch::arm_stretch};
  const SensitivityTable t = sensitivities(ex, paper_spec(), params, zero, zero, ModelMode::exact);
  for (std::size_t c = 0; c < params.size(); ++c) {
    const SourceUnit u = ex.layout.parameter_unit(params[c]);
    const double h = 1e-5 * (u == SourceUnit::m           ? 2.5
                             : u == SourceUnit::rad_per_s ? 1e-2
                             : u == SourceUnit::rad       ? 1.0
                                                          : 1e-2);
    Eigen::VectorXd ep = zero, em = zero;
    ep[params[c]] = h;
    em[params[c]] = -h;
    const Eigen::Vector3d fd = (identified_deg(ex, ep, paper_spec(), ModelMode::exact) -
                                identified_deg(ex, em, paper_spec(), ModelMode::exact)) /
                               (2 * h);
    const Eigen::Vector3d ad = t.total.col(Eigen::Index(c)) / kDeg;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(ad[k], fd[k], 1e-6 * std::abs(fd[k]) + 5e-12 / h)
          << ex.layout.parameter_id(params[c]) << " K" << k;
  }
}

TEST(ExactBudget, LinearEffectAgreesWithNonlinearReidentification) {
  // V3/V4 style: the AD effect of a 1e-5 error equals the bias of the exact re-identification with that error
  // applied to 4 digits where second-order effects are negligible (relative O(A·ε) ≈ 3e-4: tolerance 5e-4).
  const Experiment ex = paper_experiment(true);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const SensitivityTable t = sensitivities(ex, paper_spec(), {ch::dthz5, ch::dR_s}, zero, zero, ModelMode::exact);
  const Eigen::Vector3d base = identified_deg(ex, zero, paper_spec(), ModelMode::exact);
  for (int c = 0; c < 2; ++c) {
    const int p = c == 0 ? int(ch::dthz5) : int(ch::dR_s);
    const double size = c == 0 ? 1e-5 : 2.5e-5;
    Eigen::VectorXd e = zero;
    e[p] = size;
    const Eigen::Vector3d nonlinear = identified_deg(ex, e, paper_spec(), ModelMode::exact) - base;
    const Eigen::Vector3d linear = t.total.col(c) * size / kDeg;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(linear[k], nonlinear[k], 5e-4 * std::abs(nonlinear[k])) << p << " K" << k;
  }
}

TEST(Budget, BundledExampleTotalsAndFlags) {
  // The bundled example: ≥ 40 sources, totals equal the root-sum-square of the effects (no groups there)
  // and the drives' rate noise (model.md §3.2, a variance of its own per coefficient), shares sum to 1, every
  // source ranked once, and the exact-vs-paper comparison flags the levelling (which the paper drops) but not
  // Δθz5 (where they agree).
  const Config cfg = bundled_example();
  ASSERT_GE(cfg.tolerances.size(), 40u);
  const BudgetDetail r = compute_budget(cfg);
  ASSERT_EQ(r.sources.size(), cfg.tolerances.size());
  for (Eigen::Index k = 0; k < r.standard_uncertainty.size(); ++k) {
    double sum = 0, share = 0;
    for (const auto& s : r.sources) {
      sum += s.effect[k] * s.effect[k];
      share += s.share[k];
    }
    ASSERT_EQ(r.rate_noise.size(), 2u);
    for (const auto& n : r.rate_noise) {
      sum += n.effect[k] * n.effect[k];
      share += n.share[k];
    }
    EXPECT_NEAR(r.standard_uncertainty[k], std::sqrt(sum), 1e-12 * std::sqrt(sum));
    EXPECT_NEAR(share, 1.0, 1e-12);
  }
  std::vector<int> ranks;
  for (const auto& s : r.sources) ranks.push_back(s.rank);
  std::sort(ranks.begin(), ranks.end());
  for (std::size_t i = 0; i < ranks.size(); ++i) EXPECT_EQ(ranks[i], int(i) + 1);
  for (const auto& s : r.sources) {
    if (s.id == "dthx1t") {
      EXPECT_TRUE(s.disagrees[2]) << "levelling must be flagged on K3";
    }
    if (s.id == "dthz5") {
      EXPECT_FALSE(s.disagrees[2]) << "Δθz5 agrees between the models";
    }
  }
}

}  // namespace
}  // namespace ccal::test

namespace ccal::test {
namespace {

TEST(Budget, CompensationChoicesOfSection54) {
  // model.md §5.1: leaving the Earth rate out of the model: ΔK = (−1.72e-3, +3.27e-6,
  // −8.36e-4); the paper's constant Coriolis left out (paper mode): (−6.567e-2, −2.302e-4, −6.778e-3), 4
  // digits: 1e-3. The physical Coriolis term −C cos γ (C = 2 ω_e R0 Ω sin φ / g) left out: model.md gives the
  // K1-only
  // (+1.766e-5, −3.36e-8, +8.575e-6); the exact pipeline evaluates the whole instrument polynomial, adding
  // 2K2⟨a_i δa_i⟩ = 2K2 A C ⟨cos²γ⟩ and 3K3⟨a_i² δa_i⟩, which dominate on K2. An independent closed-form
  // least-squares evaluation of those means gives (+2.83205e-5, +3.60868e-7, +1.29093e-5): tolerance 1e-4.
  // The Earth-rate row is a per-run constant like the levelling leak; its cross terms move K0 by ≈ 4 %
  // (see EffectsThePaperOmits): K0 to 6 %, K2 and K3 to 1 %.
  const Experiment ex = paper_experiment(true);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const auto rows = compensation_choices(ex, paper_spec(), zero, zero, ModelMode::exact, true);
  ASSERT_EQ(rows.size(), 2u);
  const Eigen::Vector3d earth = rows[0].bias / kDeg, coriolis = rows[1].bias / kDeg;
  const Eigen::Vector3d paper_coriolis = rows[1].paper_bias / kDeg;
  EXPECT_NEAR(earth[0], -1.72e-3, 6e-2 * 1.72e-3);
  EXPECT_NEAR(earth[1], +3.27e-6, 1e-2 * 3.27e-6);
  EXPECT_NEAR(earth[2], -8.36e-4, 1e-2 * 8.36e-4);
  EXPECT_NEAR(coriolis[0], +2.83205e-5, 1e-4 * 2.83205e-5);
  EXPECT_NEAR(coriolis[1], +3.60868e-7, 1e-4 * 3.60868e-7);
  EXPECT_NEAR(coriolis[2], +1.29093e-5, 1e-4 * 1.29093e-5);
  EXPECT_NEAR(paper_coriolis[0], -6.567e-2, 1e-3 * 6.567e-2);
  EXPECT_NEAR(paper_coriolis[1], -2.302e-4, 1e-3 * 2.302e-4);
  EXPECT_NEAR(paper_coriolis[2], -6.778e-3, 1e-3 * 6.778e-3);
}

}  // namespace
}  // namespace ccal::test

namespace ccal::test {
namespace {

TEST(Budget, LinearisedAndAutomaticDerivativesAgree) {
  // The two derivative methods are independent routes to the same exact Jacobian (closed-form linearisation
  // of the chain contracted with the output gradient, vs Dual numbers through chain and reduction). For every
  // source of the bundled example, by path: agreement to 1e-9 of the coefficient's largest effect (the
  // linearised rule integrates the derivative with fewer fast nodes, exact for its band limit; the rest is
  // round-off on outputs swinging by K1·A).
  const Config cfg = bundled_example();
  const Experiment ex = cfg.experiment();
  std::vector<int> params;
  for (const auto& t : cfg.tolerances) params.push_back(t.parameter);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const auto lin = sensitivities(ex, cfg.identification, params, zero, zero, ModelMode::exact, {},
                                 DerivativeMethod::linearised);
  const auto ad = sensitivities(ex, cfg.identification, params, zero, zero, ModelMode::exact, {},
                                DerivativeMethod::automatic);
  ASSERT_EQ(lin.method, DerivativeMethod::linearised);
  ASSERT_EQ(ad.method, DerivativeMethod::automatic);
  for (std::size_t c = 0; c < params.size(); ++c) {
    const double u = cfg.tolerances[c].bound;
    for (Eigen::Index k = 0; k < 3; ++k) {
      const double scale = ad.total.row(k).cwiseAbs().maxCoeff() * u + 1e-300;
      EXPECT_NEAR(lin.force_path(k, Eigen::Index(c)) * u, ad.force_path(k, Eigen::Index(c)) * u, 1e-9 * scale)
          << cfg.tolerances[c].id << " K" << k;
      EXPECT_NEAR(lin.rate_path(k, Eigen::Index(c)) * u, ad.rate_path(k, Eigen::Index(c)) * u, 1e-9 * scale)
          << cfg.tolerances[c].id << " K" << k;
    }
  }
}

}  // namespace
}  // namespace ccal::test

namespace ccal::test {
namespace {

TEST(PaperBudget, LeverArmsAddTheRadiusAndIntersectionRows) {
  // model.md §5.1 note: with lever arms (L = 0.20 m, l = 0.05 m, (L+l)/R0 = 0.1, l/R0 = 0.02) the θy group
  // gains 0.1 × the ΔR row, the θx group −0.1 × the Δy row, and Δθy4 gains 0.02 × the Δx5 row. Sums of
  // 5-digit numbers: relative tolerance 3e-4.
  Experiment ex = paper_experiment(true);
  ex.geometry.L = 0.20;
  ex.geometry.l = 0.05;
  const std::vector<Row> rows = {
      {{ch::dthy3t},
       1e-5,
       1.2357e-6 + 0.1 * 9.1840e-6,
       -3.0824e-9 + 0.1 * -1.1065e-8,
       2.3307e-7 + 0.1 * 9.1870e-6},
      {{ch::dthx3t},
       1e-5,
       -1.8261e-6 - 0.1 * 1.9151e-5,
       4.4847e-9 - 0.1 * -2.1402e-8,
       4.4955e-7 - 0.1 * -9.1287e-6},
      {{ch::dthy4}, 1e-5, -5.0521e-3 + 0.02 * -2.8513e-2, 0.02 * -3.2486e-4, 0.02 * -6.6988e-3},
  };
  expect_rows(ex, rows, ModelMode::paper, 1, 3e-4);
}

}  // namespace
}  // namespace ccal::test
