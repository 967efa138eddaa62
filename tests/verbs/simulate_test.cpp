// verbs::simulate in-process (docs/model.md §8–9): error-free runs identify the configured instrument; known
// errors the model leaves out shift the coefficients by the budget's first-order shift (known_error_shift),
// and compensated ones do not; the identification is `verbs::identify` of the observations file it writes,
// bit for bit; the seed matters only for a noisy instrument.
#include "ccal/verbs/simulate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/io/truth_file.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "ccal/uncertainty/statement.hpp"
#include "test_constants.hpp"
#include "ccal/verbs/identify.hpp"
#include "verbs_support.hpp"

namespace ccal::test {
namespace {

TEST(SimulateVerb, ErrorFreeRunsIdentifyTheConfiguredCoefficients) {
  // The bundled example has no [errors] and a noise-free instrument: the truth and the analyst's model are
  // the same chain, so the fit recovers [instrument.terms] to round-off. Tolerance 1e-9 of each coefficient:
  // the outputs are up to 1.5e4 deg/s (K1 at 30 g) and K0 = 0.062 deg/s, so the outputs' round-off
  // (2e-16 × 1.5e4 per run) is ~5e-11 of K0 before the design's amplification (its condition number ~10).
  const Config config = bundled_example();
  const verbs::SimulateResult r = verbs::simulate(config);
  EXPECT_FALSE(r.noisy);
  EXPECT_EQ(r.error_count, 0);
  ASSERT_EQ(r.identification.fit.names, config.identification.free_terms);
  EXPECT_NEAR(r.output_unit_si, std::numbers::pi / 180, 1e-17);  // deg/s
  for (std::size_t k = 0; k < r.identification.fit.names.size(); ++k) {
    const std::string& id = r.identification.fit.names[k];
    const double expected = configured(config, id, r.output_unit_si);
    EXPECT_NEAR(r.identification.fit.value[Eigen::Index(k)], expected, 1e-9 * std::abs(expected)) << id;
  }
  // One run mean per run of the plan, each the observation equation of its run: truth = model, so the
  // output is Σ K_j ⟨regressor_j⟩ + s_ω ⟨ω_IA⟩ over every column (free and fixed terms, SI) to the
  // round-off of the sum, 1e-12 of the output (the regressors come from the same chain).
  ASSERT_EQ(r.observations.runs.size(), config.plan.runs.size());
  for (Eigen::Index i = 0; i < r.observations.output.size(); ++i) {
    double model = r.observations.known_rate[i];
    for (std::size_t j = 0; j < r.observations.columns.size(); ++j)
      model += config.instrument.coefficient(r.observations.columns[j]).value() *
               r.observations.regressors(i, Eigen::Index(j));
    EXPECT_NEAR(r.observations.output[i], model, 1e-12 * std::abs(r.observations.output[i])) << i;
  }
}

TEST(SimulateVerb, NoDegreesOfFreedomLeavesTheStandardErrorsUndefinedAsIdentifyDoes) {
  // Three runs for three free terms: the fit passes every run mean, s² = 0/0, and the standard errors are
  // undefined (NaN: n/a in the text), not 0, which would read as exact coefficients; `reduce` shares the path
  // (verbs::identify_observations).
  Config config = bundled_example();
  config.plan.runs.resize(3);
  const verbs::SimulateResult r = verbs::simulate(config);
  const FitResult& fit = r.identification.fit;
  EXPECT_EQ(fit.dof, 0);
  EXPECT_TRUE(fit.std_error.array().isNaN().all()) << fit.std_error.transpose();
  EXPECT_TRUE(std::isnan(fit.residual_std) && std::isnan(fit.chi2_per_dof));
  ASSERT_FALSE(fit.warnings.empty());
  EXPECT_EQ(fit.warnings.front().rfind("no degrees of freedom (3 rows, 3 free terms): ", 0), 0u);
}

TEST(SimulateVerb, UncompensatedKnownErrorsShiftTheCoefficientsByTheirFirstOrderShift) {
  // With the regressors computed without the known [errors], the identified coefficients are off by the
  // shift the budget's sensitivities give (uncertainty/statement.hpp known_error_shift, SI): the same
  // first-order effect, computed through the linearised chain instead of the nonlinear runs. They differ
  // by the second-order remainder, ~(1e-5 rad)·(the first-order shift) for arcsecond angles: within 1e-3 of
  // each shift, plus 1e-9 of the coefficient for the fit's round-off.
  const Config config = parse_config(example_with_errors(false), "errors.toml");
  const verbs::SimulateResult r = verbs::simulate(config);
  EXPECT_EQ(r.error_count, 5);
  const Eigen::VectorXd shift = known_error_shift(config, config.mode);
  ASSERT_EQ(shift.size(), Eigen::Index(r.identification.fit.names.size()));
  for (std::size_t k = 0; k < r.identification.fit.names.size(); ++k) {
    const std::string& id = r.identification.fit.names[k];
    const double truth = configured(config, id, r.output_unit_si);
    const double expected_shift = shift[Eigen::Index(k)] / r.output_unit_si;
    EXPECT_GT(std::abs(expected_shift), 1e-7 * std::abs(truth)) << id << ": the errors must show";
    EXPECT_NEAR(r.identification.fit.value[Eigen::Index(k)] - truth, expected_shift,
                1e-3 * std::abs(expected_shift) + 1e-9 * std::abs(truth))
        << id;
  }
}

TEST(SimulateVerb, CompensatedKnownErrorsLeaveTheConfiguredCoefficients) {
  // The model computed with the known errors is the truth again: the configured values to the round-off of
  // the first test (1e-9).
  const Config config = parse_config(example_with_errors(true), "compensated.toml");
  const verbs::SimulateResult r = verbs::simulate(config);
  for (std::size_t k = 0; k < r.identification.fit.names.size(); ++k) {
    const std::string& id = r.identification.fit.names[k];
    const double expected = configured(config, id, r.output_unit_si);
    EXPECT_NEAR(r.identification.fit.value[Eigen::Index(k)], expected, 1e-9 * std::abs(expected)) << id;
  }
}

TEST(SimulateVerb, ATruthFileIsTheMachineAndTheConfigurationWhatTheLabKnows) {
  // The machine has the truth's errors (five), the lab knows one ([errors] dthz5). The run means are the
  // machine's: bit for bit those of a configuration whose [errors] are the truth's (the same chain at the same
  // values). The regressors are the model's: with compensate = true those of the configuration's own [errors],
  // bit for bit, not the truth's; with compensate = false those of zero errors in both.
  const std::string truth_text = "[errors]\ndthz5 = \"2 arcsec\"\ndthy1t = \"3 arcsec\"\ndomega = \"2e-6 rad/s\"\n"
                                 "dOmega = \"-1e-6 rad/s\"\ndx3_c1 = \"5 um\"\n";
  for (const bool compensate : {false, true}) {
    SCOPED_TRACE(compensate ? "compensated" : "uncompensated");
    std::string known = edited(std::string(bundled_example_text()),
                               "# dthz5 = \"2 arcsec\"       # instrument azimuth (IA) zero error", "dthz5 = \"2 arcsec\"");
    if (compensate) known = edited(known, "compensate = false", "compensate = true");
    const Config lab = parse_config(known, "lab.toml");
    const Config machine = parse_config(example_with_errors(compensate), "machine.toml");
    verbs::SimulateOptions o;
    o.truth = parse_truth(truth_text, "truth.toml", lab);
    const verbs::SimulateResult with_truth = verbs::simulate(lab, o);
    const verbs::SimulateResult as_machine = verbs::simulate(machine);
    const verbs::SimulateResult as_known = verbs::simulate(lab);
    EXPECT_EQ(with_truth.error_count, 5);
    EXPECT_EQ(with_truth.machine_errors, machine.centrifuge.errors);
    ASSERT_TRUE(with_truth.truth);
    EXPECT_EQ(with_truth.truth->source, "truth.toml");
    EXPECT_EQ(with_truth.observations.output, as_machine.observations.output);
    EXPECT_EQ(with_truth.observations.regressors, as_known.observations.regressors);
    if (compensate) {
      EXPECT_NE(with_truth.observations.regressors, as_machine.observations.regressors);
    }
  }
}

TEST(SimulateVerb, ADrawnTruthIsTheErrorsPlusOneDrawOfEveryTolerance) {
  // --draw-truth: the machine's errors are [errors] + draw_sources(tolerances, correlations, seed), parameter by
  // parameter, bit for bit; the regressors are the model's as without it. The example states no instrument
  // noise, so its run means differ from a truth file with those errors only by the drives' drawn rate noise:
  // with the rate noise removed they are that truth's, bit for bit. And it is one answer or the other.
  Config config = bundled_example();
  Tolerance gravity;  // and an input of the measuring chain, drawn as an error of the machine's chain
  gravity.parameter = chain_parameter({ChainKind::gravity, 0});
  gravity.id = "g";
  gravity.bound = 1e-3;
  config.tolerances.push_back(gravity);
  verbs::SimulateOptions o;
  o.draw_truth = true;
  o.seed = 11;
  const verbs::SimulateResult drawn = verbs::simulate(config, o);
  const std::vector<double> draws = draw_sources(config.tolerances, config.correlations, 11);
  ASSERT_EQ(drawn.drawn, draws);
  Eigen::VectorXd expected = config.centrifuge.errors;
  std::vector<std::pair<int, double>> chain;  // the measuring chain's draws: errors of the machine's chain
  for (std::size_t k = 0; k < draws.size(); ++k) {
    const int p = config.tolerances[k].parameter;
    if (is_chain_parameter(p))
      chain.emplace_back(p, draws[k]);
    else
      expected[p] += draws[k];
  }
  EXPECT_EQ(drawn.machine_errors, expected);
  EXPECT_EQ(drawn.config.chain.errors, chain);
  EXPECT_FALSE(chain.empty());
  EXPECT_EQ(drawn.observations.regressors, verbs::simulate(config).observations.regressors);
  config.centrifuge.rate_noise = {};
  const verbs::SimulateResult quiet = verbs::simulate(config, o);
  EXPECT_NE(quiet.observations.output, drawn.observations.output);
  verbs::SimulateOptions t;
  t.truth = SimulationTruth{};
  t.truth->errors = expected;
  t.truth->chain_errors = chain;
  EXPECT_EQ(quiet.observations.output, verbs::simulate(config, t).observations.output);
  t.draw_truth = true;
  EXPECT_THROW(verbs::simulate(config, t), OptionError);
}

TEST(SimulateVerb, ATruthsMeasuringChainIsTheMachinesReadingAndTerms) {
  // A truth's output_gain and output_offset are the reading's: (1 + gain) ȳ + offset of the machine without them,
  // to round-off; its K1 moves the machine's instrument, as a configuration with that K1 (bit for bit).
  Config config = bundled_example();
  config.instrument.noise_density = config.instrument.quantum = 0;
  const verbs::SimulateResult plain = verbs::simulate(config);
  verbs::SimulateOptions o;
  o.truth = parse_truth("[errors]\noutput_gain = \"50 ppm\"\noutput_offset = \"0.001 deg/s\"\n", "t.toml", config);
  const verbs::SimulateResult read = verbs::simulate(config, o);
  const Eigen::VectorXd expected = plain.observations.output * (1 + 50e-6) + Eigen::VectorXd::Constant(
                                       plain.observations.output.size(), 0.001 * kDeg);
  for (Eigen::Index j = 0; j < expected.size(); ++j)
    EXPECT_NEAR(read.observations.output[j], expected[j], 1e-15 * std::abs(expected[j]) + 1e-18) << j;
  EXPECT_EQ(read.error_count, plain.error_count + 2);
  o.truth = parse_truth("[errors]\nK1 = \"0.01 deg/s/g\"\n", "t.toml", config);
  Config moved = config;
  moved.instrument.coefficients[1] += 0.01 * kDeg;
  ASSERT_EQ(moved.instrument.term_ids[1], "K1");
  EXPECT_EQ(verbs::simulate(config, o).observations.output, verbs::simulate(moved).observations.output);
}

TEST(SimulateVerb, IdentificationIsThatOfItsObservationsFile) {
  // The contract of `ccal simulate` and `ccal identify`: identifying the written file gives the same bits.
  const Config config = parse_config(example_with_errors(false), "errors.toml");
  const verbs::SimulateResult r = verbs::simulate(config);
  const verbs::IdentifyResult id = verbs::identify(parse_csv(r.observations_csv, "obs.csv"));
  ASSERT_EQ(id.identification.fit.names, r.identification.fit.names);
  for (Eigen::Index k = 0; k < r.identification.fit.value.size(); ++k) {
    EXPECT_EQ(id.identification.fit.value[k], r.identification.fit.value[k]) << k;
    EXPECT_EQ(id.identification.fit.std_error[k], r.identification.fit.std_error[k]) << k;
  }
  EXPECT_EQ(id.rows, config.plan.runs.size());
  EXPECT_EQ(id.identification.units, r.identification.units);
}

TEST(SimulateVerb, TheSeedMattersOnlyForANoisyInstrument) {
  const Config quiet = bundled_example();
  verbs::SimulateOptions a, b;
  a.seed = 1;
  b.seed = 2;
  EXPECT_EQ(verbs::simulate(quiet, a).observations.output, verbs::simulate(quiet, b).observations.output);
  // White output noise of density N gives run means off by N/√T ≈ 0.1/√450 = 4.7e-3 deg/s: different
  // seeds, different outputs; the same seed, the same bits.
  const Config noisy =
      parse_config(edited(std::string(bundled_example_text()), "noise_density = \"0 deg/s/rtHz\"",
                          "noise_density = \"0.1 deg/s/rtHz\""),
                   "noisy.toml");
  const verbs::SimulateResult n1 = verbs::simulate(noisy, a), n2 = verbs::simulate(noisy, b);
  EXPECT_TRUE(n1.noisy);
  EXPECT_EQ(verbs::simulate(noisy, a).observations.output, n1.observations.output);
  EXPECT_NE(n1.observations.output, n2.observations.output);
  // The scatter of the noisy means about the quiet ones is N/√T per run: 6 runs, each within 6 σ.
  const verbs::SimulateResult q = verbs::simulate(quiet, a);
  const double sigma = 0.1 * std::numbers::pi / 180 / std::sqrt(450.0);
  for (Eigen::Index i = 0; i < q.observations.output.size(); ++i)
    EXPECT_NEAR(n1.observations.output[i], q.observations.output[i], 6 * sigma) << i;
}

TEST(SimulateVerb, PaperModeOffThePapersMountingIsRefused) {
  Config config = bundled_example();
  verbs::SimulateOptions o;
  o.mode = ModelMode::paper;
  config.plan.runs[0].mounting = Mounting::pa_vertical;
  EXPECT_THROW(verbs::simulate(config, o), InputError);
}

}  // namespace
}  // namespace ccal::test
