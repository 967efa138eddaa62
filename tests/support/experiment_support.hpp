#pragma once
// The paper's experiment (model.md §6: R0 = 2.5 m, six counter-rotating runs at 5…30 g, T = 450 s, ψ = π,
// g = 9.8, 45.75° N) for the simulation and budget tests.
#include <numbers>
#include <string>
#include <vector>

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

// A centrifuge away from the paper's case, for the run-mean kernel's tests: lever arms L and l, a tilted
// horizontal axis, harmonic order `order`, Earth rotation; one run per duration, at 4, 10, 16, … g, the four
// mountings in turn, every run counter-rotating but the last (a fixed platform); a PIGA with cross terms, a rate
// term and an IA-rate gain.
inline Experiment general_centrifuge(int order, const std::vector<double>& durations) {
  Experiment ex;
  ex.geometry = Geometry{2.5, 0.3, 0.07, 0.02};
  ex.layout = ErrorLayout(order);
  ex.site = paper_site(true);
  const Mounting mountings[] = {Mounting::ia_horizontal, Mounting::ia_reversed, Mounting::pa_vertical,
                                Mounting::ia_vertical};
  const int runs = int(durations.size());
  for (int k = 0; k < runs; ++k) {
    ccal::Run r;
    r.name = "run" + std::to_string(k);
    r.g_level = 4.0 + 6.0 * k;
    r.duration = durations[std::size_t(k)];
    r.initial_phase = 0.3 + k;
    r.arm_azimuth = 0.2 * k;
    r.mounting = mountings[k % 4];
    r.mode = k == runs - 1 ? PlatformMode::fixed : PlatformMode::counter_rotating;
    ex.plan.runs.push_back(r);
  }
  ex.instrument = paper_piga();
  ex.instrument.term_ids = {"K0", "K1", "K2", "K3", "K_oq", "K_p", "K_io", "K_pp", "K_w"};
  ex.instrument.coefficients.resize(9);
  ex.instrument.coefficients << 1e-3, 8.8, 3e-4, 5e-5, 2e-5, 2e-4, 1e-5, 3e-5, 2e-3;
  ex.instrument.rate_gain = 0.9;
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
