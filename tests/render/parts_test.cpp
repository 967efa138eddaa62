// The fit's parts shared by identify, simulate and reduce (src/render/parts.cpp), in-process on hand-made
// results: the observability table's figures, units and status per term with its warnings, and the
// instruments' correlation table and JSON (the LPU's, with the Monte Carlo's in brackets only when it ran, and
// 0 for a coefficient that does not vary, never NaN). The identification's own text is tests/render/identify_test.cpp's.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "../src/render/parts.hpp"
#include "render_support.hpp"

namespace ccal {
namespace parts_render_test {

using test::line_starting;
using test::table_cells;

verbs::ObservabilityReport observability() {
  verbs::ObservabilityReport r;
  r.basis = "the noise model";
  r.result.detection_factor = 3;
  TermObservability k2;
  k2.term = "K2";
  k2.sensitivity = 0.123456;
  k2.fraction = 0.5;
  k2.standard_error = 2e-6;
  k2.min_detectable = 6e-6;
  TermObservability k3 = k2;
  k3.term = "K3";
  k3.status = TermStatus::weak;
  k3.reason = "K3 is aliased with K1";
  k3.fix = "add a run at 30 g";
  r.result.terms = {k2, k3};
  r.units = {"deg/s/g^2", "deg/s/g^3"};
  r.warnings = {"K3 is weak"};
  return r;
}

TEST(ObservabilityText, EachTermsFiguresUnitAndStatusThenTheWarnings) {
  const std::string text = render::observability_text(observability());
  EXPECT_NE(text.find("resolution of the run means: the noise model; detectable = 3 sigma"), std::string::npos)
      << text;
  const auto k3 = line_starting(text, "K3 ");
  ASSERT_TRUE(k3) << text;
  // sensitivity to 4 digits, the rest to 3, the unit as displayed, the status by name.
  EXPECT_EQ(table_cells(*k3), (std::vector<std::string>{"K3", "0.1235", "0.5", "2e-06", "6e-06", "deg/s/g^3",
                                                        "weak"}))
      << *k3;
  EXPECT_NE(text.find("  - warning: K3 is weak\n"), std::string::npos) << text;
  const nlohmann::ordered_json j = render::observability_json(observability());
  EXPECT_EQ(j["terms"]["K3"]["reason"], "K3 is aliased with K1");
  EXPECT_FALSE(j["terms"]["K2"].contains("reason"));  // an ok term has no reason and no fix
  EXPECT_EQ(j["terms"]["K2"]["unit"], "deg/s/g^2");
}

// Two instruments' K2: covariance 1e-12 between variances 1e-12 and 4e-12 (correlation 0.5), and a third
// coefficient that does not vary.
verbs::InstrumentCovariance covariance(std::uint64_t trials) {
  verbs::InstrumentCovariance c;
  c.names = {"A K2", "B K2", "B K3"};
  c.units = {"deg/s/g^2", "deg/s/g^2", "deg/s/g^3"};
  c.lpu = Eigen::MatrixXd::Zero(3, 3);
  c.lpu << 1e-12, 1e-12, 0, 1e-12, 4e-12, 0, 0, 0, 0;
  if (trials > 0) {
    c.monte_carlo = c.lpu;
    c.monte_carlo(0, 1) = c.monte_carlo(1, 0) = 0.9e-12;  // 0.45
    c.trials = trials;
    c.seed = 5;
  }
  return c;
}

// The table's row of coefficient `name` (its header row also starts with the first name: the corner is blank).
std::optional<std::string> row_of(const std::string& text, const std::string& name) {
  for (const std::string& l : test::rendered_lines(text)) {
    const auto first = l.find_first_not_of(' ');
    if (first != std::string::npos && l.compare(first, name.size() + 1, name + " ") == 0 &&
        l.find('.') != std::string::npos)
      return l;
  }
  return std::nullopt;
}

TEST(CovarianceText, CorrelationsOfTheLpuAndTheMonteCarloInBracketsOnlyWhenItRan) {
  const std::string lpu_only = render::covariance_text(covariance(0));
  const auto a = row_of(lpu_only, "A K2");
  ASSERT_TRUE(a) << lpu_only;
  EXPECT_NE(a->find("1.000"), std::string::npos) << *a;
  EXPECT_NE(a->find("0.500"), std::string::npos) << *a;
  EXPECT_EQ(a->find("("), std::string::npos) << *a;
  const auto b3 = row_of(lpu_only, "B K3");
  ASSERT_TRUE(b3) << lpu_only;
  EXPECT_EQ(b3->find("nan"), std::string::npos) << *b3;  // a coefficient that does not vary: 0, not NaN
  EXPECT_NE(lpu_only.find("(LPU)"), std::string::npos) << lpu_only;

  const std::string both = render::covariance_text(covariance(2000));
  EXPECT_NE(both.find("Monte Carlo of 2000 trials in brackets"), std::string::npos) << both;
  ASSERT_TRUE(row_of(both, "A K2")) << both;
  EXPECT_NE(row_of(both, "A K2")->find("0.500 (0.450)"), std::string::npos) << both;
}

TEST(CovarianceJson, TheMatricesByRowsAndTheMonteCarloOnlyWhenItRan) {
  const nlohmann::ordered_json lpu_only = render::covariance_json(covariance(0));
  EXPECT_EQ(lpu_only["lpu_correlation"][0][1].get<double>(), 0.5);
  EXPECT_EQ(lpu_only["lpu_correlation"][2][2].get<double>(), 0.0);
  EXPECT_FALSE(lpu_only.contains("monte_carlo"));
  const nlohmann::ordered_json both = render::covariance_json(covariance(2000));
  EXPECT_EQ(both["monte_carlo"][0][1].get<double>(), 0.9e-12);
  EXPECT_EQ(both["monte_carlo_trials"], 2000);
  EXPECT_EQ(both["units"][2], "deg/s/g^3");
}

}  // namespace parts_render_test
}  // namespace ccal
