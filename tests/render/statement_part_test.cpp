// The calibration statement as read (render/statement.hpp, src/render/statement_part.cpp), on statements of
// verbs::identify: the heading says how k was found (Student's t at p, or stated), each result line rounds U to
// two significant digits with the estimate to the same place (JCGM 100 §7.2.6), a stated k gives the p of a
// normal quantity, the Monte Carlo check's table appears only when it ran, a coefficient whose interval holds 0
// is named, and nu = inf reads "inf".
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/render/statement.hpp"
#include "ccal/uncertainty/statement.hpp"
#include "ccal/verbs/identify.hpp"
#include "ccal/verbs/simulate.hpp"
#include "render_support.hpp"
#include "verbs_support.hpp"

namespace ccal {
namespace statement_part_render_test {

using test::line_starting;

verbs::CalibrationStatement paper_statement(std::optional<double> stated_k, std::int64_t trials) {
  const Config paper = load_config(test::kPaperConfigPath);
  verbs::IdentifyOptions o;
  o.statement = true;
  o.statement_options.coverage_factor = stated_k;
  o.statement_options.statement_trials = trials;
  o.statement_options.threads = 1;
  o.config = paper;
  return *verbs::identify(parse_csv(verbs::simulate(paper).observations_csv, "obs.csv"), o).statement;
}

TEST(StatementText, EachResultLineRoundsUToTwoDigitsWithStudentsK) {
  const verbs::CalibrationStatement st = paper_statement(std::nullopt, 0);
  const std::string text = render::text(st);
  EXPECT_EQ(text.rfind("Calibration statement (JCGM 100 §7): ", 0), 0u) << text;
  const std::string words = test::words_of(text);
  EXPECT_NE(words.find("k from Student's t at p = 95 %; known [errors]: none."), std::string::npos) << words;
  for (const CoefficientStatement& c : st.coefficients) {
    const RoundedFigures r = round_figures(c);
    const std::string line = fmt::format("{} = ({} ± {}) {}, k = {:.3f}, p = 95 %: [{}, {}]", c.input.coefficient,
                                         r.estimate, r.expanded, c.input.unit, c.coverage_factor, r.low, r.high);
    EXPECT_NE(words.find(line), std::string::npos) << line << "\n" << text;
  }
  // U to two significant digits: K2's U as written has two digits after its leading zeros.
  const RoundedFigures k2 = round_figures(st.coefficients[1]);
  std::string digits;
  for (char ch : k2.expanded)
    if (std::isdigit(static_cast<unsigned char>(ch)) && (ch != '0' || !digits.empty())) digits += ch;
  EXPECT_EQ(digits.size(), 2u) << k2.expanded;
  // Statement trials 0: no Monte Carlo table, and a sentence saying so.
  EXPECT_NE(words.find("No Monte Carlo check of the intervals (statement trials 0, or no [tolerances])."),
            std::string::npos);
  EXPECT_EQ(text.find("u (MC)"), std::string::npos);
}

TEST(StatementText, AStatedKGivesTheNormalQuantitysP) {
  const verbs::CalibrationStatement st = paper_statement(2.0, 0);
  const std::string words = test::words_of(render::text(st));
  EXPECT_NE(words.find("k = 2 stated (p = 95.45 % for a normal quantity)"), std::string::npos) << words;
  for (const CoefficientStatement& c : st.coefficients) {
    ASSERT_TRUE(c.stated);
    const RoundedFigures r = round_figures(c);
    // nu_eff finite (Type A from the fit's scatter): Student's t's p at nu_eff too.
    ASSERT_TRUE(std::isfinite(c.effective_dof));
    EXPECT_NE(words.find(fmt::format("{} = ({} ± {}) {}, k = 2 (stated), p = {:.4g} % for a normal quantity, "
                                     "{:.4g} % for Student's t at nu_eff = ",
                                     c.input.coefficient, r.estimate, r.expanded, c.input.unit,
                                     100 * c.stated->normal, 100 * c.stated->student_t)),
              std::string::npos)
        << words;
  }
}

TEST(StatementText, AStatedKNamesBothProbabilitiesApart) {
  // At the paper's nu_eff (1e41 and more) both probabilities read 95.45 %: set Student's apart by hand, so that
  // the line shows which is which.
  verbs::CalibrationStatement st = paper_statement(2.0, 0);
  st.coefficients[0].stated->student_t = 0.9;
  const std::string words = test::words_of(render::text(st));
  EXPECT_NE(words.find("k = 2 (stated), p = 95.45 % for a normal quantity, 90 % for Student's t at nu_eff = "),
            std::string::npos)
      << words;
}

TEST(StatementText, TheMonteCarloCheckHasItsTableAndWhatEachStates) {
  const verbs::CalibrationStatement st = paper_statement(std::nullopt, 2000);
  ASSERT_GT(st.monte_carlo_trials, 0u);
  const std::string text = render::text(st);
  const std::string words = test::words_of(text);
  EXPECT_NE(words.find(fmt::format("Monte Carlo check (JCGM 101 §8; M = {}", st.monte_carlo_trials)),
            std::string::npos)
      << words;
  for (const CoefficientStatement& c : st.coefficients) {
    ASSERT_TRUE(c.monte_carlo);
    const auto row = line_starting(text.substr(text.find("u (MC)")), c.input.coefficient + " ");
    ASSERT_TRUE(row) << text;
    const std::string stated = c.method == IntervalMethod::monte_carlo ? "Monte Carlo"
                               : c.monte_carlo->validated             ? "Student t"
                                                                      : "Student t (M too small to tell: ";
    EXPECT_NE(row->find(stated), std::string::npos) << *row;
  }
}

TEST(StatementText, AnIntervalHoldingZeroIsNamedAndInfiniteDofReadsInf) {
  verbs::CalibrationStatement st = paper_statement(std::nullopt, 0);
  st.coefficients[0].significant = false;
  st.coefficients[1].input.type_a.dof = std::numeric_limits<double>::infinity();
  const std::string text = render::text(st);
  const std::string k0 = st.coefficients[0].input.coefficient;
  EXPECT_NE(test::words_of(text).find(k0 + "'s interval holds 0: the test does not tell " + k0 + " from zero at p = 95 %."),
            std::string::npos)
      << text;
  // Each coefficient whose interval holds 0 is named once, and only those (K3's does in this test already).
  std::size_t holding_zero = 0;
  for (const CoefficientStatement& c : st.coefficients) holding_zero += !c.significant;
  EXPECT_EQ(test::lines_holding(text, "interval holds 0"), holding_zero);
  const auto parts = test::table_cells(*line_starting(text.substr(text.find("nu_A")), "K2 "));
  ASSERT_GE(parts.size(), 3u);
  EXPECT_EQ(parts[2], "inf");
  // The JSON names the same figures; nu = inf is null there.
  const auto j = nlohmann::json::parse(render::json(st));
  EXPECT_EQ(j["coefficients"][k0]["significant"], false);
  EXPECT_TRUE(j["coefficients"]["K2"]["type_a"]["dof"].is_null());
  EXPECT_EQ(j["coefficients"]["K2"]["rounded"]["expanded_uncertainty"], round_figures(st.coefficients[1]).expanded);
}

}  // namespace statement_part_render_test
}  // namespace ccal
