#pragma once
// A centrifuge test plan: the runs, each a constant-speed spin of duration T (docs/model.md §6).
//
// Phase convention (model.md §6.1): γ(t) = φ0 + γ̇ t is the IA angle from the outward radial. The paper fixes
// the *terminal* phase ψ = γ(T) (ψ = π) rather than φ0, so that φ0 = (ψ + Ω T) mod 2π depends violently on
// g and T (dφ0/dg = ΩT/(2g)): a run stores Ω (through the g-level), T and ψ, and φ0 is derived, never stored
// alone.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/model/centrifuge.hpp"
#include "ccal/model/site.hpp"

namespace ccal {

// How the instrument's axes sit in the mounting frame 5 (x5, y5 in the base plane, z5 up). IA × PA = OA.
enum class Mounting {
  ia_horizontal,  // IA = x5, PA = y5, OA = z5 (the paper's)
  ia_reversed,    // IA = −x5, PA = −y5, OA = z5
  pa_vertical,    // IA = x5, PA = z5, OA = −y5
  ia_vertical,    // IA = z5, PA = x5, OA = y5
};

// Columns IA, PA, OA of the instrument in frame-5 coordinates.
Eigen::Matrix3d mounting_matrix(Mounting mounting);
// The configuration's words for a mounting ("ia_horizontal", …) and a platform mode ("counter_rotating",
// "fixed").
std::string_view mounting_name(Mounting mounting) noexcept;

struct Run {
  std::string name;
  double g_level = 0.0;   // A = Ω² R0 / g_site [g], positive; sets the nominal main-axis rate
  double duration = 0.0;  // T [s]
  PlatformMode mode = PlatformMode::counter_rotating;
  // Exactly one of the two phases is given: the initial φ0 = γ(0), or the terminal ψ = γ(T).
  std::optional<double> initial_phase;   // φ0 [rad]
  std::optional<double> terminal_phase;  // ψ [rad]
  double arm_azimuth = 0.0;              // θ1(0): the arm's azimuth from East (x0), counter-clockwise [rad]
  Mounting mounting = Mounting::ia_horizontal;
};

struct TestPlan {
  std::vector<Run> runs;
};

std::string_view platform_mode_name(PlatformMode mode) noexcept;

// Nominal main-axis rate of a run: Ω = √(A g / R0) [rad/s].
double nominal_rate(const Run& run, const Geometry& geometry, const Site& site);
// Nominal platform rate γ̇: −Ω on a counter-rotating platform, 0 on a fixed one.
double nominal_platform_rate(const Run& run, const Geometry& geometry, const Site& site);
// φ0 of a run: given, or (ψ − γ̇ T) mod 2π from the terminal phase (= (ψ + ΩT) mod 2π counter-rotating).
double initial_phase(const Run& run, const Geometry& geometry, const Site& site);
// An angle as its place in a turn, [0, 2π).
double angle_in_turn(double angle);
// The IA's inertial azimuth from East at t = 0: θ1(0) + φ0.
double initial_ia_azimuth(const Run& run, const Geometry& geometry, const Site& site);

}  // namespace ccal
