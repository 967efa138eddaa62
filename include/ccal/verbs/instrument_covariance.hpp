#pragma once
// The covariance between the results of several instruments calibrated in one test ([[instruments]],
// docs/model.md §4.2). The machine's errors, g, the clock and the encoders are one for all the instruments, so
// their coefficients are correlated; each instrument's mounting (dx5, dy5, dthx5, dthy5, dthz5), fixed terms and
// output chain are its own. For the statements' quantities y = K̂ + b − C (f(e) − f(0)) + Type A of each
// instrument (verbs/statement.hpp):
//
//   LPU           cov(y_a, y_b) = E_a R_ab E_bᵀ,  E the sources' signed effects c·u (the budget's, in the
//                 statement's units), R_ab the sources' correlation with a pair of own sources of two
//                 instruments set to 0 (a = b: the whole R, the budget's own covariance);
//   Monte Carlo   the shared sources drawn once per trial for all instruments, each instrument's own drawn for it.
//
// The Type A parts (each instrument's own output noise) are independent between instruments and add to the
// diagonal blocks only; neither figure holds them. The drives' rate noise, which enters every instrument's run
// means alike, is left out of both: it is part of each fit's scatter (Type A).
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "ccal/core/model_mode.hpp"
#include "ccal/setup/config.hpp"

namespace ccal::verbs {

struct InstrumentCovariance {
  // Per instrument, in the configuration's order: its id, and where its coefficients start among the rows.
  std::vector<std::string> instruments;
  std::vector<Eigen::Index> first_row;
  std::vector<std::string> names;  // per row: "<id> <term>", e.g. "B K2"
  std::vector<std::string> units;  // per row: the coefficient's unit (the statement's)
  Eigen::MatrixXd lpu;             // the tolerances' covariance of every instrument's coefficients
  Eigen::MatrixXd monte_carlo;     // the same by the Monte Carlo (empty for trials = 0)
  std::uint64_t trials = 0;
  std::uint64_t seed = 0;
};

// Whether a tolerance's input belongs to each instrument on its own (its mounting, fixed terms, output chain).
bool instrument_own_input(int parameter) noexcept;

// The sources of a test of several instruments, drawn as one: every shared tolerance once, then each instrument's
// own tolerances as its copies ("<id>:<tolerance id>", groups likewise its own), with the [[correlations]] among
// them (a pair of two instruments' own sources uncorrelated); per instrument, the source of each of its tolerances
// (of_instrument[a][k]: the source of tolerance k of instrument a). InputError for a machine's tolerance that is
// not every instrument's.
struct JointSources {
  std::vector<Tolerance> sources;
  std::vector<Correlation> correlations;
  std::vector<std::vector<std::size_t>> of_instrument;
};
JointSources joint_sources(const std::vector<Config>& instruments);

// The covariance of the instruments' configurations (Config::instruments, each with the inputs its test measured
// already charged: with_measured_inputs), in `mode`; the Monte Carlo with `trials` trials (0: none).
InstrumentCovariance instrument_covariance(const std::vector<Config>& instruments, ModelMode mode,
                                           std::uint64_t trials, std::uint64_t seed, int threads);

}  // namespace ccal::verbs
