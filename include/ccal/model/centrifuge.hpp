#pragma once
// The centrifuge as data: nominal geometry plus the values of every error parameter (docs/model.md §2–3).

#include <Eigen/Core>
#include <string_view>

#include "ccal/model/error_sources.hpp"

namespace ccal {

enum class PlatformMode {
  counter_rotating,  // γ̇ = −(Ω + Δω + ΔΩ): the platform holds its inertial heading
  fixed,             // γ constant: the instrument turns with the arm
};

// How the counter-rotating platform's drive is commanded (docs/model.md §2.3). It decides whether the
// platform follows the main axis's rate ripple.
enum class PlatformControl {
  speed,         // its own rate loop: γ follows its own nominal angle φ0 − (Ω + Δω + ΔΩ)t
  phase_locked,  // slaved to the main axis's measured angle: γ = φ0 − (θ1 − θ1(0)) − ΔΩ t
};

struct Geometry {
  double R0 = 2.5;    // nominal radius: main axis to azimuth axis [m]
  double L = 0.0;     // azimuth-axis origin o3 to working base plane [m]
  double l = 0.0;     // base plane to instrument origin o5 [m]
  double beta = 0.0;  // horizontal-axis angle [rad]; 0 in the paper
  // The instrument's place on the working base plane and its turn about z5 (one of several instruments of a
  // test, [[instruments]] position and azimuth; docs/model.md §4.2): its origin o5 at (x5, y5, l) in frame 4,
  // its axes turned by azimuth5 about z5 before the run's mounting. 0 for an instrument on the platform axis.
  double x5 = 0.0, y5 = 0.0;  // [m]
  double azimuth5 = 0.0;      // [rad]
  PlatformControl platform_control = PlatformControl::speed;  // the platform drive's command (not geometry,
                                                              // but a property of the machine like β)
};

// Random rate noise of the drives (docs/model.md §3.2): the white relative-rate noise density N of each
// drive, two-sided PSD N² [1/Hz], equal to the Allan deviation of the relative rate at τ = 1 s.
struct DriveNoise {
  double main = 0.0;      // N1 of the main axis [1/√Hz]
  double platform = 0.0;  // N3 of the platform drive [1/√Hz] (a fixed platform does not turn: no noise)
  bool any() const { return main > 0.0 || platform > 0.0; }
};

// The joint encoders a test of this machine logs (`[centrifuge] encoders`): what `ccal reduce` will measure
// from them (docs/model.md §13.3), which the design's expected statement credits before the test.
struct EncoderSet {
  bool main = false;      // the main-axis encoder (θ1)
  bool platform = false;  // the platform encoder (γ)
};

struct CentrifugeModel {
  Geometry geometry;
  DriveNoise rate_noise;
  EncoderSet encoders;
  ErrorLayout layout{1};
  Eigen::VectorXd errors = Eigen::VectorXd::Zero(ErrorLayout{1}.size());  // SI, indexed by `layout`

  CentrifugeModel() = default;
  explicit CentrifugeModel(Geometry g, int harmonic_order = 1)
      : geometry(g), layout(harmonic_order), errors(Eigen::VectorXd::Zero(layout.size())) {}

  // By parameter id ("dthz5", "dx3_c1", …); throws std::out_of_range naming the id if there is none.
  double error(std::string_view id) const;
};

}  // namespace ccal
