#pragma once
// Random rate noise of the drives (docs/model.md §3.2): a stationary, white fluctuation n(t) of each drive's
// relative rate, q̇ = q̇ⁿ (1 + r(qⁿ) + n(t)), given by its density N (two-sided PSD N², in 1/√Hz; equal to the
// Allan deviation of the relative rate at τ = 1 s, σ_A(τ) = N/√τ). To first order a run mean moves by
//     δȳ = (1/T) ∫₀ᵀ h(s) n(s) ds,   h(s) = q̇ⁿ [G_r(s) − Ġ_c(s) + ∫ₛᵀ G_a(t) dt],
// with G_a, G_r, G_c the output's derivatives with respect to the drive's angle, rate and acceleration along
// the run (for a phase-locked platform the main axis's direction includes the platform's following), so
// that the run means scatter independently with σ_j = N √(∫ h_j²) / T: a Type A component of the budget and
// a draw per run in the Monte Carlo. Its bias, through ⟨n²⟩ in the centripetal term, is second order.
#include <Eigen/Core>
#include <vector>

#include "ccal/reduction/observe.hpp"
#include "ccal/setup/config.hpp"

namespace ccal {

// σ_j / N for every run: the standard deviation of each run's output mean [output SI] per unit density of
// the rate noise of one drive (ripple1: main axis, ripple3: platform), at the errors `e` (indexed by the
// layout). The runs' integrands are taken as periodic in the fast phase: the slow drift ΔΩ t and the
// partial last revolution change it by O(|ΔΩ|T) and O(1/(ΩT)) relative.
Eigen::VectorXd rate_noise_gain(const Experiment& ex, const Eigen::VectorXd& e, int drive);
// Both drives' σ_j / N in one pass over the runs (the output's derivatives with respect to both drives'
// joints come from one evaluation per node); a drive not asked for gets zeros.
struct RateNoiseGains {
  Eigen::VectorXd main, platform;
};
RateNoiseGains rate_noise_gains(const Experiment& ex, const Eigen::VectorXd& e, bool main, bool platform);

// The rate noise as independent per-run sources for the Monte Carlo: one normal source per drive with noise
// and per run it moves, of standard deviation σ_j [output SI] at the configured errors, added to that run's
// output mean. Tolerance::parameter is rate_noise_parameter(run) (negative, outside every layout); ids
// "main_rate_noise@<run>", "platform_rate_noise@<run>".
std::vector<Tolerance> rate_noise_sources(const Config& cfg);
inline int rate_noise_parameter(int run) { return -1 - run; }
inline int rate_noise_run(int parameter) { return -1 - parameter; }

}  // namespace ccal
