// The measuring chain's inputs (uncertainty/chain_inputs.hpp, docs/model.md §10.7), each against a closed form:
// g against minus the radius (AD), the output's gain and offset and a fixed term against a re-fit of the
// observations, a declared input against its own sensitivity, and the time base and an encoder's error against
// a reduction of logs that carry them (chain_inputs_logs_test.cpp).
#include "ccal/uncertainty/chain_inputs.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "experiment_support.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

int chain_code(ChainKind kind, int index = 0) { return chain_parameter({kind, index}); }

// K̂ per unit of each input (coefficients × inputs, SI), at zero errors.
Eigen::MatrixXd chain_sensitivity(const Experiment& ex, const IdentificationSpec& spec,
                                  const std::vector<int>& parameters) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  return sensitivities(ex, spec, parameters, zero, zero, ModelMode::exact).total;
}

Eigen::VectorXd fitted(const Observations<double>& obs, const IdentificationSpec& spec) {
  return identify_coefficients<double>(obs, spec);
}

TEST(ChainInputs, GravityActsAsMinusTheRadius) {
  // A relative error ε of g scales every kinematic specific force by 1/(1 + ε), as the radius's −ε R0 does (at
  // zero errors the instrument's lever arms are along the main axis and feel no centripetal force). The radius's
  // column is AD, g's a fourth-order difference of the exact chain with h = 1e-3 g: they agree to the
  // difference's truncation, O(h⁴) ~ 1e-12, and its round-off, ~1e-13/1e-3 of the column; tolerance 1e-9.
  const Config config = bundled_example();
  const Experiment ex = config.experiment();
  const IdentificationSpec& spec = config.identification;
  const Eigen::MatrixXd s = chain_sensitivity(ex, spec, {chain_code(ChainKind::gravity), ch::dR_s});
  const double eps = 1e-6;
  for (Eigen::Index k = 0; k < s.rows(); ++k) {
    const double by_g = s(k, 0) * eps * ex.site.g, by_radius = -s(k, 1) * eps * ex.geometry.R0;
    EXPECT_NEAR(by_g, by_radius, 1e-9 * std::abs(by_radius)) << spec.free_terms[std::size_t(k)];
    EXPECT_NE(by_radius, 0.0);
  }
}

TEST(ChainInputs, CoefficientsPerStandardGravityAreTheSameInstrument) {
  // [site] g_unit = "standard": the g-levels and the coefficients are per g_n. The same machine and runs (the
  // g-levels scaled by g/g_n to keep the speeds) and the same instrument (K_n scaled by (g_n/g)^n) give the
  // same run means, and the fit gives the coefficients so scaled: 1e-12 relative (round-off of the chain).
  const Config local = bundled_example();
  Config standard = local;
  standard.site.unit_g = kStandardGravity;
  standard.instrument.g_symbol = "gn";
  const double ratio = kStandardGravity / local.site.g;
  for (ccal::Run& run : standard.plan.runs) run.g_level /= ratio;
  for (std::size_t k = 0; k < standard.instrument.term_ids.size(); ++k) {
    const int n = parse_term(standard.instrument.term_ids[k]).value().power;
    standard.instrument.coefficients[Eigen::Index(k)] *= std::pow(ratio, n);
  }
  for (auto& [id, value] : standard.identification.fixed_terms) value *= std::pow(ratio, parse_term(id).value().power);
  const Experiment a = local.experiment(), b = standard.experiment();
  // At the errors' corner too (the paper's rules per g_n: gravity g/g_n of the specific force), in both modes.
  std::mt19937 rng(5);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(a.layout.size());
  for (const ModelMode mode : {ModelMode::exact, ModelMode::paper})
    for (const Eigen::VectorXd& e : {zero, Eigen::VectorXd(corner_draw(local, 1.0, rng))}) {
      SCOPED_TRACE(mode == ModelMode::exact ? "exact" : "paper");
      const Observations<double> oa = observe<double>(a, e, zero, local.identification, mode);
      const Observations<double> ob = observe<double>(b, e, zero, standard.identification, mode);
      for (Eigen::Index j = 0; j < oa.output.size(); ++j)
        EXPECT_NEAR(ob.output[j], oa.output[j], 1e-12 * std::abs(oa.output[j]) + 1e-15) << j;
      const Eigen::VectorXd ka = fitted(oa, local.identification), kb = fitted(ob, standard.identification);
      for (std::size_t k = 0; k < local.identification.free_terms.size(); ++k) {
        const int n = parse_term(local.identification.free_terms[k]).value().power;
        EXPECT_NEAR(kb[Eigen::Index(k)], ka[Eigen::Index(k)] * std::pow(ratio, n),
                    1e-10 * std::abs(ka[Eigen::Index(k)] * std::pow(ratio, n)))
            << local.identification.free_terms[k];
      }
    }
  // Per g_n, the local g acts through gravity alone, which the example's horizontal input axis does not sense:
  // g's column is zero but for the difference's round-off (1e-13 of a run mean per 1e-3 g).
  const Eigen::MatrixXd s = chain_sensitivity(b, standard.identification, {chain_code(ChainKind::gravity)});
  const Eigen::MatrixXd by_radius = chain_sensitivity(b, standard.identification, {ch::dR_s});
  for (Eigen::Index k = 0; k < s.rows(); ++k)
    EXPECT_LT(std::abs(s(k, 0) * 1e-4 * b.site.g), 1e-9 * std::abs(by_radius(k, 0) * 1e-4 * b.geometry.R0)) << k;
}

TEST(ChainInputs, GainAndOffsetAreARefitOfTheReadOutput) {
  // The reading (1 + ε) ȳ + b re-fitted: K̂ moves by H⁺ ȳ ε and H⁺ 1 b, which the columns state (linear
  // least squares: exact but for the round-off of the fit, 1e-15 of K̂ over ε = 1e-6; tolerance 1e-8).
  const Config config = bundled_example();
  const Experiment ex = config.experiment();
  const IdentificationSpec& spec = config.identification;
  const Eigen::MatrixXd s =
      chain_sensitivity(ex, spec, {chain_code(ChainKind::output_gain), chain_code(ChainKind::output_offset)});
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const Observations<double> obs = observe<double>(ex, zero, zero, spec);
  const double eps = 1e-6, offset = 1e-4 * kDeg;
  Observations<double> gained = obs, shifted = obs;
  gained.output *= 1 + eps;
  shifted.output.array() += offset;
  const Eigen::VectorXd base = fitted(obs, spec);
  const Eigen::VectorXd by_gain = (fitted(gained, spec) - base) / eps;
  const Eigen::VectorXd by_offset = (fitted(shifted, spec) - base) / offset;
  for (Eigen::Index k = 0; k < s.rows(); ++k) {
    EXPECT_NEAR(s(k, 0), by_gain[k], 1e-8 * by_gain.cwiseAbs().maxCoeff()) << k;
    EXPECT_NEAR(s(k, 1), by_offset[k], 1e-8) << k;  // K0 moves by b, K2 and K3 not at all
  }
  EXPECT_NEAR(s(0, 1), 1.0, 1e-12);
}

TEST(ChainInputs, AFixedTermIsARefitWithItsTrueValueMoved) {
  // The truth's K1 is the lab's + δ: the run means move by δ Z_j exactly (the output is linear in K1), so the
  // re-fit moves by H⁺ Z δ. Its round-off: the run means reach 260 rad/s, so their round-off 3e-14 rad/s over
  // δ Z ~ 5e-3 rad/s (δ = 1 % of K1) is 1e-11 of the change, and K̂ keeps 2e-3 of it: 5e-9 relative; 1e-8.
  const Config config = bundled_example();
  const Experiment ex = config.experiment();
  const IdentificationSpec& spec = config.identification;
  const int k1 = 1;  // all_term_ids(): K0, K1, …
  ASSERT_EQ(all_term_ids()[k1], "K1");
  const Eigen::MatrixXd s = chain_sensitivity(ex, spec, {chain_code(ChainKind::fixed_term, k1)});
  Experiment truth = ex;
  const auto at = Eigen::Index(std::find(truth.instrument.term_ids.begin(), truth.instrument.term_ids.end(), "K1") -
                               truth.instrument.term_ids.begin());
  const double delta = 1e-2 * truth.instrument.coefficients[at];
  truth.instrument.coefficients[at] += delta;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const Eigen::VectorXd moved =
      (fitted(observe<double>(truth, ex, zero, zero, spec), spec) - fitted(observe<double>(ex, zero, zero, spec), spec)) /
      delta;
  for (Eigen::Index k = 0; k < s.rows(); ++k) EXPECT_NEAR(s(k, 0), moved[k], 1e-8 * moved.cwiseAbs().maxCoeff()) << k;
  EXPECT_GT(moved.cwiseAbs().maxCoeff(), 1e-3);  // K1's regressor is not in the free terms' span
}

TEST(ChainInputs, ADeclaredInputMovesTheCoefficientsByItsSensitivities) {
  // Its column is Σ_t Z_t s_t, and H⁺ H s = s for the free terms: exactly its sensitivity (round-off, 1e-12).
  Config config = bundled_example();
  config.chain.declared.push_back({"temperature", "", "K", {{"K0", 0.002 * kDeg}, {"K2", 1e-6 * kDeg}}});
  const Experiment ex = config.experiment();
  const Eigen::MatrixXd s = chain_sensitivity(ex, config.identification, {chain_code(ChainKind::declared, 0)});
  EXPECT_NEAR(s(0, 0), 0.002 * kDeg, 1e-12 * kDeg);
  EXPECT_NEAR(s(1, 0), 1e-6 * kDeg, 1e-12 * kDeg);
  EXPECT_NEAR(s(2, 0), 0.0, 1e-12 * kDeg);
}

}  // namespace
}  // namespace ccal::test
