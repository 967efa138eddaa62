// The observations file and the CSV reader: the header comment round-trips, simulated observations are
// written in output units in canonical column order with every digit, and the fit problem of a table binds
// terms to columns or to powers of the input.
#include <gtest/gtest.h>

#include <numbers>

#include "ccal/io/observation_csv.hpp"
#include "experiment_support.hpp"

namespace ccal::test {
namespace {

TEST(ObservationCsv, HeaderRoundTrip) {
  ObservationsHeader h;
  h.terms = {{"K0", "K0"}, {"K2", "Z2"}, {"K_pp", "K_pp"}};
  h.fixed = {{{"K1", "K1"}, 505.2097, "deg/s/g"}, {{"K3", "K3"}, -1.25e-3, "deg/s/g^3"}};
  h.known = {"rate"};
  h.output_unit = "deg/s";
  const std::string line = format_observations_header(h);
  EXPECT_EQ(
      line,
      "# ccal observations v1; terms=K0:K0,K2:Z2,K_pp:K_pp; fixed=K1:K1=505.2097 deg/s/g,K3:K3=-0.00125 "
      "deg/s/g^3; known=rate; output_unit=deg/s");
  const CsvTable t = parse_csv(line + "\nrun,output\na,1\n", "h.csv");
  const auto back = observations_header(t);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->line, 1);
  ASSERT_EQ(back->terms.size(), 3u);
  EXPECT_EQ(back->terms[1].id, "K2");
  EXPECT_EQ(back->terms[1].column, "Z2");
  ASSERT_EQ(back->fixed.size(), 2u);
  EXPECT_EQ(back->fixed[0].value, 505.2097);  // the shortest decimal that reads back as the same double
  EXPECT_EQ(back->fixed[1].unit, "deg/s/g^3");
  EXPECT_EQ(back->known, std::vector<std::string>{"rate"});
  EXPECT_EQ(back->output_unit, "deg/s");
  // A plain table has no header; a term both free and fixed is refused at the comment's line.
  EXPECT_FALSE(observations_header(parse_csv("x,y\n1,2\n", "p.csv")).has_value());
  try {
    observations_header(parse_csv("\n# ccal observations v1; terms=K0; fixed=K0=1\nx\n1\n", "d.csv"));
    ADD_FAILURE();
  } catch (const CsvError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(std::string(e.what()).find("'K0' is listed twice"), std::string::npos) << e.what();
  }
}

TEST(ObservationCsv, HeaderCarriesTheConfigurationsFingerprint) {
  // Written only when known (older files stay readable), read back exactly, a malformed one refused at its line.
  ObservationsHeader h;
  h.terms = {{"K0", "K0"}};
  h.output_unit = "deg/s";
  EXPECT_EQ(format_observations_header(h).find("config_sha256"), std::string::npos);
  h.config_sha256 = std::string(64, 'a');
  const std::string line = format_observations_header(h);
  EXPECT_TRUE(line.ends_with("; config_sha256=" + std::string(64, 'a'))) << line;
  EXPECT_EQ(observations_header(parse_csv(line + "\nrun,output\na,1\n", "h.csv"))->config_sha256, h.config_sha256);
  try {
    observations_header(parse_csv("# ccal observations v1; terms=K0; config_sha256=ABC\nx\n1\n", "d.csv"));
    ADD_FAILURE();
  } catch (const CsvError& e) {
    EXPECT_EQ(e.line(), 1);
    EXPECT_NE(std::string(e.what()).find("'ABC' is not a SHA-256; accepted: 64 lower-case hex digits"),
              std::string::npos)
        << e.what();
  }
}

TEST(ObservationCsv, HeaderCarriesEachLogsFileAndFingerprint) {
  // A line per log after the header, read back exactly, the file name last so that it may hold ';' and '=';
  // a malformed line is refused at its own line.
  ObservationsHeader h;
  h.terms = {{"K0", "K0"}};
  h.output_unit = "deg/s";
  h.logs = {{"5g", std::string(64, 'b'), "logs/5g.csv"}, {"run; 2", std::string(64, 'c'), "a; b=c.csv"}};
  const std::string text = format_observations_header(h);
  EXPECT_NE(text.find("\n# ccal log v1; run=5g; sha256=" + std::string(64, 'b') + "; file=logs/5g.csv\n"),
            std::string::npos)
      << text;
  const auto back = observations_header(parse_csv(text + "\nrun,output\na,1\n", "h.csv"));
  ASSERT_TRUE(back.has_value());
  ASSERT_EQ(back->logs.size(), 2u);
  EXPECT_EQ(back->logs[0], h.logs[0]);
  EXPECT_EQ(back->logs[1].file, "a; b=c.csv");
  for (const auto& [line, hint] :
       {std::pair{"# ccal log v1; run=5g; sha256=xyz; file=a.csv", "'xyz' is not a SHA-256"},
        std::pair{"# ccal log v2; run=5g", "unsupported log line"},
        std::pair{"# ccal log v1; file=a.csv", "bad log line"}}) {
    try {
      observations_header(parse_csv(std::string("# ccal observations v1; terms=K0\n") + line + "\nx\n1\n", "d.csv"));
      ADD_FAILURE() << line;
    } catch (const CsvError& e) {
      EXPECT_EQ(e.line(), 2);
      EXPECT_NE(std::string(e.what()).find(hint), std::string::npos) << e.what();
    }
  }
}

TEST(ObservationCsv, HeaderCarriesTheLogsSpansAndWhatTheyMeasured) {
  // `duration=` on a log line and a "# ccal measured v1" line per measured input, read back exactly (u with 17
  // digits); the words last, so that they may hold ';'. A malformed line is refused at its own line.
  ObservationsHeader h;
  h.terms = {{"K0", "K0"}};
  h.output_unit = "deg/s";
  h.logs = {{"5g", std::string(64, 'b'), "logs/5g.csv", 449.875}};
  h.measured = {{"domega", 1.0844353669380768e-15, true, "main-axis encoder; its line fit"},
                {"ripple1_c1", 5.773502691896258e-11, false, "the ripple's fit"}};
  const std::string text = format_observations_header(h);
  EXPECT_NE(text.find("; duration=449.875; file=logs/5g.csv\n"), std::string::npos) << text;
  const auto back = observations_header(parse_csv(text + "\nrun,output\na,1\n", "h.csv"));
  ASSERT_TRUE(back.has_value());
  ASSERT_EQ(back->logs.size(), 1u);
  EXPECT_EQ(back->logs[0], h.logs[0]);
  ASSERT_EQ(back->measured.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(back->measured[k].id, h.measured[k].id);
    EXPECT_EQ(back->measured[k].standard_uncertainty, h.measured[k].standard_uncertainty);
    EXPECT_EQ(back->measured[k].resolved, h.measured[k].resolved);
    EXPECT_EQ(back->measured[k].how, h.measured[k].how);
  }
  const std::string log = "# ccal log v1; run=5g; sha256=" + std::string(64, 'b');
  for (const auto& [line, hint] :
       {std::pair{log + "; duration=-3; file=a.csv", "not a positive number of seconds"},
        std::pair{std::string("# ccal measured v1; id=domega; u=0; resolved=true; how=x"), "not a positive number"},
        std::pair{std::string("# ccal measured v1; id=domega; u=1e-9; resolved=maybe; how=x"),
                  "bad measured-input entry"},
        std::pair{std::string("# ccal measured v1; id=domega; u=1e-9; how=x"), "incomplete measured-input line"},
        std::pair{std::string("# ccal measured v1; id=domega; u=1e-9; resolved=true"), "bad measured-input line"},
        std::pair{std::string("# ccal measured v2; id=domega"), "unsupported measured-input line"}}) {
    try {
      observations_header(parse_csv("# ccal observations v1; terms=K0\n" + line + "\nx\n1\n", "d.csv"));
      ADD_FAILURE() << line;
    } catch (const CsvError& e) {
      EXPECT_EQ(e.line(), 2);
      EXPECT_NE(std::string(e.what()).find(hint), std::string::npos) << e.what();
    }
  }
}

TEST(ObservationCsv, CellsAndPlaces) {
  const CsvTable t =
      parse_csv("# c\r\n run , x ,y\r\n\r\n\"a, b\", +1.5 ,-2e-3\r\n\"say \"\"hi\"\"\",0,1\r\n", "t.csv");
  EXPECT_EQ(t.header, (std::vector<std::string>{"run", "x", "y"}));
  EXPECT_EQ(t.header_line, 2);
  EXPECT_EQ(t.row_lines, (std::vector<int>{4, 5}));
  EXPECT_EQ(t.rows[0][0], "a, b");
  EXPECT_EQ(t.rows[1][0], "say \"hi\"");
  EXPECT_EQ(t.numbers("x", "test")[0], 1.5);
  EXPECT_EQ(t.numbers("y", "test")[0], -2e-3);
  try {
    t.numbers("run", "test");
    ADD_FAILURE();
  } catch (const CsvError& e) {
    EXPECT_EQ(e.line(), 4);
    EXPECT_EQ(e.column(), 1);
    EXPECT_EQ(e.column_name(), "run");
    EXPECT_TRUE(std::string(e.what()).starts_with("t.csv:4:1: run: 'a, b' is not a number")) << e.what();
  }
  EXPECT_FALSE(parse_number("1.5x").has_value());
  EXPECT_FALSE(parse_number("+-1").has_value());
  EXPECT_FALSE(parse_number("inf").has_value());
  EXPECT_EQ(parse_number(" 2 "), 2.0);
}

TEST(ObservationCsv, TermAssignmentSplitsAtTheFirstEqualsSign) {
  auto parts = [](std::string_view text) {
    const auto a = split_term_assignment(text);
    return a ? std::vector<std::string>{a->term, a->value, a->unit} : std::vector<std::string>{"none"};
  };
  EXPECT_EQ(parts("K1=505.2 deg/s/g"), (std::vector<std::string>{"K1", "505.2", "deg/s/g"}));
  EXPECT_EQ(parts(" \tK1:Z1 \t= \t505.2\t deg/s/g \t"),
            (std::vector<std::string>{"K1:Z1", "505.2", "deg/s/g"}));
  EXPECT_EQ(parts("K0=-1e-3"), (std::vector<std::string>{"K0", "-1e-3", ""}));
  EXPECT_EQ(parts("K2 = 3 ppm / g"), (std::vector<std::string>{"K2", "3", "ppm / g"}));
  EXPECT_EQ(parts("K1=a=b c"), (std::vector<std::string>{"K1", "a=b", "c"}));
  EXPECT_EQ(parts("=5"), (std::vector<std::string>{"", "5", ""}));
  EXPECT_EQ(parts("K1="), (std::vector<std::string>{"K1", "", ""}));
  EXPECT_EQ(parts("K1 505.2"), (std::vector<std::string>{"none"}));
  // The observations header's fixed entries read with it: blanks and tabs around each part.
  const auto h = observations_header(parse_csv(
      "# ccal observations v1; terms=K0:K0; fixed=K1:Z1 =\t505.25 \t deg/s/g\nK0,Z1\n1,2\n", "f.csv"));
  ASSERT_TRUE(h.has_value());
  ASSERT_EQ(h->fixed.size(), 1u);
  EXPECT_EQ(h->fixed[0].term.id, "K1");
  EXPECT_EQ(h->fixed[0].term.column, "Z1");
  EXPECT_EQ(h->fixed[0].value, 505.25);
  EXPECT_EQ(h->fixed[0].unit, "deg/s/g");
}

TEST(ObservationCsv, SimulatedObservationsInOutputUnits) {
  // K_w and K_p columns follow the canonical order (K0 … K10, then the named terms) whatever the spec's
  // order, and every value is written with 17 significant digits so that it reads back exactly.
  const Experiment ex = paper_experiment(true);
  IdentificationSpec spec;
  spec.free_terms = {"K_w", "K3", "K0", "K_p"};
  spec.fixed_terms = {{"K1", 505.2097 * kDeg}};
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(ex.layout.size());
  const auto obs = observe<double>(ex, zero, zero, spec);
  const std::string text = observations_csv(obs, spec, ex.instrument);
  const CsvTable t = parse_csv(text, "sim.csv");
  EXPECT_EQ(t.header,
            (std::vector<std::string>{"run", "a_i", "output", "rate", "K0", "K1", "K3", "K_p", "K_w"}));
  const auto h = observations_header(t).value();
  EXPECT_EQ(h.terms.size(), 4u);
  EXPECT_EQ(h.terms[0].id, "K_w");
  EXPECT_EQ(h.fixed[0].unit, "deg/s/g");
  EXPECT_EQ(h.fixed[0].value, 505.2097 * kDeg / kDeg);  // exactly the converted double
  const Eigen::VectorXd output = t.numbers("output", "test");
  const Eigen::VectorXd kw = t.numbers("K_w", "test");
  for (Eigen::Index j = 0; j < output.size(); ++j) {
    EXPECT_EQ(output[j], obs.output[j] / kDeg);  // deg/s, bit for bit
    EXPECT_EQ(kw[j], obs.regressors(j, 0));      // ⟨ω_IA⟩ stays in rad/s
  }
  EXPECT_EQ(t.rows[0][0], "5g");
}

TEST(ObservationCsv, FitProblemBindsTermsToColumnsOrPowers) {
  const CsvTable t = parse_csv("run,x,y,Z2,s,c\na,1,10,5,1,1\nb,2,20,6,2,1\nc,3,30,7,4,1\n", "f.csv");
  TableFitSpec spec;
  spec.input = "x";
  spec.output = "y";
  spec.terms = {{"K0", ""}, {"K2", "Z2"}};
  spec.fixed = {{{"K3", ""}, 0.5}};
  spec.known = {"c"};
  spec.weight = "s";
  const FitProblem p = table_fit_problem(t, spec);
  EXPECT_EQ(p.term_names, (std::vector<std::string>{"K0", "K2", "K3"}));
  EXPECT_EQ(p.H.col(0), Eigen::Vector3d(1, 1, 1));
  EXPECT_EQ(p.H.col(1), Eigen::Vector3d(5, 6, 7));   // the bound column, not x²
  EXPECT_EQ(p.H.col(2), Eigen::Vector3d(1, 8, 27));  // x³
  EXPECT_EQ(p.y, Eigen::Vector3d(9, 19, 29));        // y − c
  EXPECT_EQ(p.weights, Eigen::Vector3d(1, 0.25, 0.0625));
  EXPECT_EQ(p.fixed.at("K3"), 0.5);
  EXPECT_EQ(p.row_labels, (std::vector<std::string>{"a", "b", "c"}));
  // A named term must be bound: that is the caller's check.
  spec.terms.push_back({"K_pp", ""});
  EXPECT_THROW(table_fit_problem(t, spec), std::invalid_argument);
}

}  // namespace
}  // namespace ccal::test
