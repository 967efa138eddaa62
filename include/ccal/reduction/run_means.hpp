#pragma once
// The instrument-output means of every run of a test plan, for many error vectors: the Monte Carlo trial's
// inner loop. Same chain, same spectral rule and same instrument as average_run<double> (run_average.hpp,
// equal to round-off, tests/reduction/run_means_test.cpp), reorganised so that a trial needs no allocation, no library
// trigonometry, and one pass over the nodes of each run (docs/model.md §12):
//  - everything that does not depend on the errors is tabulated once: cos and sin of the main-axis angle at
//    the fast nodes (θ1(0) + 2πj/M), of the nominal platform angle there (φ0 − 2πj/M), and of the nominal
//    half-phases mΩT/2 of the weights; a trial turns them by the small angles its drive errors add (Δω T/2,
//    the platform drift −ΔΩ t_q) with the exact short series of frames.hpp;
//  - the blocks A, B, C of the chain are composed once per trial (B's arm stretch c·θ̇1² is added per run);
//  - the main-axis half (frame 3t) is evaluated once per fast node and carried into frame-3t coordinates,
//    where each platform node only adds the platform's motion relative to frame 3t:
//        f = F₀ + Ω̇ × r + Ω × (Ω × r) + 2 Ω × ṙ + r̈ + 2 ω_c × (Ω × r + ṙ),   ω = Ω + ω_ie + ω_r,
//    with F₀ = a₃ₜ + 2 ω_c × v₃ₜ + g ẑ₀ the specific force of o3t, Ω, Ω̇ the angular velocity and acceleration
//    of frame 3t, and r, ṙ, r̈, ω_r the position, velocity, acceleration of o5 and the angular velocity of
//    frame 5 relative to frame 3t (all in frame-3t coordinates).
#include <memory>
#include <span>
#include <vector>

#include "ccal/model/centrifuge.hpp"
#include "ccal/model/error_sources.hpp"
#include "ccal/model/instrument.hpp"
#include "ccal/model/plan.hpp"
#include "ccal/model/site.hpp"
#include "ccal/reduction/run_average.hpp"

namespace ccal {

class RunMeanKernel {
 public:
  // The number of fast nodes M is fixed here: options.quadrature.fast_nodes, or when 0 what average_run takes
  // with dynamic errors present (512 on a counter-rotating run whose instrument has the |a_i|a_i term). The
  // number of slow nodes follows each trial's ΔΩ as in run_quadrature. The frozen-platform variant of the
  // chain (ChainOptions::frozen_platform) is not supported (std::invalid_argument).
  RunMeanKernel(const Geometry& geometry, const ErrorLayout& layout, const Site& site,
                const std::vector<Run>& runs, const InstrumentModel& instrument,
                const ReductionOptions& options = {});
  ~RunMeanKernel();
  RunMeanKernel(RunMeanKernel&&) noexcept;
  RunMeanKernel& operator=(RunMeanKernel&&) noexcept;

  // The scratch space of means(): grown to the largest rule met and then reused, so that a call allocates
  // nothing once it has grown. It holds no state between calls, so a copy is a new, empty workspace (a trial
  // function that owns one can be copied once per thread). One thread at a time uses a workspace.
  class Workspace {
   public:
    Workspace();
    ~Workspace();
    Workspace(const Workspace&);
    Workspace& operator=(const Workspace&);
    Workspace(Workspace&&) noexcept;
    Workspace& operator=(Workspace&&) noexcept;

   private:
    friend class RunMeanKernel;
    struct Buffers;
    std::unique_ptr<Buffers> buffers_;
  };

  // ⟨instrument output⟩ of every run [output SI] for `errors` (SI, in the layout's order), in the caller's
  // workspace. The kernel is only read: concurrent calls are safe with one workspace each.
  void means(std::span<const double> errors, std::span<double> out, Workspace& workspace) const;
  // The same in a workspace of its own, allocated for the call: for single evaluations.
  void means(std::span<const double> errors, std::span<double> out) const;
  // The means of `trials` error vectors at once (trial t's errors at errors[t·layout size …], its means into
  // out[t·runs …]): trials that share their rule (slow nodes, drive ripple present or not) go through the
  // chain eight at a time, one per SIMD lane, so that a trial costs less than alone; each trial's means are
  // the bits means() gives it, whatever the trials beside it.
  void means(std::span<const double> errors, std::size_t trials, std::span<double> out,
             Workspace& workspace) const;

 private:
  struct Data;
  std::unique_ptr<const Data> data_;
};

}  // namespace ccal
