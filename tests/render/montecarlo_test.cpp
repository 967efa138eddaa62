// `ccal montecarlo` as read (render/montecarlo.hpp), on results of verbs::monte_carlo: every figure in the
// coefficient's display unit (the budget's scale), the validation's verdict per coefficient, the advice for a
// coefficient that fails it (sampling error or not), the adaptive procedure's table and verdict only when it
// ran, and a JSON and CSV whose numbers are the text's in the same units.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <string>

#include "ccal/core/format.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/render/montecarlo.hpp"
#include "ccal/verbs/montecarlo.hpp"
#include "render_support.hpp"

namespace ccal {
namespace montecarlo_render_test {

using test::line_starting;
using test::table_cells;

verbs::MonteCarloResult small_run(int digits = 0) {
  verbs::MonteCarloOptions o;
  o.propagation.trials = digits > 0 ? 10000 : 4000;
  o.propagation.seed = 3;
  o.propagation.threads = 1;
  o.propagation.digits = digits;
  if (digits > 0) o.propagation.max_trials = 40000;  // bounds the adaptive procedure only
  return verbs::monte_carlo(bundled_example(), o);
}

// The row of `name` in the table whose header starts with `header`.
std::vector<std::string> row_after(const std::string& text, const std::string& header, const std::string& name) {
  const auto at = text.find(header);
  EXPECT_NE(at, std::string::npos) << header;
  const auto row = line_starting(text.substr(at == std::string::npos ? 0 : at), name + " ");
  EXPECT_TRUE(row) << name;
  return row ? table_cells(*row) : std::vector<std::string>{};
}

TEST(MonteCarloText, TheFiguresAreInTheDisplayUnitsWithTheirVerdict) {
  const verbs::MonteCarloResult r = small_run();
  const std::string text = render::text(r);
  for (std::size_t k = 0; k < r.monte_carlo.outputs.size(); ++k) {
    const OutputSummary& s = r.monte_carlo.outputs[k];
    const double f = r.budget.display_scale[k];
    const auto stats = row_after(text, "std u(y)", s.name);
    ASSERT_EQ(stats.size(), 6u) << text;
    EXPECT_EQ(stats[1], r.budget.units[k]);
    EXPECT_EQ(stats[3], number(s.std_dev * f, 5));
    EXPECT_EQ(stats[4], fmt::format("[{}, {}]", number(s.low_symmetric * f, 5), number(s.high_symmetric * f, 5)));
    const auto lpu = row_after(text, "LPU u_c", s.name);
    ASSERT_EQ(lpu.size(), 8u) << text;
    EXPECT_EQ(lpu[2], number(s.lpu_std * f, 5));
    EXPECT_EQ(lpu[7], s.validated ? "yes" : "no");
  }
  // A fixed M: no adaptive table, and the closing line says how M was run.
  EXPECT_EQ(text.find("Adaptive procedure"), std::string::npos);
  EXPECT_TRUE(line_starting(text, "M = 4000 trials (1 stage of 4000), seed 3, 1 thread, ")) << text;
  EXPECT_TRUE(line_starting(text, "Validation of the LPU (JCGM 101 §8; u_c from `ccal budget --mode exact`"));
}

TEST(MonteCarloText, AFailedValidationGetsItsAdviceByItsCause) {
  verbs::MonteCarloResult r = small_run();
  OutputSummary& s = r.monte_carlo.outputs[1];
  ASSERT_TRUE(s.has_lpu);
  // The first validated, the second just beyond delta, well within three standard errors of the interval's
  // ends: sampling explains it.
  r.monte_carlo.outputs[0].validated = true;
  s.validated = false;
  s.d_low = s.validation_delta + 0.5 * s.interval_end_std_error;
  s.d_high = 0;
  const auto advice = render::validation_advice_lines(r);
  ASSERT_EQ(advice.size(), r.monte_carlo.outputs.size());
  EXPECT_TRUE(advice[0].empty());
  EXPECT_EQ(advice[1].rfind(s.name + ": not validated: max(d_low, d_high) exceeds delta by ", 0), 0u) << advice[1];
  EXPECT_NE(advice[1].find("sampling error explains it; run `ccal montecarlo --digits 2`"), std::string::npos)
      << advice[1];
  EXPECT_TRUE(line_starting(render::text(r), s.name + ": not validated"));
  // Far beyond: the LPU misses the distribution.
  s.d_low = s.validation_delta + 10 * s.interval_end_std_error;
  EXPECT_NE(render::validation_advice_lines(r)[1].find("sampling error does not explain it"), std::string::npos);
  const auto lpu = row_after(render::text(r), "LPU u_c", s.name);
  ASSERT_FALSE(lpu.empty());
  EXPECT_EQ(lpu.back(), "no");
}

TEST(MonteCarloText, TheAdaptiveProcedureHasItsTableAndVerdict) {
  const verbs::MonteCarloResult r = small_run(1);
  ASSERT_TRUE(r.monte_carlo.adaptive);
  const std::string text = render::text(r);
  EXPECT_TRUE(line_starting(text, "Adaptive procedure (JCGM 101 §7.9.4, n_dig = 1)")) << text;
  const OutputSummary& s = r.monte_carlo.outputs[0];
  const auto row = row_after(text, "2 s(y)", s.name);
  ASSERT_EQ(row.size(), 7u);
  EXPECT_EQ(row[3], number(2 * s.s_mean * r.budget.display_scale[0], 3));
  const std::string verdict =
      r.monte_carlo.converged ? "; adaptive procedure converged." : "; adaptive procedure NOT converged.";
  EXPECT_NE(text.find(verdict), std::string::npos) << text;
  const auto j = nlohmann::json::parse(render::json(r));
  EXPECT_TRUE(j["adaptive"].get<bool>());
  EXPECT_EQ(j["coefficients"][s.name]["adaptive"]["s_mean"].get<double>(), s.s_mean * r.budget.display_scale[0]);
}

TEST(MonteCarloJson, TheNumbersAreTheTextsInTheSameUnits) {
  const verbs::MonteCarloResult r = small_run();
  const auto j = nlohmann::json::parse(render::json(r));
  EXPECT_EQ(j["command"], "montecarlo");
  EXPECT_EQ(j["trials"], 4000);
  EXPECT_FALSE(j["coefficients"].begin()->contains("adaptive"));  // fixed M: no adaptive part
  const auto rows = test::rendered_lines(render::csv(r));
  ASSERT_EQ(rows.size(), 1 + r.monte_carlo.outputs.size());
  for (std::size_t k = 0; k < r.monte_carlo.outputs.size(); ++k) {
    const OutputSummary& s = r.monte_carlo.outputs[k];
    const double f = r.budget.display_scale[k];
    const auto& c = j["coefficients"][s.name];
    EXPECT_EQ(c["unit"], r.budget.units[k]);
    EXPECT_EQ(c["std_dev"].get<double>(), s.std_dev * f);
    EXPECT_EQ(c["lpu"]["validated"].get<bool>(), s.validated);
    EXPECT_EQ(c["histogram"]["counts"].size(), s.histogram.counts.size());
    const auto csv = test::csv_fields(rows[k + 1]);
    ASSERT_EQ(csv.size(), 15u);
    EXPECT_EQ(csv[0], s.name);
    EXPECT_EQ(std::stod(csv[3]), s.std_dev * f);
    EXPECT_EQ(csv[14], s.validated ? "true" : "false");
  }
  // The covariance in the display units: the correlation times both standard deviations.
  const double f0 = r.budget.display_scale[0], f1 = r.budget.display_scale[1];
  EXPECT_EQ(j["covariance"][0][1].get<double>(), r.monte_carlo.covariance(0, 1) * f0 * f1);
  EXPECT_EQ(j["correlation"][0][1].get<double>(), r.monte_carlo.correlation(0, 1));
}

}  // namespace montecarlo_render_test
}  // namespace ccal
