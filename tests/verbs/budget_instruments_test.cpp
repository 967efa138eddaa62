// `ccal budget` of a test of several instruments (examples/two_instruments.toml): each instrument's budget is
// exactly its budget alone, and the covariance of all their coefficients is instrument_covariance's LPU, whose
// diagonal blocks are those budgets' tolerance parts.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/render/budget.hpp"
#include "ccal/verbs/budget.hpp"
#include "ccal/verbs/instrument_covariance.hpp"
#include "test_paths.hpp"

namespace ccal::verbs {
namespace {

const Config& budget_two_config() {
  static const Config c = load_config(CCAL_SOURCE_DIR + "/examples/two_instruments.toml");
  return c;
}

const BudgetResult& budget_two_result() {
  static const BudgetResult r = budget(budget_two_config());
  return r;
}

// Bit for bit: each instrument's part is budget() of its own configuration (the same code, the same inputs), in
// its numbers, its text and its JSON; the whole result's JSON holds each one's after its id.
TEST(BudgetInstruments, EachInstrumentsBudgetIsItsBudgetAlone) {
  const BudgetResult& r = budget_two_result();
  ASSERT_EQ(r.instruments.size(), 2u);
  const nlohmann::ordered_json whole = nlohmann::ordered_json::parse(render::json(r));
  ASSERT_EQ(whole["instruments"].size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const Config& one = budget_two_config().instruments[i];
    const BudgetResult alone = budget(one);
    const BudgetResult& part = r.instruments[i];
    EXPECT_EQ(part.config.instrument_id, one.instrument_id);
    ASSERT_EQ(part.budget.expanded_uncertainty.size(), alone.budget.expanded_uncertainty.size());
    for (Eigen::Index k = 0; k < alone.budget.expanded_uncertainty.size(); ++k)
      EXPECT_EQ(part.budget.expanded_uncertainty[k], alone.budget.expanded_uncertainty[k]) << i << " " << k;
    EXPECT_EQ(render::text(part), render::text(alone));
    EXPECT_EQ(render::csv(part), render::csv(alone));
    nlohmann::ordered_json x = whole["instruments"][i];
    EXPECT_EQ(x["id"], one.instrument_id);
    x.erase("id");
    EXPECT_EQ(x, nlohmann::ordered_json::parse(render::json(alone))) << one.instrument_id;
  }
  // The two instruments differ (B's lever arm and azimuth): a part that is the first's twice would pass the
  // comparisons above for A only.
  EXPECT_NE(r.instruments[0].budget.expanded_uncertainty[2], r.instruments[1].budget.expanded_uncertainty[2]);
}

// The covariance is instrument_covariance's LPU (no trials), bit for bit; each diagonal element plus the drives'
// rate noise (Type A, which the covariance leaves out) is that instrument's budget u², to 1e-12 relative (sums of
// 60 squares in another order). A correlation between the instruments is there to be stated.
TEST(BudgetInstruments, TheCovarianceIsTheInstrumentsLpu) {
  const BudgetResult& r = budget_two_result();
  ASSERT_TRUE(r.covariance.has_value());
  const InstrumentCovariance expected = instrument_covariance(budget_two_config().instruments, ModelMode::exact, 0, 0, 0);
  ASSERT_EQ(r.covariance->lpu.rows(), 6);
  EXPECT_EQ(r.covariance->lpu, expected.lpu);
  EXPECT_EQ(r.covariance->names, expected.names);
  EXPECT_EQ(r.covariance->trials, 0u);
  for (std::size_t i = 0; i < 2; ++i) {
    const ccal::BudgetDetail& b = r.instruments[i].budget;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto kk = Eigen::Index(k);
      double variance = r.covariance->lpu(r.covariance->first_row[i] + kk, r.covariance->first_row[i] + kk);
      for (const RateNoiseBudget& n : b.rate_noise) variance += std::pow(n.effect[kk] * b.display_scale[k], 2);
      const double u = b.standard_uncertainty[kk] * b.display_scale[k];
      EXPECT_NEAR(std::sqrt(variance), u, 1e-12 * u) << i << " " << b.coefficients[k];
    }
  }
  double largest = 0;
  for (Eigen::Index a = 0; a < 3; ++a)
    for (Eigen::Index b = 3; b < 6; ++b)
      largest = std::max(largest, std::abs(r.covariance->lpu(a, b)) /
                                      std::sqrt(r.covariance->lpu(a, a) * r.covariance->lpu(b, b)));
  EXPECT_GT(largest, 0.2);
}

// One instrument: no parts, no covariance, the budget as before (the golden outputs hold its text and JSON).
TEST(BudgetInstruments, OneInstrumentHasNoParts) {
  const BudgetResult one = budget(budget_two_config().instruments[1]);
  EXPECT_TRUE(one.instruments.empty());
  EXPECT_FALSE(one.covariance.has_value());
  EXPECT_EQ(nlohmann::json::parse(render::json(one)).count("instruments"), 0u);
}

// The text: a section per instrument, headed by its id, then the correlation table; the CSV: one table, each line
// after its instrument's id, as many lines as the two tables.
TEST(BudgetInstruments, TextAndCsvHoldEveryInstrument) {
  const BudgetResult& r = budget_two_result();
  const std::string text = render::text(r);
  const auto a = text.find("=== instrument A ===\n"), b = text.find("=== instrument B ===\n");
  const auto table = text.find("correlation of the instruments' coefficients through the machine's errors (LPU)");
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  ASSERT_NE(table, std::string::npos);
  EXPECT_LT(a, b);
  EXPECT_LT(b, table);
  EXPECT_NE(text.find(render::text(r.instruments[1])), std::string::npos);
  // An instrument of several is not sent to the verbs that answer for one.
  EXPECT_EQ(text.find("ccal montecarlo"), std::string::npos);
  const std::string csv = render::csv(r);
  EXPECT_EQ(csv.rfind("instrument,rank,source,", 0), 0u) << csv.substr(0, 80);
  const auto lines = [](const std::string& s) { return std::count(s.begin(), s.end(), '\n'); };
  EXPECT_EQ(lines(csv), lines(render::csv(r.instruments[0])) + lines(render::csv(r.instruments[1])) - 1);
  EXPECT_NE(csv.find("\nB,1,"), std::string::npos);
}

// A bad option is refused once, before any instrument is budgeted, naming the option.
TEST(BudgetInstruments, BadOptionsAreRefusedForTheWholeTest) {
  BudgetOptions o;
  o.coverage_probability = 1.5;
  EXPECT_THROW(budget(budget_two_config(), o), OptionError);
}

}  // namespace
}  // namespace ccal::verbs
