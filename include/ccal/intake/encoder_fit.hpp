#pragma once
// One-pass least-squares fit of an encoder's unwrapped angle (docs/model.md §13.1):
//     α(τ) = a + b τ + Σ_{k=1..N} (Ĉk cos kα + Ŝk sin kα) + residual,   τ = t − t_first,
// the line being the joint's nominal angle and the harmonics its angle error δ. The harmonics take the
// measured angle α as argument where the model has the nominal one: the two differ by δ, so the regressors
// differ by O(δ) and the fitted coefficients by O(δ²), second order in the ripple.
//
// Accumulated as normal equations in one pass, memory independent of the number of samples. The sums are of
// the angle less a reference line (the centred least-squares line of the first kReferenceSamples samples):
// what is summed is then of the size of the ripple and the rate error of the reference, not of the angle
// travelled (thousands of radians), so the residual sum of squares Σr² = Σd² − βᵀXᵀd keeps its digits.
#include <cstddef>
#include <vector>

#include "ccal/core/sincos_track.hpp"

namespace ccal {

struct EncoderFitResult {
  std::size_t samples = 0;
  double slope = 0;  // b [rad/s]
  double start = 0;  // a, the line at τ = 0 [rad] (unwrapped)
  double end = 0;    // the line at the last sample [rad] (unwrapped)
  double rms = 0;    // RMS residual of the fit [rad]
  // Ĉ1, Ŝ1, …, ĈN, ŜN [rad]; empty when not fitted (N = 0, less than a revolution, or too few samples).
  std::vector<double> harmonics;
  double harmonic_sigma = 0;  // standard error of one harmonic coefficient [rad] (their largest)
};

class EncoderFit {
 public:
  static constexpr std::size_t kReferenceSamples = 4096;
  // The harmonics' cos α, sin α come from a SinCosTrack turning up to `max_turn` from its anchors (0: from
  // std::cos and std::sin at every sample).
  explicit EncoderFit(int harmonic_order, double max_turn = SinCosTrack::kMaxTurn);
  // One sample: τ [s], the unwrapped angle [rad] and the reading it came from (the same angle up to whole
  // turns; the argument of the harmonics), τ increasing.
  void add(double tau, double angle, double reading) {
    if (referenced_)
      push(tau, angle, reading);
    else
      buffer(tau, angle, reading);
  }
  // The fit of all samples added (at least two).
  EncoderFitResult result();

 private:
  void set_reference();
  // A sample before the reference line is set.
  void buffer(double tau, double angle, double reading);
  // A referenced sample to the batch; the batch accumulated when full.
  void push(double tau, double angle, double reading) {
    batch_tau_[batch_size_] = tau;
    batch_angle_[batch_size_] = angle;
    batch_reading_[batch_size_] = reading;
    if (++batch_size_ == kBatch) accumulate_batch();
  }
  // The batch's samples into the sums, one after the other in their order (the same sums, bit for bit, as
  // adding them one at a time): the harmonics' pairs for the whole batch first, then the products with the
  // sums in registers.
  void accumulate_batch();
  void accumulate_products(std::size_t n);
  void accumulate_first_harmonic(std::size_t n);

  static constexpr std::size_t kBatch = 256;

  int order_;
  std::size_t p_;               // unknowns: 2 + 2N
  SinCosTrack first_harmonic_;  // cos α, sin α of the readings, in their order
  std::vector<double> buffer_;  // τ, α, reading until the reference line is set
  bool referenced_ = false;
  double ref_start_ = 0, ref_slope_ = 0;
  std::vector<double> normal_;  // XᵀX, p×p row-major (upper triangle accumulated)
  std::vector<double> rhs_;     // Xᵀd
  std::vector<double> x_;       // regressors of one sample
  // Referenced samples waiting to be accumulated, and cos α, sin α of their readings.
  std::size_t batch_size_ = 0;
  double batch_tau_[kBatch], batch_angle_[kBatch], batch_reading_[kBatch];
  double batch_cos_[kBatch], batch_sin_[kBatch];
  double dd_ = 0;  // Σd²
  double last_tau_ = 0;
  std::size_t n_ = 0;
};

}  // namespace ccal
