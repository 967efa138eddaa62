// The budget's totals with correlation groups and its correlation matrix, checked against the law of
// propagation of uncertainty (JCGM 100 §5.2, model.md §10.1) carried out here by hand from the per-source
// effects: sources of one group are fully correlated with the same sign, so their effects add linearly with
// their signs, g_kG = Σ_{s∈G} c_ks; groups (an ungrouped source is a group of one) add in quadrature,
// Cov_ij = Σ_G g_iG g_jG, u_k = √Cov_kk, r_ij = Cov_ij / (u_i u_j).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/budget.hpp"
#include "independent_lpu.hpp"  // sigma_from_bound: σ of each distribution, written out

namespace ccal {
namespace {

// The bundled example with two correlation groups: the three radial/intersection lengths (normal, 25 µm) and
// the main-axis levelling pair (normal, 1e-5 rad), whose effects on K0, K2, K3 are large and of mixed signs.
Config grouped_example() {
  Config cfg = bundled_example();
  // The paper's tolerances only: no Type A rows of the drives' noise, no ripple rows (which would dominate
  // and decorrelate K0 and K3).
  cfg.centrifuge.rate_noise = {};
  std::erase_if(cfg.tolerances, [](const Tolerance& t) { return t.id.starts_with("ripple"); });
  for (Tolerance& t : cfg.tolerances) {
    if (t.id == "dR_s" || t.id == "dy2t" || t.id == "dy3t") t.group = "lengths";
    if (t.id == "dthx1t" || t.id == "dthy1t") t.group = "levelling";
  }
  return cfg;
}

// Cov from the per-source effects, by hand.
Eigen::MatrixXd covariance_by_hand(const BudgetDetail& b) {
  std::map<std::string, Eigen::VectorXd> group_sum;
  const Eigen::Index n = Eigen::Index(b.coefficients.size());
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(n, n);
  for (const SourceBudget& s : b.sources) {
    if (s.group.empty()) {
      cov += s.effect * s.effect.transpose();
    } else {
      auto [it, fresh] = group_sum.try_emplace(s.group, Eigen::VectorXd::Zero(n));
      it->second += s.effect;
    }
  }
  for (const auto& [name, g] : group_sum) cov += g * g.transpose();
  return cov;
}

TEST(BudgetGroups, TotalsAddGroupMembersLinearlyAndGroupsInQuadrature) {
  // Tolerance 1e-12 relative: the same sums in another order (round-off). The grouped totals must also
  // differ visibly from the root-sum-square of every effect (by more than 1e-3), or the test could not tell
  // a group from independent sources.
  const Config cfg = grouped_example();
  BudgetOptions o;
  o.compare_with_paper = false;
  const BudgetDetail b = compute_budget(cfg, o);
  ASSERT_EQ(b.sources.size(), cfg.tolerances.size());
  // Each effect is sensitivity × σ, with σ from the bound and distribution written out above.
  for (const SourceBudget& s : b.sources) {
    const double sigma = test::sigma_from_bound(s.bound, s.distribution);
    EXPECT_NEAR(s.standard_uncertainty, sigma, 1e-15 * sigma) << s.id;
    for (Eigen::Index k = 0; k < s.effect.size(); ++k)
      EXPECT_NEAR(s.effect[k], s.sensitivity[k] * sigma, 1e-14 * std::abs(s.effect[k])) << s.id;
  }
  const Eigen::MatrixXd cov = covariance_by_hand(b);
  for (Eigen::Index k = 0; k < cov.rows(); ++k) {
    const double u = std::sqrt(cov(k, k));
    SCOPED_TRACE(b.coefficients[std::size_t(k)]);
    EXPECT_NEAR(b.standard_uncertainty[k], u, 1e-12 * u);
    EXPECT_NEAR(b.expanded_uncertainty[k], b.coverage.factor * u, 1e-12 * u);
    double rss = 0;
    for (const SourceBudget& s : b.sources) rss += s.effect[k] * s.effect[k];
    EXPECT_GT(std::abs(u - std::sqrt(rss)), 1e-3 * u) << "the groups must matter for this check";
  }
}

TEST(BudgetGroups, CorrelationIsCovarianceOverTheProductOfBothUncertainties) {
  // r_ij = Cov_ij / (u_i u_j) for i ≠ j, from the hand covariance; 1 on the diagonal. The three u_k differ
  // by orders of magnitude, so a normalisation by u_i² alone would be off by u_j/u_i. Tolerance 1e-12
  // (round-off). The example's K0–K3 correlation is far from 0 (levelling moves both), so the check bites.
  const Config cfg = grouped_example();
  BudgetOptions o;
  o.compare_with_paper = false;
  const BudgetDetail b = compute_budget(cfg, o);
  const Eigen::MatrixXd cov = covariance_by_hand(b);
  const Eigen::Index n = cov.rows();
  ASSERT_EQ(n, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      const double want = i == j ? 1.0 : cov(i, j) / std::sqrt(cov(i, i) * cov(j, j));
      EXPECT_NEAR(b.covariance(i, j), cov(i, j), 1e-12 * std::sqrt(cov(i, i) * cov(j, j))) << i << j;
      EXPECT_NEAR(b.correlation(i, j), want, 1e-12) << i << j;
    }
  EXPECT_GT(std::abs(b.correlation(0, 2)), 0.1);
  // Same without groups (the configured example): independent sources only.
  Config plain_cfg = bundled_example();
  plain_cfg.centrifuge.rate_noise = {};
  const BudgetDetail plain = compute_budget(plain_cfg, o);
  const Eigen::MatrixXd plain_cov = covariance_by_hand(plain);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      if (i != j) {
        EXPECT_NEAR(plain.correlation(i, j), plain_cov(i, j) / std::sqrt(plain_cov(i, i) * plain_cov(j, j)),
                    1e-12)
            << i << j;
      }
}

}  // namespace
}  // namespace ccal
