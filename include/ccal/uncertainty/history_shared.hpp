#pragma once
// What calibrations on one set-up share (docs/model.md §16.1): the errors of the machine's inputs that both
// charged at their tolerance. A calibration statement lists, per Type B input, whether the test measured it
// or charged it at its tolerance, its signed effect e = c u on each coefficient (the sensitivity times the
// input's standard uncertainty) and its correlation group; with the [[correlations]] among the inputs charged
// at their tolerance, that is its whole Type B part: u_B(K)² = eᵀ R e (R: 1 within a group, the
// [[correlations]] ρ, identity otherwise). Two calibrations i, j on the same set-up meet the same machine
// errors in those inputs, so their coefficients' errors covary:
//     Cov(x_i, x_j) = Σ_{α,β ∈ S} e_{i,α} R_{αβ} e_{j,β},   S: the inputs charged at their tolerance in both,
// R_{αβ} as both state it (1 for α = β; where their groups or [[correlations]] differ, 0). Different set-ups,
// an input measured in either test, or a calibration whose shared part is not known (recorded before it was
// kept): no shared part.

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace ccal {

// One Type B input of a calibration statement (its "inputs" entry).
struct SharedInput {
  std::string id;         // the [tolerances] id
  bool measured = false;  // measured in that test: charged at its measurement, shared with none
  std::string group;      // the tolerance's correlation group; "": none
  std::map<std::string, double> effect;  // signed u_i(K) = c u per coefficient, in the statement's units
};

// A correlation among the inputs charged at their tolerance (the statement's "input_correlations").
struct SharedCorrelation {
  std::string first, second;
  double r = 0;
};

// What a calibration shares with others on its set-up.
struct SharedPart {
  std::string setup_sha256;  // the set-up's fingerprint: calibrations share only when equal
  std::vector<SharedInput> inputs;
  std::vector<SharedCorrelation> correlations;
  std::vector<std::string> order;  // the coefficients of covariance_b, in its order
  Eigen::MatrixXd covariance_b;    // the statement's Type B covariance of the coefficients
};

// R_{αβ} within one calibration: 1 for α = β or one non-empty group, a [[correlations]] ρ, else 0.
double input_correlation(const SharedPart& part, const std::string& first, const std::string& second);

// Cov(x_i, x_j) of `coefficient` (above); 0 when either is not known (nullopt) or they are on different
// set-ups.
double shared_covariance(const std::optional<SharedPart>& i, const std::optional<SharedPart>& j,
                         const std::string& coefficient);

// The matrix C of shared_covariance over calibrations (points × points; the diagonal is each one's shared
// part with itself, which history_trend does not read).
Eigen::MatrixXd shared_covariance_matrix(const std::vector<const std::optional<SharedPart>*>& parts,
                                         const std::string& coefficient);

}  // namespace ccal
