// The allocation's guards (docs/model.md §10.3): the coefficients without a target held at their configured
// U unless let grow (and named when they grow), the floors of the tolerances as lower bounds of the scales
// (closed form with a floor active, optimality on random problems with floors), and the targets the floors
// make impossible refused with what the floors allow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/allocate.hpp"
#include "test_constants.hpp"

namespace ccal::test {
namespace {

using ccal::test::kDeg;

// a_s = (k_p J_s u_s / T)² of a one-row problem of independent sources.
Eigen::VectorXd row_weights(const AllocationProblem& p) {
  Eigen::VectorXd a(p.sensitivity.cols());
  for (Eigen::Index s = 0; s < a.size(); ++s)
    a[s] = std::pow(p.coverage_factor * p.sensitivity(0, s) * p.standard_uncertainty[s] / p.target[0], 2);
  return a;
}

AllocationProblem one_row() {
  AllocationProblem p;
  p.sensitivity.resize(1, 4);
  p.sensitivity << 3.0, -0.2, 40.0, 0.7;
  p.standard_uncertainty = Eigen::Vector4d(1.0, 2.0, 0.01, 1.5);
  p.cost = Eigen::VectorXd::Ones(4);
  p.target = Eigen::VectorXd::Constant(1, 0.5);
  p.max_scale = 1e6;
  return p;
}

TEST(AllocationFloor, AnActiveFloorIsMetExactlyAndTheRestHasTheClosedForm) {
  // Without floors λ_s = a_s^(−1/3) / √(Σ_t a_t^(1/3)); source 0 is then tightened to λ_0 ≈ 0.06. With its
  // floor at λ_min = 0.08 it sits on it, and the others solve the same problem with the capacity
  // 1 − a_0 λ_min²: λ_s = a_s^(−1/3) √(1 − a_0 λ_min²) / √(Σ_{t≠0} a_t^(1/3)). Tolerances: 1e-16 on the
  // floor (the clamp gives x = λ_min² exactly; √ of its square is λ_min to an ulp), 1e-12 on the closed form
  // (the solver's 1e-13 on the normalised constraint, with margin).
  AllocationProblem p = one_row();
  const Eigen::VectorXd a = row_weights(p);
  const AllocationSolution free = solve_allocation(p);
  ASSERT_TRUE(free.converged);
  ASSERT_LT(free.scale[0], 0.07);
  p.min_scale = Eigen::VectorXd::Zero(4);
  p.min_scale[0] = 0.08;
  const AllocationSolution s = solve_allocation(p);
  ASSERT_TRUE(s.converged) << s.method << " " << s.iterations << " " << s.scale.transpose();
  EXPECT_NEAR(s.scale[0], 0.08, 1e-16);
  double sum = 0;
  for (int i = 1; i < 4; ++i) sum += std::cbrt(a[i]);
  const double capacity = 1 - a[0] * 0.08 * 0.08;
  for (int i = 1; i < 4; ++i)
    EXPECT_NEAR(s.scale[i], std::pow(a[i], -1.0 / 3) * std::sqrt(capacity / sum), 1e-12 * s.scale[i]) << i;
  EXPECT_NEAR(s.expanded[0], p.target[0], 1e-12);
  EXPECT_FALSE(s.unreachable[0]);
  // A floor below the free optimum changes nothing.
  p.min_scale[0] = 0.5 * free.scale[0];
  const AllocationSolution loose = solve_allocation(p);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(loose.scale[i], free.scale[i], 1e-12 * free.scale[i]) << i;
}

TEST(AllocationFloor, RandomProblemsWithFloorsAreOptimal) {
  // KKT conditions of min Σ C_g/√x_g s.t. a x ≤ 1, L ≤ x ≤ X, on random problems (3 rows, 8 sources, some
  // floors): feasibility (1e-9 relative, the solver's round-off with margin), λ ≥ λ_min exactly (to 1e-15),
  // stationarity inside the bounds, the right sign at each bound, and no random feasible point nearby
  // cheaper.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int solved = 0, floored = 0;
  for (int trial = 0; trial < 40; ++trial) {
    SCOPED_TRACE(trial);
    AllocationProblem p;
    p.sensitivity = Eigen::MatrixXd::NullaryExpr(3, 8, [&] { return unit(rng) - 0.3; });
    p.standard_uncertainty = Eigen::VectorXd::NullaryExpr(8, [&] { return 0.1 + unit(rng); });
    p.cost = Eigen::VectorXd::NullaryExpr(8, [&] { return 0.2 + unit(rng); });
    p.target = Eigen::VectorXd::NullaryExpr(3, [&] { return 0.3 + unit(rng); });
    p.max_scale = 5;
    // Floors on about half the sources, between 0.5 and 1.5 times their scale without floors: most of them
    // active; problems the floors make impossible are skipped.
    const AllocationSolution unfloored = solve_allocation(p);
    p.min_scale = Eigen::VectorXd::Zero(8);
    for (int g = 0; g < 8; ++g)
      if (unit(rng) < 0.5) p.min_scale[g] = std::min(p.max_scale, unfloored.scale[g] * (0.5 + unit(rng)));
    const AllocationSolution s = solve_allocation(p);
    if (std::any_of(s.unreachable.begin(), s.unreachable.end(), [](bool b) { return b; })) continue;
    ++solved;
    ASSERT_TRUE(s.converged) << s.method;
    Eigen::MatrixXd a(3, 8);
    for (int k = 0; k < 3; ++k)
      for (int g = 0; g < 8; ++g)
        a(k, g) =
            std::pow(p.coverage_factor * p.sensitivity(k, g) * p.standard_uncertainty[g] / p.target[k], 2);
    const Eigen::VectorXd x = s.scale.cwiseAbs2();
    for (int k = 0; k < 3; ++k) EXPECT_LE(a.row(k).dot(x), 1 + 1e-9) << k;
    for (int g = 0; g < 8; ++g) {
      EXPECT_GE(s.scale[g], p.min_scale[g] * (1 - 1e-15)) << g;
      const double pull = 0.5 * p.cost[g] * std::pow(x[g], -1.5), push = a.col(g).dot(s.multiplier);
      const bool at_floor = p.min_scale[g] > 0 && s.scale[g] <= p.min_scale[g] * (1 + 1e-12);
      const bool at_top = s.scale[g] >= p.max_scale * (1 - 1e-12);
      floored += at_floor;
      if (at_floor)
        EXPECT_GE(push, pull * (1 - 1e-8)) << g;  // it would go lower
      else if (at_top)
        EXPECT_LE(push, pull * (1 + 1e-8)) << g;
      else
        EXPECT_NEAR(push, pull, 1e-8 * pull) << g;
    }
    const double best = (p.cost.array() / s.scale.array()).sum();
    std::normal_distribution<double> step(0.0, 0.3);
    for (int probe = 0; probe < 300; ++probe) {
      Eigen::VectorXd y(8);
      for (int g = 0; g < 8; ++g)
        y[g] = std::clamp(x[g] * std::exp(step(rng)), std::pow(p.min_scale[g], 2), 25.0);
      double worst = 0;
      for (int k = 0; k < 3; ++k) worst = std::max(worst, a.row(k).dot(y));
      if (worst > 1) continue;  // not feasible (scaling down could cross a floor)
      ASSERT_GE((p.cost.array() / y.array().sqrt()).sum(), best * (1 - 1e-12)) << probe;
    }
  }
  EXPECT_GE(solved, 15);   // many problems stay feasible (34 of 40 with this seed)
  EXPECT_GE(floored, 20);  // and many floors are active (72)
}

TEST(AllocationFloor, ATargetTheFloorsMakeImpossibleIsReported) {
  // Source 2 alone at its floor gives a_2 λ_min² = 4 > 1: the target cannot be met; the least U is
  // T √(Σ a_s λ_min,s²) (the others at 0), here T · 2 (to round-off).
  AllocationProblem p = one_row();
  const Eigen::VectorXd a = row_weights(p);
  p.min_scale = Eigen::VectorXd::Zero(4);
  p.min_scale[2] = 2 / std::sqrt(a[2]);
  const AllocationSolution s = solve_allocation(p);
  ASSERT_EQ(s.unreachable.size(), 1u);
  EXPECT_TRUE(s.unreachable[0]);
  EXPECT_NEAR(s.least_expanded[0], 2 * p.target[0], 1e-12);
  p.min_scale[2] = 1e7;  // above max_scale
  EXPECT_THROW(solve_allocation(p), InputError);
}

// The bundled example (with the drives' noise) and a target on K3 alone: without the guard the allocation
// loosened what K0 depends on and K0's U grew about 4×.
class HeldCoefficients : public ::testing::Test {
 protected:
  const Config cfg = bundled_example();
  static const AllocatedCoefficient& coefficient(const AllocationDetail& r, const std::string& id) {
    return *std::find_if(r.coefficients.begin(), r.coefficients.end(),
                         [&](const auto& c) { return c.id == id; });
  }
  static AllocateOptions options(bool grow) {
    AllocateOptions o;
    o.targets = {"K3=1e-3"};  // deg/s/g^3, K3's display unit
    o.verify_trials = 0;
    o.let_others_grow = grow;
    return o;
  }
};

TEST_F(HeldCoefficients, UntargetedCoefficientsDoNotGrowByDefault) {
  // U_k(λ) ≤ U_k(1) for every coefficient without a target, to 1e-9 relative (the solver holds the
  // normalised row to 1e-12; the report recomputes U from the allocated scales, round-off ~1e-15).
  const AllocationDetail r = allocate_tolerances(cfg, options(false));
  ASSERT_TRUE(r.converged);
  EXPECT_FALSE(r.let_others_grow);
  for (const AllocatedCoefficient& c : r.coefficients) {
    SCOPED_TRACE(c.id);
    if (c.has_target) {
      EXPECT_LE(c.allocated_expanded, c.target * (1 + 1e-9));
      continue;
    }
    EXPECT_TRUE(c.held);
    EXPECT_FALSE(c.grew);
    EXPECT_LE(c.allocated_expanded, c.configured_expanded * (1 + 1e-9));
  }
  // K0 is limiting: held at its configured U (active to 1e-6).
  const AllocatedCoefficient& k0 = coefficient(r, "K0");
  EXPECT_NEAR(k0.allocated_expanded, k0.configured_expanded, 1e-6 * k0.configured_expanded);
}

TEST_F(HeldCoefficients, UntargetedCoefficientsGrowWhenAllowedAndAreNamed) {
  const AllocationDetail held = allocate_tolerances(cfg, options(false));
  const AllocationDetail r = allocate_tolerances(cfg, options(true));
  EXPECT_TRUE(r.let_others_grow);
  const AllocatedCoefficient& k0 = coefficient(r, "K0");
  EXPECT_FALSE(k0.held);
  EXPECT_TRUE(k0.grew);
  EXPECT_GT(k0.allocated_expanded, 3 * k0.configured_expanded);  // 0.036 → 0.149 deg/s
  // Letting the others grow is cheaper (fewer constraints), never dearer.
  EXPECT_LT(r.objective, held.objective);
}

TEST_F(HeldCoefficients, AFloorIsNeverUndercut) {
  // dthy1t is tightened to λ ≈ 0.07 for K3 ≤ 1e-3 deg/s/g³; with a floor at half its bound it stays at
  // exactly 0.2 (1e-15: the clamp, to an ulp) and the target still holds (others take up the slack).
  Config c = cfg;
  for (Tolerance& t : c.tolerances)
    if (t.id == "dthy1t") t.floor = 0.2 * t.bound;
  const AllocationDetail r = allocate_tolerances(c, options(false));
  ASSERT_TRUE(r.converged);
  const auto s =
      std::find_if(r.sources.begin(), r.sources.end(), [](const auto& a) { return a.id == "dthy1t"; });
  ASSERT_NE(s, r.sources.end());
  EXPECT_NEAR(s->scale, 0.2, 1e-15);
  EXPECT_TRUE(s->at_floor);
  for (const AllocatedSource& a : r.sources) EXPECT_GE(a.allocated_bound, a.floor * (1 - 1e-15)) << a.id;
  EXPECT_LE(coefficient(r, "K3").allocated_expanded, 1e-3 * kDeg * (1 + 1e-9));
}

TEST_F(HeldCoefficients, ATargetTheFloorsMakeImpossibleIsRefusedWithWhatTheyAllow) {
  // Every floor at its bound: nothing can be tightened, the least U of K3 is the configured one (0.046
  // deg/s/g³), 46× the target.
  Config c = cfg;
  for (Tolerance& t : c.tolerances) t.floor = t.bound;
  try {
    allocate_tolerances(c, options(false));
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("target on K3 = 0.001 deg/s/g^3: the floors allow at least U = 0.04608 deg/s/g^3"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("lower floors"), std::string::npos) << what;
  }
  // A floor above max_scale × bound names --max-scale.
  Config high = cfg;
  high.tolerances[0].floor = high.tolerances[0].bound;
  AllocateOptions o = options(false);
  o.max_scale = 0.5;
  try {
    allocate_tolerances(high, o);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("max_scale: 0.5 is below the floor of", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace ccal::test
