// verbs::identify in-process (docs/cli.md `ccal identify`): a plain table's polynomial fit against the closed
// forms of least squares written out here (a straight line: slope S_xy/S_xx, intercept ȳ − b x̄, standard
// errors from s² = RSS/(n − 2); a weighted mean: Σ w y / Σ w with variance 1/Σ w), a held term subtracted
// before the fit, the calibration statement of a budget, and the options' errors naming the option.
#include "ccal/verbs/identify.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "ccal/core/errors.hpp"
#include "ccal/core/options.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/verbs/simulate.hpp"
#include "verbs_support.hpp"

namespace ccal::test {
namespace {

// Points (x, y) off the line 1.5 + 2x by fixed deviations (not random: the closed forms are exact anyway).
const std::vector<double> kX{0.5, 1, 2, 3, 4.5, 6, 7.5};
const std::vector<double> kDev{0.01, -0.02, 0.015, 0.0, -0.01, 0.02, -0.005};

CsvTable line_table() {
  std::string text = "x,y,s\n";
  for (std::size_t i = 0; i < kX.size(); ++i)
    text += fmt::format("{:.17g},{:.17g},{:.17g}\n", kX[i], 1.5 + 2 * kX[i] + kDev[i], 0.01 * double(i + 1));
  return parse_csv(text, "line.csv");
}

verbs::IdentifyOptions line_options(std::vector<std::string> terms) {
  verbs::IdentifyOptions o;
  o.terms = std::move(terms);
  o.input_column = std::string("x");  // not = "x": GCC 12 misreads that inlined here (-Wrestrict)
  o.output_column = std::string("y");  // not = "y": GCC 12 misreads that inlined here (-Wrestrict)
  return o;
}

TEST(IdentifyVerb, StraightLineEqualsTheClosedFormOfLeastSquares) {
  const verbs::IdentifyResult r = verbs::identify(line_table(), line_options({"K0", "K1"}));
  const double n = double(kX.size());
  double sx = 0, sy = 0;
  for (std::size_t i = 0; i < kX.size(); ++i) sx += kX[i], sy += 1.5 + 2 * kX[i] + kDev[i];
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < kX.size(); ++i) {
    sxx += (kX[i] - mx) * (kX[i] - mx);
    sxy += (kX[i] - mx) * (1.5 + 2 * kX[i] + kDev[i] - my);
  }
  const double b = sxy / sxx, a = my - b * mx;
  double rss = 0;
  for (std::size_t i = 0; i < kX.size(); ++i) rss += std::pow(1.5 + 2 * kX[i] + kDev[i] - a - b * kX[i], 2);
  const double s2 = rss / (n - 2);
  // Tolerance 1e-12 relative on the estimates (two different orders of summation of 7 terms of size ~10)
  // and 1e-9 on the standard errors (s² is a difference of nearly equal sums: RSS ~1e-3 of Σy²·1e-4).
  ASSERT_EQ(r.identification.fit.names, (std::vector<std::string>{"K0", "K1"}));
  EXPECT_NEAR(r.identification.fit.value[0], a, 1e-12 * std::abs(a));
  EXPECT_NEAR(r.identification.fit.value[1], b, 1e-12 * std::abs(b));
  const double se_b = std::sqrt(s2 / sxx), se_a = std::sqrt(s2 * (1 / n + mx * mx / sxx));
  EXPECT_NEAR(r.identification.fit.std_error[0], se_a, 1e-9 * se_a);
  EXPECT_NEAR(r.identification.fit.std_error[1], se_b, 1e-9 * se_b);
  EXPECT_EQ(r.identification.fit.dof, int(n) - 2);
  EXPECT_EQ(r.rows, kX.size());
  // The units of a plain table are written with its column names.
  EXPECT_EQ(r.identification.units, (std::vector<std::string>{"y", "y/x"}));
}

TEST(IdentifyVerb, AHeldTermIsSubtractedBeforeTheFit) {
  // K1 held at 2: K0 is the mean of y − 2x = 1.5 + the mean deviation, to 1e-14 (7 terms of size ~1.5).
  verbs::IdentifyOptions o = line_options({"K0"});
  o.fix = std::vector<std::string>{"K1=2"};
  const verbs::IdentifyResult r = verbs::identify(line_table(), o);
  double mean_dev = 0;
  for (double d : kDev) mean_dev += d / double(kDev.size());
  EXPECT_NEAR(r.identification.fit.value[0], 1.5 + mean_dev, 1e-14);
  ASSERT_EQ(r.identification.fixed.size(), 1u);
  EXPECT_EQ(r.identification.fixed[0].value, 2.0);
}

TEST(IdentifyVerb, WeightedConstantIsTheWeightedMean) {
  // K0 alone with σ_i from the column s: the weighted mean Σ w y / Σ w, w = 1/σ², with standard error
  // 1/√Σw (the σ taken as known: a weighted fit's covariance is (HᵀWH)⁻¹). 1e-13 relative: sums of 7 terms.
  verbs::IdentifyOptions o;
  o.terms = std::vector<std::string>{"K0"};
  o.output_column = "y";
  o.weight_column = "s";
  const verbs::IdentifyResult r = verbs::identify(line_table(), o);
  double sw = 0, swy = 0;
  for (std::size_t i = 0; i < kX.size(); ++i) {
    const double w = 1 / std::pow(0.01 * double(i + 1), 2);
    sw += w;
    swy += w * (1.5 + 2 * kX[i] + kDev[i]);
  }
  EXPECT_TRUE(r.identification.weighted);
  EXPECT_NEAR(r.identification.fit.value[0], swy / sw, 1e-13 * swy / sw);
  EXPECT_NEAR(r.identification.fit.std_error[0], 1 / std::sqrt(sw), 1e-13 / std::sqrt(sw));
}

TEST(IdentifyVerb, TheBudgetGivesTheStatementOfEachCoefficient) {
  // Observations of the paper's set-up (no rate noise, so the budget's u is the Type B part) with a noisy
  // instrument, identified with that configuration as budget: per coefficient the Type A part is the noise
  // model's, σ = N/√T for every run (equal T), so C_A = σ² (HᵀH)⁻¹ while the fit's standard error is
  // s √((HᵀH)⁻¹_kk): u_A = (σ/s)·std_error, ν = ∞ (1e-10 relative: the pseudo-inverse against the fit's QR);
  // u_c² = u_A² + u_B² (1e-12 relative: one sum of squares).
  const Config config = parse_config(edited(read_text(kPaperConfigPath), "noise_density = \"0 deg/s/rtHz\"",
                                            "noise_density = \"0.05 deg/s/rtHz\""),
                                     "noisy-paper.toml");
  const verbs::SimulateResult sim = verbs::simulate(config);
  verbs::IdentifyOptions o;
  o.statement = true;
  o.config = config;
  const verbs::IdentifyResult r = verbs::identify(parse_csv(sim.observations_csv, "obs.csv"), o);
  ASSERT_TRUE(r.statement.has_value());
  ASSERT_EQ(r.statement->coefficients.size(), r.identification.fit.names.size());
  ASSERT_TRUE(r.statement->type_a.from_noise_model);
  ASSERT_FALSE(r.statement->type_a.excess) << "the noise the observations have is the noise the set-up states";
  for (std::size_t k = 0; k < r.statement->coefficients.size(); ++k) {
    const CoefficientStatement& c = r.statement->coefficients[k];
    EXPECT_EQ(c.input.coefficient, r.identification.fit.names[k]);
    const double sigma = config.instrument.noise_density / std::sqrt(config.plan.runs.front().duration) /
                         output_unit_si(config.instrument.output_unit);
    const double u_a = sigma / r.identification.fit.residual_std * r.identification.fit.std_error[Eigen::Index(k)];
    EXPECT_NEAR(c.input.type_a.u, u_a, 1e-10 * u_a);
    EXPECT_TRUE(std::isinf(c.input.type_a.dof));
    EXPECT_GT(c.input.type_b.u, 0.0);
    EXPECT_NEAR(c.combined, std::hypot(c.input.type_a.u, c.input.type_b.u), 1e-12 * c.combined);
  }
}

TEST(IdentifyVerb, BadOptionsNameTheField) {
  // An OptionError names the field of IdentifyOptions (each front end words it with its own spelling).
  auto refusal = [](const verbs::IdentifyOptions& o) -> std::pair<std::string, std::string> {
    try {
      verbs::identify(line_table(), o);
    } catch (const OptionError& e) {
      return {e.field(), e.what()};
    }
    return {"no error", ""};
  };
  const auto [field, what] = refusal(line_options({"K0", "Q7"}));
  EXPECT_EQ(field, "terms");
  EXPECT_EQ(what.rfind("terms: 'Q7' is not a term id; accepted: K0, K1, K2,", 0), 0u) << what;
  verbs::IdentifyOptions fix = line_options({"K0"});
  fix.fix = std::vector<std::string>{"K1=two"};
  EXPECT_EQ(refusal(fix).second,
            "fix: 'two' in 'K1=two' is not a finite number; accepted: <term>=<value>, e.g. "
            "K1=505.2097");
  verbs::IdentifyOptions bound = line_options({"K0", "K_pp"});
  EXPECT_EQ(refusal(bound).second,
            "terms: K_pp is not a power of the input, so it needs its column: bind it as "
            "K_pp:<column>, e.g. K_pp:K_pp (only K0 ... K10 are computed from the "
            "input_column column)");
  // An empty list of terms is refused by the table's row, as from every front end.
  EXPECT_EQ(refusal(line_options({})).second, "terms: none given; accepted: at least one TERMS");
  // The statement needs its configuration, and the configuration is read only for a statement.
  verbs::IdentifyOptions statement = line_options({"K0", "K1"});
  statement.statement = true;
  EXPECT_EQ(refusal(statement).second,
            "statement: needs the configuration whose tolerances give its Type B "
            "part; accepted: that configuration as config");
  verbs::IdentifyOptions config = line_options({"K0", "K1"});
  config.config = parse_config(read_text(kPaperConfigPath), "paper.toml");
  EXPECT_EQ(refusal(config).second,
            "config: paper.toml is read only for the calibration statement; accepted: "
            "with statement");
}

TEST(IdentifyVerb, NoDegreesOfFreedomLeavesTheStandardErrorsUndefined) {
  // Two points, two free terms: the line passes both, RSS = 0 with dof = 0, so s² = RSS/dof is 0/0 and the
  // unweighted standard errors s·√((HᵀH)⁻¹)ₖₖ are undefined. A 0 would read as an exact coefficient: they are
  // NaN (n/a, null, an empty cell), as are the residual std and chi2/dof, and the warning says so.
  const CsvTable two = parse_csv("x,y\n1,2\n2,3\n", "two.csv");
  const verbs::IdentifyResult r = verbs::identify(two, line_options({"K0", "K1"}));
  const FitResult& fit = r.identification.fit;
  EXPECT_EQ(fit.dof, 0);
  EXPECT_NEAR(fit.value[0], 1.0, 1e-14);
  EXPECT_NEAR(fit.value[1], 1.0, 1e-14);
  EXPECT_TRUE(std::isnan(fit.std_error[0]) && std::isnan(fit.std_error[1]));
  EXPECT_TRUE(std::isnan(fit.residual_std) && std::isnan(fit.chi2_per_dof));
  ASSERT_FALSE(fit.warnings.empty());
  EXPECT_EQ(fit.warnings.front().rfind("no degrees of freedom (2 rows, 2 free terms): ", 0), 0u);
  EXPECT_NE(fit.warnings.front().find("standard errors"), std::string::npos);
  EXPECT_EQ(std::count_if(fit.warnings.begin(), fit.warnings.end(),
                          [](const std::string& w) { return w.starts_with("no degrees of freedom"); }),
            1);
  // With weights the standard errors come from σ (1/√Σw for a weighted mean) and stay; only the residual
  // scale is undefined.
  const CsvTable one = parse_csv("x,y,s\n1,2,0.5\n", "one.csv");
  verbs::IdentifyOptions weighted = line_options({"K0"});
  weighted.weight_column = "s";
  const FitResult& w = verbs::identify(one, weighted).identification.fit;
  EXPECT_NEAR(w.std_error[0], 0.5, 1e-15);
  EXPECT_TRUE(std::isnan(w.residual_std));
}

TEST(IdentifyVerb, KnownColumnsMustBeOtherThanTheOutputAndEachOnce) {
  // Subtracting the output from itself leaves y = 0 and every coefficient 0 ± 0: refused, as is a column
  // listed twice (subtracted twice) and 'none' among columns, naming the known option.
  auto refusal = [](std::vector<std::string> known) -> std::pair<std::string, std::string> {
    verbs::IdentifyOptions o = line_options({"K0", "K1"});
    o.known = std::move(known);
    try {
      verbs::identify(line_table(), o);
    } catch (const OptionError& e) {
      return {e.field(), e.what()};
    }
    return {"no error", ""};
  };
  EXPECT_EQ(refusal({"y"}), (std::pair<std::string, std::string>{
                                "known",
                                "known: y is the output column (output_column), which cannot be "
                                "subtracted from itself; accepted: the columns of known contributions "
                                "to subtract from the output, other than the output"}));
  EXPECT_EQ(refusal({"s", "s"}), (std::pair<std::string, std::string>{
                                     "known", "known: s is listed twice; accepted: each column once"}));
  EXPECT_EQ(refusal({"none", "s"}).first, "known");
  EXPECT_EQ(refusal({"s"}).first, "no error");
}

TEST(IdentifyVerb, NoStatementWithoutDegreesOfFreedom) {
  // Three of the paper's six runs for its three free terms: no degrees of freedom, so the Type A part of the
  // statement (the standard errors) is undefined and a statement would be misleading; refused, naming it.
  const Config config = parse_config(read_text(kPaperConfigPath), "paper.toml");
  std::string csv = verbs::simulate(config).observations_csv;
  for (int dropped = 0; dropped < 3; ++dropped) csv.erase(csv.rfind('\n', csv.size() - 2) + 1);
  verbs::IdentifyOptions o;
  o.statement = true;
  o.config = config;
  try {
    verbs::identify(parse_csv(csv, "obs.csv"), o);
    ADD_FAILURE() << "a statement without degrees of freedom was made";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "statement");
    EXPECT_NE(std::string(e.what()).find("3 rows for 3 free terms leave no degrees of freedom"),
              std::string::npos)
        << e.what();
  }
}

TEST(IdentifyVerb, CoefficientsPerStandardGravitySayGn) {
  // A configuration whose coefficients are per g_n ([site] g_unit = "standard") writes its fixed terms per gn;
  // identifying the file gives every unit per gn too, with or without the configuration.
  std::string text(bundled_example_text());
  const std::string g = "g = \"9.8 m/s^2\"";
  ASSERT_NE(text.find(g), std::string::npos);
  text.replace(text.find(g), g.size(), g + "\ng_unit = \"standard\"");
  const Config config = parse_config(text, "standard.toml");
  const verbs::SimulateResult s = verbs::simulate(config);
  EXPECT_NE(s.observations_csv.find("/gn"), std::string::npos);
  const verbs::IdentifyResult r = verbs::identify(parse_csv(s.observations_csv, "obs.csv"));
  for (const std::string& unit : r.identification.units)
    if (unit != r.identification.units.front()) {
      EXPECT_NE(unit.find("/gn"), std::string::npos) << unit;
    }
  EXPECT_EQ(r.identification.units.back(), "deg/s/gn^3");
}

}  // namespace
}  // namespace ccal::test
