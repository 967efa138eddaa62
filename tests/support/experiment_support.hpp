#pragma once
// The paper's experiment (model.md §6: R0 = 2.5 m, six counter-rotating runs at 5…30 g, T = 450 s, ψ = π,
// g = 9.8, 45.75° N) for the simulation and budget tests.
#include <numbers>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/reduction/observe.hpp"
#include "kinematics_support.hpp"

namespace ccal::test {

inline Experiment paper_experiment(bool earth = false, int harmonic_order = 1) {
  Experiment ex;
  ex.geometry = Geometry{2.5, 0.0, 0.0, 0.0};
  ex.layout = ErrorLayout(harmonic_order);
  ex.site = paper_site(earth);
  for (int k = 1; k <= 6; ++k) {
    ccal::Run r;
    r.name = std::to_string(5 * k) + "g";
    r.g_level = 5.0 * k;
    r.duration = 450.0;
    r.terminal_phase = std::numbers::pi;
    ex.plan.runs.push_back(r);
  }
  ex.instrument = paper_piga();
  return ex;
}

inline IdentificationSpec paper_spec() {
  IdentificationSpec spec;
  spec.free_terms = {"K0", "K2", "K3"};
  spec.fixed_terms = {{"K1", 505.2097 * kDeg}};
  return spec;
}

// Identified (K0, K2, K3) in °/s/gⁿ for true errors e (model errors zero).
inline Eigen::Vector3d identified_deg(const Experiment& ex, const Eigen::VectorXd& e,
                                      const IdentificationSpec& spec, ModelMode mode,
                                      const Eigen::VectorXd* known = nullptr) {
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const auto obs = observe<double>(ex, e, known ? *known : zero, spec, mode);
  return identify_coefficients<double>(obs, spec) / kDeg;
}

// The configured errors plus every centrifuge tolerance at ±k times its bound, signs at random: a corner of the
// tolerance box (k = 3 is a 3σ draw of every normal source). The measuring chain's inputs are no errors of the
// layout and stay at the lab's values.
inline Eigen::VectorXd corner_draw(const Config& cfg, double k, std::mt19937& rng) {
  std::uniform_int_distribution<int> sign(0, 1);
  Eigen::VectorXd e = cfg.centrifuge.errors;
  for (const Tolerance& t : cfg.tolerances)
    if (!is_chain_parameter(t.parameter)) e[t.parameter] += (sign(rng) ? k : -k) * t.bound;
  return e;
}

}  // namespace ccal::test
