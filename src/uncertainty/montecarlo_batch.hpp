#pragma once
// A Monte Carlo model that evaluates a batch of trials at once (montecarlo.hpp's TrialFunction, private to
// the library): the engine draws its trials in batches (montecarlo_draws.hpp), and a model that can share
// work between trials, such as the calibration model's run means in SIMD lanes (run_means.hpp), takes a batch
// in one call. A TrialFunction that holds a BatchCallable is found by the engine (std::function::target) and
// given whole batches; called as a TrialFunction it evaluates one trial. Either way a trial's outputs must be
// the bits it gives alone, whatever the trials beside it: trial i depends only on (seed, i), for any thread
// count and however the trials are batched.
#include <cstddef>
#include <memory>
#include <span>
#include <utility>

namespace ccal::mc_batch {

class BatchTrial {
 public:
  virtual ~BatchTrial() = default;
  // A copy that shares the read-only state and has scratch of its own (one per thread).
  virtual std::unique_ptr<BatchTrial> fresh_copy() const = 0;
  // One trial: the draws of its sources → its outputs (every element).
  virtual void one(std::span<const double> draws, std::span<double> outputs) = 0;
  // `trials` trials: draws[t·sources + j] → outputs[t·outputs + o].
  virtual void many(std::span<const double> draws, std::size_t trials, std::span<double> outputs) = 0;
};

// The callable of a TrialFunction whose model takes batches: copied as a fresh copy of the model (so that
// each thread's copy of the TrialFunction has its own scratch).
class BatchCallable {
 public:
  explicit BatchCallable(std::unique_ptr<BatchTrial> trial) : trial_(std::move(trial)) {}
  BatchCallable(const BatchCallable& other) : trial_(other.trial_->fresh_copy()) {}
  BatchCallable& operator=(const BatchCallable& other) {
    if (this != &other) trial_ = other.trial_->fresh_copy();
    return *this;
  }
  BatchCallable(BatchCallable&&) noexcept = default;
  BatchCallable& operator=(BatchCallable&&) noexcept = default;
  ~BatchCallable() = default;

  void operator()(std::span<const double> draws, std::span<double> outputs) { trial_->one(draws, outputs); }
  BatchTrial& trial() { return *trial_; }

 private:
  std::unique_ptr<BatchTrial> trial_;
};

}  // namespace ccal::mc_batch
