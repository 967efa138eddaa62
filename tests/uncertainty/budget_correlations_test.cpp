// Partly correlated inputs in the budget (docs/model.md §10.1, JCGM 100 §5.2.2): u_k² = c_kᵀ V c_k with
// V_st = u_s r_st u_t, computed here from the budget's own sensitivities and the configured pairs, with
// positive and negative r; r = 1 for a pair is today's group; the cross terms' part of u² is what is left of
// the sources' own squares.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/uncertainty/budget.hpp"

namespace ccal {
namespace {

const std::string kPairs = R"(
[[correlations]]
between = ["dthy4", "dthy5"]
r = 0.6

[[correlations]]
between = ["ripple1_c1", "ripple3_c1"]
r = -0.5

[[correlations]]
between = ["dR_s", "dthz5"]
r = 0.3
)";

Config bundled_with(const std::string& extra) {
  return parse_config(std::string(bundled_example_text()) + extra, "correlations.toml");
}

double relative(double a, double b) { return std::abs(a - b) / std::abs(b); }

TEST(BudgetCorrelations, UIsTheQuadraticFormOfTheInputCovariance) {
  const Config c = bundled_with(kPairs);
  const BudgetDetail b = compute_budget(c);
  std::map<std::string, Eigen::Index> at;
  for (std::size_t s = 0; s < b.sources.size(); ++s) at[b.sources[s].id] = Eigen::Index(s);
  const auto n = Eigen::Index(b.sources.size());
  Eigen::MatrixXd V = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index s = 0; s < n; ++s) V(s, s) = std::pow(b.sources[std::size_t(s)].standard_uncertainty, 2);
  const std::map<std::pair<std::string, std::string>, double> r{
      {{"dthy4", "dthy5"}, 0.6}, {{"ripple1_c1", "ripple3_c1"}, -0.5}, {{"dR_s", "dthz5"}, 0.3}};
  for (const auto& [pair, value] : r) {
    const Eigen::Index s = at.at(pair.first), t = at.at(pair.second);
    V(s, t) = V(t, s) = b.sources[std::size_t(s)].standard_uncertainty * value *
                        b.sources[std::size_t(t)].standard_uncertainty;
  }
  const BudgetDetail independent = compute_budget(bundled_with(""));
  bool any_up = false, any_down = false;
  for (std::size_t k = 0; k < b.coefficients.size(); ++k) {
    const auto kk = Eigen::Index(k);
    Eigen::VectorXd sensitivity(n);
    for (Eigen::Index s = 0; s < n; ++s) sensitivity[s] = b.sources[std::size_t(s)].sensitivity[kk];
    double variance = sensitivity.dot(V * sensitivity);
    for (const RateNoiseBudget& noise : b.rate_noise) variance += noise.covariance(kk, kk);
    // 1e-12: the same numbers summed in another order (E F Fᵀ Eᵀ against cᵀ V c).
    EXPECT_LT(relative(b.expanded_uncertainty[kk], b.coverage.factor * std::sqrt(variance)), 1e-12)
        << b.coefficients[k];
    // The correlations move U, up where the correlated effects add, down where they cancel.
    any_up = any_up || b.expanded_uncertainty[kk] > independent.expanded_uncertainty[kk] * 1.01;
    any_down = any_down || b.expanded_uncertainty[kk] < independent.expanded_uncertainty[kk] * 0.99;
    // The cross terms' part: u² from the tolerances less the sources' own squares.
    double own = 0;
    for (const SourceBudget& s : b.sources) own += s.effect[kk] * s.effect[kk];
    double noise = 0;
    for (const RateNoiseBudget& nb : b.rate_noise) noise += nb.covariance(kk, kk);
    const double cross = variance - noise - own;
    EXPECT_NEAR(correlation_variance(b)[kk], cross, 1e-12 * variance) << b.coefficients[k];
  }
  EXPECT_TRUE(any_up);
  EXPECT_TRUE(any_down);
  EXPECT_EQ(b.input_correlation(at.at("ripple1_c1"), at.at("ripple3_c1")), -0.5);
  EXPECT_LT((b.input_factor * b.input_factor.transpose() - b.input_correlation).cwiseAbs().maxCoeff(), 1e-14);
}

TEST(BudgetCorrelations, RIsOneForAPairAsForAGroup) {
  const std::string grouped = std::string(bundled_example_text());
  // The bundled example's dthy4 and dthy5 lines, made one group.
  std::string text = grouped;
  for (const char* id : {"dthy4", "dthy5"}) {
    const std::size_t line = text.find(std::string("\n") + id + " = \"");
    ASSERT_NE(line, std::string::npos) << id;
    const std::size_t open = text.find('"', line), close = text.find('"', open + 1);
    const std::string bound = text.substr(open, close - open + 1);
    text.replace(open, close - open + 1, "{ bound = " + bound + ", group = \"level\" }");
  }
  const BudgetDetail as_group = compute_budget(parse_config(text, "group.toml"));
  const BudgetDetail as_pair =
      compute_budget(bundled_with("\n[[correlations]]\nbetween = [\"dthy4\", \"dthy5\"]\nr = 1\n"));
  ASSERT_TRUE(as_group.input_correlation.size() == 0);
  for (Eigen::Index k = 0; k < 3; ++k)  // 1e-12: an eigen-decomposition's round-off against a plain sum
    EXPECT_LT(relative(as_pair.expanded_uncertainty[k], as_group.expanded_uncertainty[k]), 1e-12) << k;
}

}  // namespace
}  // namespace ccal
