#include "ccal/intake/measured_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace ccal {

double line_rate_standard_error(double rms, std::size_t samples, double duration, double rate) {
  const double roundoff = 1e-16 * std::abs(rate);
  if (samples < 3 || !(duration > 0)) return roundoff;
  const auto n = double(samples);
  const double spread = duration * std::sqrt(n * (n + 1) / (n - 1) / 12.0);  // √Σ(τ − τ̄)²
  return std::max(rms / spread, roundoff);
}

namespace {

// The uncertainty of one relative ripple coefficient of harmonic k from an angle harmonic of standard error
// sigma and amplitude: k σ when the harmonic was resolved; k r/√3 when it was set to 0 (its true size anywhere
// within the resolution r).
struct RippleUncertainty {
  double u = 0;
  bool resolved = true;
};
RippleUncertainty ripple_uncertainty(int k, double amplitude, double sigma) {
  const double resolution = std::max(kRippleSignificance * sigma, kRippleResolutionFloor);
  if (amplitude > resolution) return {k * std::max(sigma, kRippleResolutionFloor / kRippleSignificance), true};
  return {k * resolution / std::sqrt(3.0), false};
}

// Measured ripple of one drive's channel in every run: per harmonic, the largest uncertainty over the runs.
void add_ripple(const Config& config, const LogReduction& logs, int channel, std::vector<MeasuredInput>& out) {
  const ErrorLayout& layout = config.centrifuge.layout;
  const bool main = channel == ch::ripple1;
  const bool locked = config.centrifuge.geometry.platform_control == PlatformControl::phase_locked;
  for (int k = 1; k <= layout.harmonic_order(); ++k) {
    RippleUncertainty worst{0, true};
    for (const LoggedRun& lr : logs.runs) {
      const std::vector<double>& h = main ? lr.log.theta1_harmonics : lr.log.gamma_harmonics;
      if (h.size() < std::size_t(2 * k) || (!main && lr.measured.mode != PlatformMode::counter_rotating)) return;
      double sigma = main ? lr.log.theta1_harmonic_sigma : lr.log.gamma_harmonic_sigma;
      if (!main && locked) sigma = std::hypot(sigma, lr.log.theta1_harmonic_sigma);
      const RippleUncertainty r =
          ripple_uncertainty(k, std::hypot(h[std::size_t(2 * k - 2)], h[std::size_t(2 * k - 1)]), sigma);
      if (r.u > worst.u) worst.u = r.u;
      worst.resolved = worst.resolved && r.resolved;
    }
    for (bool sine : {false, true}) {
      const int index = layout.harmonic_index(channel, k, sine);
      out.push_back({layout.parameter_id(index), worst.u, worst.resolved,
                     main ? "main-axis encoder: the rate ripple's harmonic fit in each run"
                          : "platform encoder: the rate ripple's harmonic fit in each run"});
    }
  }
}

}  // namespace

std::vector<MeasuredInput> measured_inputs(const Config& config, const LogReduction& logs) {
  std::vector<MeasuredInput> out;
  if (logs.runs.empty()) return out;
  const ErrorLayout& layout = config.centrifuge.layout;
  const auto every = [&](auto&& has) { return std::all_of(logs.runs.begin(), logs.runs.end(), has); };
  const auto rate_error = [](const ReducedLog& log, bool main) {
    return main ? line_rate_standard_error(log.theta1_rms, log.samples, log.duration, log.theta1_rate)
                : line_rate_standard_error(log.gamma_rms, log.samples, log.duration, log.gamma_rate);
  };
  if (every([](const LoggedRun& lr) { return lr.log.has_theta1; })) {
    double u = 0;
    for (const LoggedRun& lr : logs.runs) u = std::max(u, rate_error(lr.log, true));
    out.push_back({layout.parameter_id(ch::domega), u, true,
                   "main-axis encoder: the rate of each run (line fit)"});
  }
  if (every([](const LoggedRun& lr) {
        return lr.log.has_theta1 && lr.log.has_gamma && lr.measured.mode == PlatformMode::counter_rotating;
      })) {
    double u = 0;
    for (const LoggedRun& lr : logs.runs) u = std::max(u, std::hypot(rate_error(lr.log, true), rate_error(lr.log, false)));
    out.push_back({layout.parameter_id(ch::dOmega), u, true,
                   "both encoders: the platform's rate against the main axis's in each run (line fits)"});
  }
  add_ripple(config, logs, ch::ripple1, out);
  add_ripple(config, logs, ch::ripple3, out);
  return out;
}

std::vector<MeasuredInput> expected_measured_inputs(const Config& config) {
  std::vector<MeasuredInput> out;
  const EncoderSet& e = config.centrifuge.encoders;
  if (config.plan.runs.empty() || !(e.main || e.platform)) return out;
  const ErrorLayout& layout = config.centrifuge.layout;
  double shortest = config.plan.runs.front().duration;
  bool counter = true;
  for (const Run& run : config.plan.runs) {
    shortest = std::min(shortest, run.duration);
    counter = counter && run.mode == PlatformMode::counter_rotating;
  }
  const double rate = kRippleResolutionFloor / shortest;
  const auto ripple = [&](int channel, const char* how) {
    for (int k = 1; k <= layout.harmonic_order(); ++k)
      for (bool sine : {false, true})
        out.push_back({layout.parameter_id(layout.harmonic_index(channel, k, sine)),
                       k * kRippleResolutionFloor / std::sqrt(3.0), false, how});
  };
  if (e.main)
    out.push_back({layout.parameter_id(ch::domega), rate, true, "main-axis encoder (expected): the rate of each run"});
  if (e.main && e.platform && counter)
    out.push_back({layout.parameter_id(ch::dOmega), std::sqrt(2.0) * rate, true,
                   "both encoders (expected): the platform's rate against the main axis's"});
  if (e.main) ripple(ch::ripple1, "main-axis encoder (expected): the rate ripple's harmonic fit");
  if (e.platform && counter) ripple(ch::ripple3, "platform encoder (expected): the rate ripple's harmonic fit");
  return out;
}

}  // namespace ccal
