// Tolerance allocation: the optimality (KKT) conditions of the solution on small and random problems, the
// closed form of one constraint with equal costs, correlation groups, the bounds, the target parser, and the
// bundled example with targets on K2 and K3 checked against an independent budget and by Monte Carlo.
#include "ccal/uncertainty/allocate.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "independent_lpu.hpp"
#include "test_constants.hpp"
#include "test_paths.hpp"

namespace ccal::test {
namespace {

using ccal::test::kDeg;

// The problem merged into its groups, computed here independently of the library.
struct Merged {
  std::vector<int> of;
  Eigen::VectorXd cost;
  Eigen::MatrixXd a;  // (k_p c_kg / T_k)²
};

Merged merge(const AllocationProblem& p) {
  Merged m;
  std::map<std::string, int> named;
  int n = 0;
  for (Eigen::Index s = 0; s < p.sensitivity.cols(); ++s) {
    const std::string g = p.group.empty() ? "" : p.group[std::size_t(s)];
    if (g.empty()) {
      m.of.push_back(n++);
    } else if (auto it = named.find(g); it != named.end()) {
      m.of.push_back(it->second);
    } else {
      named[g] = n;
      m.of.push_back(n++);
    }
  }
  m.cost = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(p.sensitivity.rows(), n);
  for (Eigen::Index s = 0; s < p.sensitivity.cols(); ++s) {
    m.cost[m.of[std::size_t(s)]] += p.cost[s];
    c.col(m.of[std::size_t(s)]) += p.sensitivity.col(s) * p.standard_uncertainty[s];
  }
  m.a.resize(c.rows(), n);
  for (Eigen::Index k = 0; k < c.rows(); ++k)
    for (Eigen::Index g = 0; g < n; ++g) m.a(k, g) = std::pow(p.coverage_factor * c(k, g) / p.target[k], 2);
  return m;
}

// U_k = k_p √(Σ_g (Σ_{s∈g} J_ks u_s λ_s)²).
Eigen::VectorXd expanded(const AllocationProblem& p, const Eigen::VectorXd& scale) {
  const Merged m = merge(p);
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(p.sensitivity.rows(), m.cost.size());
  for (Eigen::Index s = 0; s < p.sensitivity.cols(); ++s)
    c.col(m.of[std::size_t(s)]) += p.sensitivity.col(s) * p.standard_uncertainty[s] * scale[s];
  return p.coverage_factor * c.rowwise().norm();
}

double group_objective(const Merged& m, const Eigen::VectorXd& x) {
  return (m.cost.array() / x.array().sqrt()).sum();
}

// Every optimality condition of the convex problem in x_g = λ_g², and no better point nearby.
void expect_optimal(const AllocationProblem& p, const AllocationSolution& s, std::uint32_t seed = 1) {
  ASSERT_TRUE(s.converged);
  const Merged m = merge(p);
  const auto ng = m.cost.size();
  const double X = p.max_scale * p.max_scale;
  Eigen::VectorXd x(ng);
  for (Eigen::Index src = 0; src < p.sensitivity.cols(); ++src) {
    const double l = s.scale[src];
    ASSERT_GT(l, 0.0);
    EXPECT_LE(l, p.max_scale * (1 + 1e-15));
    x[m.of[std::size_t(src)]] = l * l;
  }
  // Members of a group share one scale.
  for (Eigen::Index src = 0; src < p.sensitivity.cols(); ++src)
    EXPECT_DOUBLE_EQ(s.scale[src] * s.scale[src], x[m.of[std::size_t(src)]]) << src;
  // Primal feasibility, and the reported U.
  const Eigen::VectorXd U = expanded(p, s.scale);
  for (Eigen::Index k = 0; k < p.target.size(); ++k) {
    EXPECT_LE(U[k], p.target[k] * (1 + 1e-9)) << k;
    EXPECT_NEAR(U[k], s.expanded[k], 1e-12 * p.target[k]) << k;
    // Dual feasibility and complementary slackness.
    EXPECT_GE(s.multiplier[k], 0.0);
    if (s.multiplier[k] > 0) {
      EXPECT_GE(U[k], p.target[k] * (1 - 1e-9)) << k;
      EXPECT_TRUE(s.active[std::size_t(k)]) << k;
    }
  }
  // Stationarity: −½ C_g x_g^(−3/2) + Σ_k μ_k a_kg = 0 inside the bound, ≤ 0 at it.
  for (Eigen::Index g = 0; g < ng; ++g) {
    const double pull = 0.5 * m.cost[g] * std::pow(x[g], -1.5);
    const double push = m.a.col(g).dot(s.multiplier);
    if (x[g] < X * (1 - 1e-12))
      EXPECT_NEAR(push, pull, 1e-8 * pull) << "group " << g;
    else
      EXPECT_LE(push, pull * (1 + 1e-8)) << "group " << g;
  }
  // No random feasible point nearby is cheaper.
  const double best = group_objective(m, x);
  EXPECT_NEAR(best, s.objective, 1e-12 * best);
  std::mt19937 rng(seed);
  std::normal_distribution<double> step(0.0, 0.3);
  for (int trial = 0; trial < 500; ++trial) {
    Eigen::VectorXd y(ng);
    for (Eigen::Index g = 0; g < ng; ++g) y[g] = std::min(X, x[g] * std::exp(step(rng)));
    double worst = 0;
    for (Eigen::Index k = 0; k < m.a.rows(); ++k) worst = std::max(worst, m.a.row(k).dot(y));
    if (worst > 1) y /= worst;
    ASSERT_GE(group_objective(m, y), best * (1 - 1e-12)) << "trial " << trial;
  }
}

AllocationProblem small_problem() {
  AllocationProblem p;
  p.sensitivity.resize(2, 3);
  p.sensitivity << 1.0, 2.0, 0.5, 0.3, 0.0, 1.0;
  p.standard_uncertainty = Eigen::Vector3d(1.0, 0.5, 2.0);
  p.cost = Eigen::Vector3d(1.0, 2.0, 0.5);
  p.target = Eigen::Vector2d(1.0, 0.8);
  return p;
}

TEST(Allocation, SmallProblemIsOptimal) {
  const AllocationProblem p = small_problem();
  const AllocationSolution s = solve_allocation(p);
  expect_optimal(p, s);
  // Both targets bind: the configured U are 3.4 and 4.0 against 1.0 and 0.8.
  EXPECT_TRUE(s.active[0]);
  EXPECT_TRUE(s.active[1]);
  EXPECT_NEAR(s.configured_expanded[0], p.coverage_factor * std::sqrt(3.0), 1e-12);
  // The common scale meets the tighter target exactly and costs more.
  const double common =
      std::min(p.target[0] / s.configured_expanded[0], p.target[1] / s.configured_expanded[1]);
  EXPECT_NEAR(s.common_scale, common, 1e-15);
  EXPECT_NEAR(s.common_objective, p.cost.sum() / common, 1e-9);
  EXPECT_LT(s.objective, s.common_objective);
  EXPECT_LE(expanded(p, Eigen::VectorXd::Constant(3, s.common_scale)).maxCoeff() / 0.8, 1.25 + 1e-12);
}

TEST(Allocation, OneConstraintEqualCostsHasTheClosedForm) {
  // Minimise Σ 1/λ_s subject to Σ a_s λ_s² = 1 (a_s = (k_p J_s u_s / T)², no bound active):
  // λ_s = a_s^(−1/3) / √(Σ_t a_t^(1/3)).
  AllocationProblem p;
  p.sensitivity.resize(1, 5);
  p.sensitivity << 3.0, -0.2, 1e-3, 40.0, 0.7;
  p.standard_uncertainty.resize(5);
  p.standard_uncertainty << 1.0, 2.0, 5.0, 0.01, 1.5;
  p.cost = Eigen::VectorXd::Ones(5);
  p.target = Eigen::VectorXd::Constant(1, 0.5);
  p.max_scale = 1e6;
  const AllocationSolution s = solve_allocation(p);
  expect_optimal(p, s);
  double sum = 0;
  Eigen::VectorXd a(5);
  for (int i = 0; i < 5; ++i) {
    a[i] = std::pow(p.coverage_factor * p.sensitivity(0, i) * p.standard_uncertainty[i] / p.target[0], 2);
    sum += std::cbrt(a[i]);
  }
  for (int i = 0; i < 5; ++i)
    EXPECT_NEAR(s.scale[i], std::pow(a[i], -1.0 / 3) / std::sqrt(sum), 1e-12 * s.scale[i]);
  EXPECT_NEAR(s.expanded[0], p.target[0], 1e-12);
}

TEST(Allocation, UnequalCostsFollowTheCostToo) {
  // One constraint, no bound: λ_s ∝ (cost_s / a_s)^(1/3).
  AllocationProblem p;
  p.sensitivity.resize(1, 3);
  p.sensitivity << 1.0, 1.0, 1.0;
  p.standard_uncertainty = Eigen::Vector3d::Ones();
  p.cost = Eigen::Vector3d(1.0, 8.0, 27.0);
  p.target = Eigen::VectorXd::Constant(1, 0.1);
  p.max_scale = 1e3;
  const AllocationSolution s = solve_allocation(p);
  expect_optimal(p, s);
  EXPECT_NEAR(s.scale[1] / s.scale[0], 2.0, 1e-12);
  EXPECT_NEAR(s.scale[2] / s.scale[0], 3.0, 1e-12);
}

TEST(Allocation, GroupsShareOneScale) {
  AllocationProblem p;
  p.sensitivity.resize(2, 5);
  p.sensitivity << 1.0, 0.5, -0.2, 0.1, 2.0, 0.0, 1.0, 1.0, 0.5, -0.3;
  p.standard_uncertainty.resize(5);
  p.standard_uncertainty << 1.0, 2.0, 1.0, 3.0, 0.5;
  p.cost.resize(5);
  p.cost << 1.0, 1.0, 2.0, 0.5, 1.0;
  p.group = {"", "g", "g", "", "h"};
  p.target = Eigen::Vector2d(0.5, 0.4);
  const AllocationSolution s = solve_allocation(p);
  expect_optimal(p, s);
  EXPECT_EQ(s.scale[1], s.scale[2]);
  // The same as one source with the group's summed effect and cost.
  AllocationProblem q;
  q.sensitivity.resize(2, 4);
  q.sensitivity.col(0) = p.sensitivity.col(0);
  q.sensitivity.col(1) = p.sensitivity.col(1) * 2.0 + p.sensitivity.col(2) * 1.0;
  q.sensitivity.col(2) = p.sensitivity.col(3) * 3.0;
  q.sensitivity.col(3) = p.sensitivity.col(4) * 0.5;
  q.standard_uncertainty = Eigen::Vector4d(1.0, 1.0, 1.0, 1.0);
  q.cost = Eigen::Vector4d(1.0, 3.0, 0.5, 1.0);
  q.target = p.target;
  const AllocationSolution t = solve_allocation(q);
  EXPECT_NEAR(s.scale[0], t.scale[0], 1e-10 * t.scale[0]);
  EXPECT_NEAR(s.scale[1], t.scale[1], 1e-10 * t.scale[1]);
  EXPECT_NEAR(s.scale[3], t.scale[2], 1e-10 * t.scale[2]);
  EXPECT_NEAR(s.scale[4], t.scale[3], 1e-10 * t.scale[3]);
  EXPECT_NEAR(s.objective, t.objective, 1e-10 * t.objective);
}

TEST(Allocation, LooseTargetsAndInsensitiveSourcesGetTheLargestScale) {
  AllocationProblem p = small_problem();
  p.sensitivity.col(1).setZero();  // source 2 does not matter
  const AllocationSolution s = solve_allocation(p);
  expect_optimal(p, s);
  EXPECT_EQ(s.scale[1], p.max_scale);
  // Targets met even with every tolerance 10× looser: nothing to do.
  p.target = Eigen::Vector2d(1e3, 1e3);
  const AllocationSolution loose = solve_allocation(p);
  expect_optimal(p, loose);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(loose.scale[i], p.max_scale);
  EXPECT_EQ(loose.multiplier.maxCoeff(), 0.0);
  EXPECT_FALSE(loose.active[0]);
  EXPECT_EQ(loose.common_scale, p.max_scale);
}

TEST(Allocation, ActiveBoundsAndAnInactiveTarget) {
  AllocationProblem p = small_problem();
  p.max_scale = 1.0;    // nothing may be loosened
  p.target[0] = 3.0;    // close to its configured 3.39: only a little tightening
  p.target[1] = 100.0;  // never binding
  const AllocationSolution s = solve_allocation(p);
  expect_optimal(p, s);
  EXPECT_TRUE(s.active[0]);
  EXPECT_FALSE(s.active[1]);
  EXPECT_EQ(s.multiplier[1], 0.0);
  EXPECT_EQ(s.scale.maxCoeff(), 1.0);  // some source stays at its bound
}

TEST(Allocation, RandomProblemsAreSolvedToOptimality) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, unit(rng)); };
  const double scales[] = {1.0, 3.0, 10.0, 1e3};
  for (int problem = 0; problem < 60; ++problem) {
    SCOPED_TRACE(problem);
    const int nt = 1 + int(unit(rng) * 4), ns = 2 + int(unit(rng) * 40);
    AllocationProblem p;
    p.sensitivity.resize(nt, ns);
    for (int k = 0; k < nt; ++k)
      for (int s = 0; s < ns; ++s)
        p.sensitivity(k, s) = unit(rng) < 0.2 ? 0.0 : (unit(rng) < 0.5 ? -1 : 1) * log_uniform(1e-6, 1.0);
    p.standard_uncertainty.resize(ns);
    p.cost.resize(ns);
    for (int s = 0; s < ns; ++s) {
      p.standard_uncertainty[s] = log_uniform(1e-3, 1e3);
      p.cost[s] = log_uniform(0.1, 10.0);
      p.group.push_back(unit(rng) < 0.3 ? std::string(1, char('a' + int(unit(rng) * 3))) : "");
    }
    p.max_scale = scales[problem % 4];
    p.target.resize(nt);
    const Eigen::VectorXd configured = expanded(p, Eigen::VectorXd::Ones(ns));
    for (int k = 0; k < nt; ++k)
      p.target[k] = configured[k] > 0 ? configured[k] * log_uniform(1e-4, 3.0) : 1.0;
    const AllocationSolution s = solve_allocation(p);
    expect_optimal(p, s, std::uint32_t(problem));
    EXPECT_LE(s.objective, s.common_objective * (1 + 1e-12));
    EXPECT_LE(s.iterations, 60);
  }
}

TEST(Allocation, BadlyScaledProblemsAreSolvedToo) {
  // Uncertainties over 12 decades, sensitivities over 9, costs over 6, targets down to 1e-6 of the configured
  // uncertainty, up to 8 targets, some of them proportional: the dual iteration alone stalls on a few such
  // problems in 10⁴ (the barrier method then starts it).
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto log_uniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, unit(rng)); };
  const double scales[] = {1.0, 3.0, 10.0, 1e3, 1e6};
  for (int problem = 0; problem < 300; ++problem) {
    SCOPED_TRACE(problem);
    const int nt = 1 + int(unit(rng) * 8), ns = 1 + int(unit(rng) * 80);
    AllocationProblem p;
    p.sensitivity.resize(nt, ns);
    const double zeros = 0.5 * unit(rng);
    for (int k = 0; k < nt; ++k)
      for (int s = 0; s < ns; ++s)
        p.sensitivity(k, s) = unit(rng) < zeros ? 0.0 : (unit(rng) < 0.5 ? -1 : 1) * log_uniform(1e-9, 1.0);
    if (nt > 1 && unit(rng) < 0.2) p.sensitivity.row(1) = 3.0 * p.sensitivity.row(0);
    p.standard_uncertainty.resize(ns);
    p.cost.resize(ns);
    for (int s = 0; s < ns; ++s) {
      p.standard_uncertainty[s] = log_uniform(1e-6, 1e6);
      p.cost[s] = log_uniform(1e-3, 1e3);
      p.group.push_back(unit(rng) < 0.3 ? std::string(1, char('a' + int(unit(rng) * 5))) : "");
    }
    p.max_scale = scales[problem % 5];
    p.target.resize(nt);
    const Eigen::VectorXd configured = expanded(p, Eigen::VectorXd::Ones(ns));
    for (int k = 0; k < nt; ++k)
      p.target[k] = (configured[k] > 0 ? configured[k] : 1.0) * log_uniform(1e-6, 3.0);
    const AllocationSolution s = solve_allocation(p);
    expect_optimal(p, s, std::uint32_t(problem));
  }
}

TEST(Allocation, RejectsBadProblems) {
  AllocationProblem p = small_problem();
  p.target[1] = 0.0;
  EXPECT_THROW(solve_allocation(p), InputError);
  p.target[1] = -1.0;
  EXPECT_THROW(solve_allocation(p), InputError);
  p.target[1] = std::nan("");
  EXPECT_THROW(solve_allocation(p), InputError);
  p = small_problem();
  p.cost[0] = 0.0;
  EXPECT_THROW(solve_allocation(p), InputError);
  p = small_problem();
  p.max_scale = 0.0;
  EXPECT_THROW(solve_allocation(p), InputError);
  p = small_problem();
  p.cost.resize(2);
  EXPECT_THROW(solve_allocation(p), InputError);
  EXPECT_THROW(normal_coverage_factor(1.0), InputError);
  EXPECT_NEAR(normal_coverage_factor(0.95), 1.959963984540054, 1e-14);
}

TEST(AllocationTarget, ParsesDisplayUnitsAndExplicitUnits) {
  const std::vector<std::string> ids = {"K0", "K2", "K3"}, units = {"deg/s", "deg/s/g^2", "deg/s/g^3"};
  EXPECT_NEAR(parse_allocation_target("K3=1e-6", ids, units).expanded, 1e-6 * kDeg, 1e-22);
  EXPECT_NEAR(parse_allocation_target("K3=1e-6 deg/s/g^3", ids, units).expanded, 1e-6 * kDeg, 1e-22);
  EXPECT_NEAR(parse_allocation_target(" K2 = \"3.6e-3 deg/h/g^2\" ", ids, units).expanded, 1e-6 * kDeg,
              1e-22);
  EXPECT_NEAR(parse_allocation_target("K0=1e-6 rad/s", ids, units).expanded, 1e-6, 1e-22);
  EXPECT_EQ(parse_allocation_target("K0=1e-3", ids, units).coefficient, "K0");
  for (const char* bad : {"K3", "K3=", "=1e-6", "K3 1e-6"}) {
    try {
      parse_allocation_target(bad, ids, units);
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("COEFFICIENT=VALUE"), std::string::npos) << e.what();
    }
  }
  auto message = [&](const char* text) {
    try {
      parse_allocation_target(text, ids, units);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("K9x=1").find("unknown coefficient 'K9x'; accepted: the free terms K0, K2, K3"),
            std::string::npos)
      << message("K9x=1");
  EXPECT_NE(message("K1=1").find("K1 is not a free term"), std::string::npos) << message("K1=1");
  EXPECT_NE(message("K3=1e-6 deg/s").find("expected a quantity in"), std::string::npos)
      << message("K3=1e-6 deg/s");
  EXPECT_NE(message("K3=1e-6 furlong").find("targets: K3: "), std::string::npos) << message("K3=1e-6 furlong");
  EXPECT_NE(message("K3=0").find("positive"), std::string::npos) << message("K3=0");
  EXPECT_NE(message("K3=-1e-6").find("positive"), std::string::npos) << message("K3=-1e-6");
  EXPECT_NE(message("K3=nan").find("K3"), std::string::npos) << message("K3=nan");
}

// The paper's set-up (the bundled example without the drives' rate ripple and noise, whose noise alone
// exceeds these targets) with the targets U(K2) ≤ 1e-7 deg/s/g², U(K3) ≤ 1e-6 deg/s/g³.
class BundledAllocation : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    config_ = new Config(load_config(CCAL_SOURCE_DIR + "/tests/data/wang_ren_2014_paper.toml"));
    AllocateOptions o;
    o.verify_trials = 2000;
    o.seed = 1;
    o.targets = {"K2=1e-7", "K3=1e-6"};  // deg/s/g^2 and deg/s/g^3, their display units
    result_ = new AllocationDetail(allocate_tolerances(*config_, o));
  }
  static void TearDownTestSuite() {
    delete result_;
    delete config_;
  }
  static const Config* config_;
  static const AllocationDetail* result_;
};
const Config* BundledAllocation::config_ = nullptr;
const AllocationDetail* BundledAllocation::result_ = nullptr;

TEST_F(BundledAllocation, EveryTargetHoldsAndTheActiveOnesAreTight) {
  const AllocationDetail& r = *result_;
  ASSERT_TRUE(r.converged);
  ASSERT_EQ(r.targets.size(), 2u);
  EXPECT_NEAR(r.coverage_factor, 1.959963984540054, 1e-14);
  int active = 0;
  for (std::size_t t : r.targets) {
    const AllocatedCoefficient& c = r.coefficients[t];
    SCOPED_TRACE(c.id);
    EXPECT_LE(c.allocated_expanded, c.target * (1 + 1e-9));
    if (c.active) {
      ++active;
      EXPECT_GE(c.allocated_expanded, c.target * (1 - 1e-6));
    }
    EXPECT_GT(c.configured_expanded, c.target);  // the configured tolerances miss both targets
  }
  EXPECT_GE(active, 1);
  EXPECT_LT(r.objective, r.common_objective);
  // Sorted from the most tightened; no scale above the limit.
  for (std::size_t s = 1; s < r.sources.size(); ++s) EXPECT_LE(r.sources[s - 1].scale, r.sources[s].scale);
  for (const auto& s : r.sources) {
    EXPECT_GT(s.scale, 0.0);
    EXPECT_LE(s.scale, 10.0 * (1 + 1e-15));
    EXPECT_NEAR(s.allocated_bound, s.scale * s.bound, 1e-15 * s.bound * s.scale);
  }
  // The main-axis levelling dominates K3 (model.md §11): it must be tightened most.
  EXPECT_EQ(r.sources[0].id, "dthy1t");
  EXPECT_EQ(r.sources[1].id, "dthx1t");
  // Sources without first-order effect on K2 and K3 (e.g. the instrument's eccentricity) may be loosened 10×.
  const auto dx5 =
      std::find_if(r.sources.begin(), r.sources.end(), [](const auto& s) { return s.id == "dx5"; });
  ASSERT_NE(dx5, r.sources.end());
  EXPECT_EQ(dx5->scale, 10.0);
}

TEST_F(BundledAllocation, AnIndependentBudgetOfTheAllocatedTolerancesAgrees) {
  // U_k of the allocated tolerances recomputed without the budget: sensitivities by central differences of
  // the re-identified pipeline (independent_lpu.hpp), σ_s from bound and distribution, every σ_s scaled by
  // the source's allocated λ_s, and k_p = Φ⁻¹(0.975) = 1.959963984540054 written out. Tolerance 1e-6
  // relative: the central differences' third-order terms (h = the configured bound, ≈ 1e-10 relative) and
  // their round-off on coefficients whose effects are 1e-7 of the outputs (≈ 1e-8), with margin.
  const double k_p = 1.959963984540054;
  EXPECT_NEAR(result_->coverage_factor, k_p, 1e-12);
  std::vector<double> scale;
  for (const Tolerance& t : config_->tolerances) {
    const auto s = std::find_if(result_->sources.begin(), result_->sources.end(),
                                [&](const auto& a) { return a.id == t.id; });
    ASSERT_NE(s, result_->sources.end()) << t.id;
    scale.push_back(s->scale);
  }
  const Eigen::MatrixXd cov = independent_covariance(*config_, config_->tolerances, scale);
  for (std::size_t k = 0; k < result_->coefficients.size(); ++k) {
    const double U = k_p * std::sqrt(cov(Eigen::Index(k), Eigen::Index(k)));
    EXPECT_NEAR(result_->coefficients[k].allocated_expanded, U, 1e-6 * U) << result_->coefficients[k].id;
  }
}

TEST_F(BundledAllocation, MonteCarloVerificationPasses) {
  const AllocationVerification& v = result_->verification;
  ASSERT_EQ(v.trials, 2000u);
  EXPECT_TRUE(v.passed);
  EXPECT_NEAR(v.std_rel_error, 1 / std::sqrt(4000.0), 1e-15);
  for (std::size_t t : result_->targets) {
    const AllocatedCoefficient& c = result_->coefficients[t];
    SCOPED_TRACE(c.id);
    EXPECT_NE(c.verdict, Verdict::fail);
    EXPECT_NE(c.verdict, Verdict::not_checked);
    // The Monte Carlo standard deviation against the LPU: sampling (5 standard errors of 1/√(2M)) plus 3 %
    // for the nonlinearity (second-order effects of the sources loosened 10×; about 1–2 % at M = 2·10⁴).
    EXPECT_NEAR(c.mc_std / c.lpu_std, 1.0, 5 * v.std_rel_error + 0.03);
    EXPECT_GE(c.mc_half_width, c.mc_high - c.mc_mean);
    EXPECT_GE(c.mc_half_width, c.mc_mean - c.mc_low);
  }
}

TEST(AllocateTolerances, RejectsBadTargets) {
  const Config cfg = bundled_example();
  AllocateOptions o;
  o.verify_trials = 0;
  auto with = [&o](std::vector<std::string> targets) {
    AllocateOptions t = o;
    t.targets = std::move(targets);
    return t;
  };
  EXPECT_THROW(allocate_tolerances(cfg, with({})), InputError);
  EXPECT_THROW(allocate_tolerances(cfg, with({"K1=1e-6"})), InputError);
  EXPECT_THROW(allocate_tolerances(cfg, with({"K3=1e-6", "K3=2e-6"})), InputError);
  EXPECT_THROW(allocate_tolerances(cfg, with({"K3=0"})), InputError);
  o.max_scale = -1;
  EXPECT_THROW(allocate_tolerances(cfg, with({"K3=1e-6"})), InputError);
  o.max_scale = 10;
  o.coverage_probability = 1.0;
  EXPECT_THROW(allocate_tolerances(cfg, with({"K3=1e-6"})), InputError);
  // Without verification the result has none.
  o.coverage_probability = 0.95;
  const AllocationDetail r = allocate_tolerances(cfg, with({"K3=1e-3"}));  // deg/s/g^3, above the noise's 5.6e-4
  EXPECT_EQ(r.verification.trials, 0u);
  EXPECT_EQ(r.coefficients[2].verdict, Verdict::not_checked);
}

}  // namespace
}  // namespace ccal::test
