// The run sheet (model/run_sheet.hpp) against closed forms written here (Ω = √(A g/R0), turns ΩT/2π, the
// phases of model.md §6.1) and against the exact kinematics: the platform angle γ(T) the sheet says a run
// stops at is read back from the specific force the exact chain gives at t = T (frame 5 turned by γ from the
// arm: f5/g = (−A cos γ, A sin γ, 1) with no errors and no Earth, tests/model/plan_test.cpp).
#include "ccal/model/run_sheet.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "ccal/model/sensed_input.hpp"
#include "kinematics_support.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

using ccal::test::kPi;

Run run(std::string name, double A, double T, PlatformMode mode) {
  Run r;
  r.name = std::move(name);
  r.g_level = A;
  r.duration = T;
  r.mode = mode;
  return r;
}

// The angle difference a − b in (−π, π].
double angle_difference(double a, double b) { return std::remainder(a - b, 2 * kPi); }

TEST(RunSheet, RatesTurnsAndPhasesFollowTheClosedForms) {
  const Site site = paper_site(false);
  const Geometry geometry{2.5, 0.0, 0.0, 0.0};
  ccal::Run terminal = run("10g", 10.0, 449.269, PlatformMode::counter_rotating);
  terminal.terminal_phase = kPi / 2;
  terminal.arm_azimuth = -kPi / 2;  // shown as 270°
  ccal::Run initial = run("20g", 20.0, 300.5, PlatformMode::counter_rotating);
  initial.initial_phase = 7.0;  // beyond 2π: shown as 7 − 2π
  initial.mounting = Mounting::pa_vertical;
  ccal::Run fixed = run("5g", 5.0, 100.0, PlatformMode::fixed);
  fixed.initial_phase = 1.0;
  const std::vector<ccal::Run> runs{terminal, initial, fixed};
  const RunSheet sheet = run_sheet(TestPlan{runs}, geometry, site);
  ASSERT_EQ(sheet.lines.size(), 3u);
  // Tolerances: 1e-12 relative, a few roundings of sqrt, fmod and products of order 1e3 rad.
  for (std::size_t j = 0; j < 3; ++j) {
    const RunSheetLine& l = sheet.lines[j];
    const ccal::Run& r = runs[j];
    EXPECT_EQ(l.order, int(j) + 1);
    EXPECT_EQ(l.run, r.name);
    const double omega = std::sqrt(r.g_level * site.g / geometry.R0);
    EXPECT_NEAR(l.main_rate, omega, 1e-12 * omega);
    EXPECT_NEAR(l.turns, omega * r.duration / (2 * kPi), 1e-12 * l.turns);
    EXPECT_EQ(l.platform_rate, r.mode == PlatformMode::fixed ? 0.0 : -l.main_rate);
    EXPECT_GE(l.start_phase, 0.0);
    EXPECT_LT(l.start_phase, 2 * kPi);
    EXPECT_GE(l.stop_phase, 0.0);
    EXPECT_LT(l.stop_phase, 2 * kPi);
  }
  EXPECT_NEAR(sheet.total_duration, 449.269 + 300.5 + 100.0, 1e-12);
  // Terminal: the stop phase is the one set, the start ψ + ΩT (γ̇ = −Ω), and the azimuth wrapped.
  EXPECT_TRUE(sheet.lines[0].terminal_phase);
  EXPECT_DOUBLE_EQ(sheet.lines[0].stop_phase, kPi / 2);
  EXPECT_NEAR(angle_difference(sheet.lines[0].start_phase, kPi / 2 + sheet.lines[0].main_rate * 449.269), 0,
              1e-9);  // 1e-9 rad: ΩT ≈ 2800 rad, rounded at 1e-16 relative per step
  EXPECT_NEAR(sheet.lines[0].arm_azimuth, 1.5 * kPi, 1e-15);
  // Initial: the start wrapped into [0, 2π), the stop φ0 − ΩT.
  EXPECT_FALSE(sheet.lines[1].terminal_phase);
  EXPECT_NEAR(sheet.lines[1].start_phase, 7.0 - 2 * kPi, 1e-15);
  EXPECT_NEAR(angle_difference(sheet.lines[1].stop_phase, 7.0 - sheet.lines[1].main_rate * 300.5), 0, 1e-9);
  EXPECT_EQ(sheet.lines[1].mounting, Mounting::pa_vertical);
  // Fixed platform: γ does not move.
  EXPECT_DOUBLE_EQ(sheet.lines[2].stop_phase, 1.0);
  EXPECT_DOUBLE_EQ(sheet.lines[2].start_phase, 1.0);
}

TEST(RunSheet, StopPhaseIsWhereTheExactKinematicsLeaveThePlatform) {
  // γ(T) from the exact chain's specific force at t = T on an ia_horizontal mounting (IA = x5, PA = y5):
  // tan γ = f_PA / (−f_IA). Tolerance 1e-9 rad: γ(T) is φ0 + γ̇T with γ̇T of order 1e3 rad.
  const Site site = paper_site(false);
  const Geometry geometry{2.5, 0.0, 0.0, 0.0};
  const CentrifugeModel centrifuge(geometry, 1);
  for (double psi : {0.3, kPi / 2, 4.0}) {
    for (double T : {61.7, 449.269}) {
      ccal::Run r = run("r", 17.0, T, PlatformMode::counter_rotating);
      r.terminal_phase = psi;
      ccal::Run by_start = r;
      by_start.terminal_phase.reset();
      by_start.initial_phase = initial_phase(r, geometry, site);
      const RunSheet sheet = run_sheet(TestPlan{{r, by_start}}, geometry, site);
      const Eigen::Vector3d f = evaluate_force(site, centrifuge, by_start, T).specific_force;
      const double gamma_T = std::atan2(f[1], -f[0]);
      EXPECT_NEAR(angle_difference(sheet.lines[0].stop_phase, gamma_T), 0, 1e-9)
          << "psi " << psi << " T " << T;
      EXPECT_NEAR(angle_difference(sheet.lines[1].stop_phase, gamma_T), 0, 1e-9)
          << "psi " << psi << " T " << T;
    }
  }
}

TEST(RunSheet, MountingAxesInWordsAreTheMountingMatrixColumns) {
  // Each column of mounting_matrix (IA, PA, OA in frame 5) is ±x5, ±y5 or ±z5; the words must name it.
  for (Mounting m :
       {Mounting::ia_horizontal, Mounting::ia_reversed, Mounting::pa_vertical, Mounting::ia_vertical}) {
    const Eigen::Matrix3d M = mounting_matrix(m);
    std::string want;
    const char* axis_names[] = {"IA", "PA", "OA"};
    for (int c = 0; c < 3; ++c) {
      int row = 0;
      M.col(c).cwiseAbs().maxCoeff(&row);
      want +=
          std::string(c ? ", " : "") + axis_names[c] + " = " + (M(row, c) < 0 ? "-" : "") + "xyz"[row] + "5";
    }
    EXPECT_EQ(std::string(mounting_axes(m)), want) << mounting_name(m);
  }
}

}  // namespace
}  // namespace ccal::test
