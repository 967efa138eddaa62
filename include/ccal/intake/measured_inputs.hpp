#pragma once
// What the run logs of a test measured of the centrifuge's error inputs (docs/model.md §13.3): the drives'
// rates and the platform mismatch from the encoders' line fits, the drives' rate ripple from their harmonic
// fits, each with the standard uncertainty of that measurement. The calibration statement charges these in
// place of the inputs' tolerances (verbs/statement.hpp).

#include <vector>

#include "ccal/intake/run_log.hpp"
#include "ccal/setup/config.hpp"
#include "ccal/setup/tolerance.hpp"

namespace ccal {

// The standard error of the rate b of a least-squares line through n samples equally spaced over T with
// residual RMS s: s / √(Σ(τ − τ̄)²) = s √12 / (T √(n (n + 1)/(n − 1))) (n ≥ 3; the spacing Δ = T/(n − 1)), or
// the round-off of a rate of that size (1e-16 |rate|, relative) when the residuals are smaller still.
double line_rate_standard_error(double rms, std::size_t samples, double duration, double rate);

// The inputs every logged run measured (an input only some runs measured keeps its tolerance), in the
// layout's order, each with the largest of its runs' standard uncertainties:
//   domega      main-axis encoder in every run: the line fit's rate standard error;
//   dOmega      both encoders in every run on a counter-rotating platform: the two rates' errors combined;
//   ripple1_ck, ripple1_sk   θ1's harmonics fitted in every run: k σ (σ the standard error of one angle
//               harmonic; ck = k Ŝk, sk = −k Ĉk), or, where the harmonic was not resolved and so set to 0, k r/√3
//               with r = max(kRippleSignificance σ, kRippleResolutionFloor) the resolution (uniform within it);
//   ripple3_ck, ripple3_sk   γ's harmonics likewise on a counter-rotating platform (with θ1's σ combined in
//               quadrature when phase-locked, whose platform ripple is γ's less the main axis's).
std::vector<MeasuredInput> measured_inputs(const Config& config, const LogReduction& logs);

// What a test of the configuration's plan will measure with the encoders it declares ([centrifuge] encoders),
// before any log is written: the inputs measured_inputs returns for such logs, each at the resolution its fit
// reaches whatever the encoder's noise (a ripple harmonic k r/√3 with r = kRippleResolutionFloor, not resolved; a
// rate kRippleResolutionFloor/T over the shortest run): the design's expected statement credits them. dOmega
// and the platform's ripple need every run counter-rotating.
std::vector<MeasuredInput> expected_measured_inputs(const Config& config);

}  // namespace ccal
