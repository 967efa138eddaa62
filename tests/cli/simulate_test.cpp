// End-to-end tests of `ccal simulate` and `ccal identify`: the observations CSV contract, the round trip
// simulate → identify, polynomial fits of plain tables, weights, located errors for bad files and options,
// ill-posed plans with their hints, and -o / --observations-out writing nothing on failure.
#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ccal/core/sha256.hpp"
#include "ccal/io/config_file.hpp"
#include "cli_support.hpp"
#include "test_paths.hpp"

namespace {

using namespace ccal::test;
namespace fs = std::filesystem;

// The bundled example's instrument (°/s/gⁿ).
constexpr double kK0 = 0.061973, kK2 = 0.02, kK3 = 0.003;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) out.push_back(field);
  return out;
}

double coefficient(const nlohmann::json& j, const std::string& id) {
  return j.at("coefficients").at(id).at("value").get<double>();
}

// The example with its [identification] terms replaced.
std::string example_with_terms(const std::string& terms) {
  const std::string text = read(kExample);
  const std::string key = "terms = [\"K0\", \"K2\", \"K3\"]";
  const auto at = text.find(key);
  EXPECT_NE(at, std::string::npos);
  return text.substr(0, at) + "terms = " + terms + text.substr(at + key.size());
}

// The example with lines inserted right after the line starting with `after`.
std::string example_with(const std::string& after, const std::string& lines) {
  const std::string text = read(kExample);
  const auto at = text.find("\n" + after);
  EXPECT_NE(at, std::string::npos) << after;
  const auto end = text.find('\n', at + 1);
  return text.substr(0, end + 1) + lines + "\n" + text.substr(end + 1);
}

// A bad input whose message starts with the file, line and column: "ccal: error: <place>: ".
void expect_located(const Result& r, const std::string& place, std::initializer_list<std::string> hints) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_TRUE(r.err.starts_with("ccal: error: " + place + ": ")) << "expected '" << place << "' in " << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  for (const auto& h : hints) EXPECT_NE(r.err.find(h), std::string::npos) << "'" << h << "' in " << r.err;
}

TEST_F(Cli, HelpListsTheNewCommands) {
  const Result h = run("--help");
  ASSERT_EQ(h.code, 0);
  EXPECT_NE(h.out.find("simulate"), std::string::npos) << h.out;
  EXPECT_NE(h.out.find("identify"), std::string::npos) << h.out;
  for (const char* command : {"simulate", "identify"}) {
    const Result c = run(std::string(command) + " --help");
    EXPECT_EQ(c.code, 0) << command;
    EXPECT_NE(c.out.find("Examples:"), std::string::npos) << c.out;
  }
}

TEST_F(Cli, ObservationsCsvContract) {
  const Result r = run("simulate --observations-out obs.csv");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<std::string> lines = lines_of(read(dir_ / "obs.csv"));
  ASSERT_EQ(lines.size(), 8u);
  EXPECT_EQ(lines[0],
            "# ccal observations v1; terms=K0:K0,K2:K2,K3:K3; fixed=K1:K1=505.2097 deg/s/g; known=rate; "
            "output_unit=deg/s; config_sha256=" + ccal::bundled_example().numbers_sha256);
  // The fingerprint of the numbers, not of the text (a comment would change that): docs/config.md, "Fingerprints".
  EXPECT_NE(ccal::bundled_example().numbers_sha256, ccal::sha256_hex(ccal::bundled_example_text()));
  EXPECT_EQ(lines[1], "run,a_i,output,rate,K0,K1,K2,K3");
  const char* names[] = {"5g", "10g", "15g", "20g", "25g", "30g"};
  for (std::size_t k = 0; k < 6; ++k) {
    const std::vector<std::string> f = fields_of(lines[k + 2]);
    ASSERT_EQ(f.size(), 8u) << lines[k + 2];
    EXPECT_EQ(f[0], names[k]);
    for (std::size_t c = 1; c < f.size(); ++c) {
      // Every value reads back as a double that prints the same with 17 significant digits: nothing is lost.
      double v = 0;
      const auto [end, ec] = std::from_chars(f[c].data(), f[c].data() + f[c].size(), v);
      ASSERT_TRUE(ec == std::errc{} && end == f[c].data() + f[c].size()) << f[c];
      char buffer[64];
      std::snprintf(buffer, sizeof buffer, "%.17g", v);
      EXPECT_EQ(f[c], buffer);
    }
    // K0's regressor is the mean of 1: the quadrature weights sum to 1 up to round-off (a few ulp).
    EXPECT_NEAR(std::stod(f[4]), 1.0, 1e-15);
    // K1's regressor is ⟨a_i⟩, the a_i column.
    EXPECT_EQ(f[5], f[1]);
    // Counter-rotating at A g: ⟨a_i²⟩ ≈ A²/2 (model.md §8; the partial last revolution moves it by < 1%).
    const double A = 5.0 * double(k + 1);
    EXPECT_NEAR(std::stod(f[6]), A * A / 2, 0.01 * A * A / 2);
  }
  // --format csv prints the same file.
  const Result csv = run("simulate --format csv");
  ASSERT_EQ(csv.code, 0) << csv.err;
  EXPECT_EQ(csv.out, read(dir_ / "obs.csv"));
}

TEST_F(Cli, ADrawnTruthAndATruthFileAreRefusedTogether) {
  // Two answers for the machine's errors: exit code 2, both named, nothing written. Alone, --draw-truth runs
  // and its JSON has the draws.
  expect_bad_input(run("simulate " + kLab + " --draw-truth --truth " + kLabTruth + " --observations-out obs.csv"),
                   {"--draw-truth", "lab_truth.toml", "two answers for the machine's errors"});
  EXPECT_FALSE(std::filesystem::exists(dir_ / "obs.csv"));
  const Result drawn = run("simulate " + kLab + " --draw-truth --seed 4 --format json");
  ASSERT_EQ(drawn.code, 0) << drawn.err;
  EXPECT_NE(drawn.out.find("\"drawn_errors_si\""), std::string::npos);
}

TEST_F(Cli, SimulateThenIdentifyRecoversTheCoefficients) {
  // The example has no [errors]: truth and model are the same chain, so the fit is exact up to round-off. The
  // run means are differences of outputs swinging by K1·A ≈ 15 000 °/s, each good to ≈ 1e-16 · 15 000
  // = 1.5e-12 °/s; divided by the spread of the regressors that is < 1e-11 relative on K0, K2 and K3 (K3's Z3
  // spans ≈ 5 g³), so 1e-9 relative has a wide margin while still catching any lost digit in the CSV (17
  // significant digits).
  ASSERT_EQ(run("simulate --observations-out obs.csv -o sim.json --format json").code, 0);
  const Result r = run("identify obs.csv --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(coefficient(j, "K0"), kK0, 1e-9 * kK0);
  EXPECT_NEAR(coefficient(j, "K2"), kK2, 1e-9 * kK2);
  EXPECT_NEAR(coefficient(j, "K3"), kK3, 1e-9 * kK3);
  EXPECT_EQ(j.at("coefficients").size(), 3u);
  EXPECT_EQ(j.at("fixed").at("K1").at("unit"), "deg/s/g");
  EXPECT_DOUBLE_EQ(j.at("fixed").at("K1").at("value").get<double>(), 505.2097);
  EXPECT_EQ(j.at("known"), nlohmann::json::array({"rate"}));
  // simulate identified the same file in memory: the same numbers, to the last bit.
  const nlohmann::json sim = nlohmann::json::parse(read(dir_ / "sim.json"));
  for (const char* id : {"K0", "K2", "K3"}) {
    EXPECT_EQ(coefficient(sim.at("identification"), id), coefficient(j, id)) << id;
  }
  // The same fit with everything spelt out on the command line, the fixed value in another unit: 8.817572678
  // rad/s/g is 505.2097 °/s/g to 10 digits (ΔK1 < 3e-8 °/s/g); times ⟨a_i⟩ < 0.006 g that moves the outputs
  // by < 2e-10 °/s, 3e-9 of K0, so 1e-8 relative checks that the unit was converted (a factor 57 otherwise).
  const Result spelt = run(
      "identify obs.csv --terms K0,K2:K2,K3:K3 --fix 'K1:K1=8.817572678 rad/s/g' --known rate --format json");
  ASSERT_EQ(spelt.code, 0) << spelt.err;
  const nlohmann::json s = nlohmann::json::parse(spelt.out);
  EXPECT_NEAR(s["fixed"]["K1"]["value"].get<double>(), 8.817572678 * 180 / 3.14159265358979323846, 1e-12);
  EXPECT_NEAR(coefficient(s, "K0"), kK0, 1e-8 * kK0);
  EXPECT_NEAR(coefficient(s, "K3"), kK3, 1e-8 * kK3);
  // Unbound K2, K3 are powers of ⟨a_i⟩, not the run means ⟨a_i²⟩, ⟨a_i³⟩ of the file's columns: a warning
  // says so.
  const Result powers = run("identify obs.csv --terms K0,K2,K3 --format json");
  ASSERT_EQ(powers.code, 0) << powers.err;
  const nlohmann::json w = nlohmann::json::parse(powers.out).at("warnings");
  ASSERT_EQ(w.size(), 2u) << w;
  EXPECT_NE(w[0].get<std::string>().find("bind it as K2:K2"), std::string::npos) << w;
  // Text output: the table, the statistics, the residuals per run, the correlation matrix.
  const Result text = run("identify obs.csv");
  ASSERT_EQ(text.code, 0) << text.err;
  for (const char* part : {"coefficient", "std error", "deg/s/g^3", "K1 (fixed)", "residual std [deg/s]",
                           "degrees of freedom", "chi2/dof", "condition number", "30g", "correlation"})
    EXPECT_NE(text.out.find(part), std::string::npos) << part << " in\n" << text.out;
}

TEST_F(Cli, SimulateIdentifiesExactlyAsIdentifyDoesItsFile) {
  // simulate identifies its observations from the numbers the file holds, without writing and reading the
  // file: every number of the fit (coefficients, standard errors, correlation, residuals, χ², condition) must
  // equal `ccal identify` of that file to the last bit, on the bundled example and on a configuration with
  // lever arms, known errors, drive and instrument noise, a fixed-platform run and the IA reversed. Only the
  // observability may differ: simulate knows the runs' noise, a file alone gives the fit's scatter.
  const std::string second = std::string(CCAL_SOURCE_DIR) + "/tests/data/golden/second.toml";
  for (const std::string& config : {std::string(), second}) {
    ASSERT_EQ(run("simulate " + config + " --observations-out obs.csv -o sim.json --format json").code, 0);
    const Result id = run("identify obs.csv --format json");
    ASSERT_EQ(id.code, 0) << id.err;
    const nlohmann::json file = nlohmann::json::parse(id.out);
    const nlohmann::json memory = nlohmann::json::parse(read(dir_ / "sim.json")).at("identification");
    for (const char* key : {"coefficients", "fixed", "known", "terms", "residual_std", "residuals", "dof",
                            "chi2_per_dof", "condition_number", "correlation", "weighted", "output_unit"})
      EXPECT_EQ(memory.at(key), file.at(key)) << config << ": " << key;
  }
}

TEST_F(Cli, JsonKeys) {
  const Result r = run("simulate --observations-out obs.csv --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json sim = nlohmann::json::parse(r.out);
  EXPECT_EQ(sim.at("command"), "simulate");
  EXPECT_EQ(sim.at("mode"), "exact");
  EXPECT_EQ(sim.at("output_unit"), "deg/s");
  EXPECT_FALSE(sim.at("noise").at("applied").get<bool>());
  ASSERT_EQ(sim.at("runs").size(), 6u);
  const auto& run20 = sim.at("runs")[3];
  EXPECT_EQ(run20.at("name"), "20g");
  EXPECT_DOUBLE_EQ(run20.at("g_level_g").get<double>(), 20.0);
  EXPECT_NEAR(run20.at("initial_phase_rad").get<double>(), 4.0720, 1e-4);  // model.md §6.1
  for (const char* key : {"rate_rad_per_s", "duration_s", "a_i_g", "rate_term", "output"})
    EXPECT_TRUE(run20.at(key).is_number()) << key;
  for (const char* id : {"K0", "K1", "K2", "K3"})
    EXPECT_TRUE(run20.at("regressors").at(id).is_number()) << id;

  const Result id = run("identify obs.csv --format json");
  ASSERT_EQ(id.code, 0) << id.err;
  for (const nlohmann::json& j : {nlohmann::json::parse(id.out), sim.at("identification")}) {
    for (const char* term : {"K0", "K2", "K3"}) {
      const auto& c = j.at("coefficients").at(term);
      EXPECT_TRUE(c.at("value").is_number());
      EXPECT_TRUE(c.at("std_error").is_number());
      EXPECT_TRUE(c.at("unit").is_string());
    }
    EXPECT_EQ(j["coefficients"]["K2"]["unit"], "deg/s/g^2");
    EXPECT_TRUE(j.at("residual_std").is_number());
    EXPECT_EQ(j.at("dof").get<int>(), 3);
    EXPECT_TRUE(j.at("chi2_per_dof").is_number());
    EXPECT_GE(j.at("condition_number").get<double>(), 1.0);
    const auto& corr = j.at("correlation");
    ASSERT_EQ(corr.size(), 3u);
    for (std::size_t a = 0; a < 3; ++a) {
      ASSERT_EQ(corr[a].size(), 3u);
      EXPECT_DOUBLE_EQ(corr[a][a].get<double>(), 1.0);
    }
    EXPECT_EQ(j.at("residuals").size(), 6u);
    EXPECT_TRUE(j.at("residuals").at("25g").is_number());
    EXPECT_TRUE(j.at("warnings").is_array());
    EXPECT_EQ(j.at("output_unit"), "deg/s");
  }
}

TEST_F(Cli, PolynomialFitOfAPlainTable) {
  // y = 1 + 2x + 3x² at x = −5 … 5: integers, exact in double, so the only error is the solver's round-off
  // (≈ 1e-15 relative with a condition number of ≈ 10 and refinement); 1e-12 leaves three digits of margin.
  std::string text = "x,y\n";
  for (int x = -5; x <= 5; ++x)
    text += std::to_string(x) + "," + std::to_string(1 + 2 * x + 3 * x * x) + "\n";
  write("p.csv", text);
  const Result r = run("identify p.csv --input-column x --output-column y --terms K0,K1,K2 --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(coefficient(j, "K0"), 1.0, 1e-12);
  EXPECT_NEAR(coefficient(j, "K1"), 2.0, 1e-12);
  EXPECT_NEAR(coefficient(j, "K2"), 3.0, 1e-12);
  EXPECT_EQ(j["coefficients"]["K2"]["unit"], "y/x^2");
  EXPECT_EQ(j.at("dof").get<int>(), 8);
  EXPECT_TRUE(j.at("output_unit").is_null());
  EXPECT_TRUE(j.at("residuals").contains("line 2"));  // no run column: rows are named by their line
  // Holding K1 at its value leaves K0, K2 unchanged.
  const Result f = run("identify p.csv --input-column x --output-column y --terms K0,K2 --fix K1=2 --format json");
  ASSERT_EQ(f.code, 0) << f.err;
  const nlohmann::json jf = nlohmann::json::parse(f.out);
  EXPECT_NEAR(coefficient(jf, "K0"), 1.0, 1e-12);
  EXPECT_NEAR(coefficient(jf, "K2"), 3.0, 1e-12);
}

TEST_F(Cli, Weights) {
  // K0 alone of y = 1, 2, 4 with σ = 1, 1, 0.5 (weights 1, 1, 4): the weighted mean 19/6 with standard error
  // √(1/Σw) = √(1/6) from the weights, and residual std √(χ²/dof). Round-off of a 3-term sum: 1e-14.
  write("w.csv", "run,y,s\na,1,1\nb,2,1\nc,4,0.5\n");
  const Result r = run("identify w.csv --output-column y --terms K0 --weight-column s --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(coefficient(j, "K0"), 19.0 / 6.0, 1e-14);
  EXPECT_NEAR(j["coefficients"]["K0"]["std_error"].get<double>(), std::sqrt(1.0 / 6.0), 1e-14);
  const double m = 19.0 / 6.0;
  const double chi2 = (1 - m) * (1 - m) + (2 - m) * (2 - m) + 4 * (4 - m) * (4 - m);
  EXPECT_NEAR(j.at("residual_std").get<double>(), std::sqrt(chi2 / 2), 1e-14);
  EXPECT_TRUE(j.at("weighted").get<bool>());
  EXPECT_NEAR(j.at("residuals").at("c").get<double>(), 4 - m, 1e-14);
  // Unweighted, the plain mean 7/3.
  const Result u = run("identify w.csv --output-column y --terms K0 --format json");
  ASSERT_EQ(u.code, 0) << u.err;
  EXPECT_NEAR(coefficient(nlohmann::json::parse(u.out), "K0"), 7.0 / 3.0, 1e-14);
  // A σ that is not positive, and a missing weight column, are located.
  write("w0.csv", "run,y,s\na,1,1\nb,2,0\nc,4,0.5\n");
  expect_located(run("identify w0.csv --output-column y --terms K0 --weight-column s"), "w0.csv:3:3",
                 {"s: ", "not positive"});
  expect_located(run("identify w.csv --output-column y --terms K0 --weight-column sigma"), "w.csv:1",
                 {"sigma: no such column", "the weights"});
}

TEST_F(Cli, BadCsvFilesAreLocated) {
  write("p.csv", "x,y\n0,1\n1,3\n2,7\n");
  const std::string fit = " --input-column x --output-column y --terms K0,K1";
  // Missing column: the header's line and the column's name.
  expect_located(run("identify p.csv --input-column z --output-column y --terms K0,K1"), "p.csv:1",
                 {"z: no such column", "accepted: one of the columns x, y"});
  expect_located(run("identify p.csv --input-column x --output-column out --terms K0,K1"), "p.csv:1",
                 {"out: no such column"});
  // Non-numeric, NaN, infinite and empty cells: line, 1-based field and the column name.
  write("a.csv", "x,y\n0,1\n1,abc\n2,7\n");
  expect_located(run("identify a.csv" + fit), "a.csv:3:2", {"y: 'abc' is not a number"});
  write("b.csv", "# a comment line\nx,y\n0,1\n1,3\nnan,7\n");
  expect_located(run("identify b.csv" + fit), "b.csv:5:1", {"x: 'nan' is not a finite number"});
  write("c.csv", "x,y\n0,1\n1,-inf\n");
  expect_located(run("identify c.csv" + fit), "c.csv:3:2", {"y: '-inf' is not a finite number"});
  write("d.csv", "x,y\n0,1\n1,\n2,7\n");
  expect_located(run("identify d.csv" + fit), "d.csv:3:2", {"y: empty cell"});
  // Ragged rows: too few and too many fields.
  write("e.csv", "x,y\n0,1\n1\n");
  expect_located(run("identify e.csv" + fit), "e.csv:3:2", {"y: ragged row: 1 field, the header has 2"});
  write("f.csv", "x,y\n0,1,5\n");
  expect_located(run("identify f.csv" + fit), "f.csv:2:3", {"ragged row: 3 fields, the header has 2"});
  // Fewer rows than free terms.
  write("g.csv", "x,y\n0,1\n");
  expect_located(run("identify g.csv" + fit), "g.csv:2",
                 {"1 data row cannot determine 2 free terms (K0, K1)"});
  // Empty file, comments only, a header of numbers, a duplicate column, an unterminated quote.
  write("h.csv", "");
  expect_located(run("identify h.csv" + fit), "h.csv:1", {"empty file"});
  write("i.csv", "# nothing\n\n");
  expect_located(run("identify i.csv" + fit), "i.csv:2", {"no header row"});
  write("j.csv", "0,1\n1,3\n");
  expect_located(run("identify j.csv" + fit), "j.csv:1:1", {"holds numbers, not column names", "x,y"});
  write("k.csv", "x,y,x\n0,1,2\n");
  expect_located(run("identify k.csv" + fit), "k.csv:1:3", {"x: duplicate column name (also column 1)"});
  write("l.csv", "run,x,y\n\"a,b\",0,1\n\"c,1,3\n");
  expect_located(run("identify l.csv" + fit), "l.csv:3:1", {"unterminated quote"});
  // A quoted run name with a comma is one field.
  write("m.csv", "run,x,y\n\"a,b\",0,1\nc,1,3\n");
  EXPECT_EQ(run("identify m.csv" + fit).code, 0);
  // A malformed observations header is located at its line.
  write("n.csv",
        "# ccal observations v1; terms=K0:K0,K99:K2; known=rate\nrun,output,rate,K0,K2\na,1,0,1,2\n");
  expect_located(run("identify n.csv"), "n.csv:1", {"'K99' is not a term id"});
  write("o.csv", "# ccal observations v2; terms=K0:K0\nrun,output,K0\na,1,1\n");
  expect_located(run("identify o.csv"), "o.csv:1", {"unsupported version 'v2'", "v1"});
  // A file that cannot be read.
  expect_located(run("identify missing.csv" + fit), "missing.csv", {"cannot read the file"});
}

TEST_F(Cli, BadIdentifyOptions) {
  write("p.csv", "x,y\n0,1\n1,3\n2,7\n");
  expect_bad_input(run("identify p.csv --input-column x --output-column y --terms K0,K99"),
                   {"--terms: 'K99' is not a term id", "K10", "K_pp"});
  expect_bad_input(run("identify p.csv --input-column x --output-column y --terms K0,K_pp"),
                   {"--terms: K_pp is not a power of the input", "K_pp:<column>"});
  expect_bad_input(run("identify p.csv --input-column x --output-column y --terms K0,K1,K0"),
                   {"--terms: K0 is listed twice"});
  expect_bad_input(run("identify p.csv --input-column x --output-column y --terms K0,K1 --fix K2"),
                   {"--fix: 'K2' has no value", "K1=505.2097"});
  expect_bad_input(run("identify p.csv --input-column x --output-column y --terms K0,K1 --fix K2=abc"),
                   {"--fix: 'abc' in 'K2=abc' is not a finite number"});
  expect_bad_input(run("identify p.csv --input-column x --output-column y --terms K0,K1 --fix K1=2"),
                   {"--fix: K1 is also a free term"});
  expect_bad_input(run("identify p.csv --input-column x --output-column y --terms K0 --fix 'K1=2 deg/s/g'"),
                   {"--fix", "needs the file's output_unit"});
  expect_bad_input(run("identify p.csv --input-column x --output-column y"),
                   {"p.csv: no '# ccal observations' line", "--terms"});
  expect_bad_input(run("identify p.csv --terms K0 --output-column y --format html"), {"--format", "html"});
}

TEST_F(Cli, AliasedTermsAreRefusedWithTheMountingHint) {
  // K0, K2, K3, K_pp on the paper's counter-rotating plan: ⟨a_p²⟩ = A² − ⟨a_i²⟩ + O(A²/ΩT), so K2 and K_pp
  // are correlated beyond 0.99999 (tests/reduction/observe_test.cpp). simulate refuses the configured terms ...
  write("pp.toml", example_with_terms("[\"K0\", \"K2\", \"K3\", \"K_pp\"]"));
  const Result s = run("simulate pp.toml -o out.txt --observations-out obs.csv");
  expect_bad_input(
      s, {"pp.toml: ", "cannot separate K2 and K_pp",
          "; runs with another mounting (ia_reversed, pa_vertical, ia_vertical) would separate them"});
  EXPECT_FALSE(fs::exists(dir_ / "out.txt"));
  EXPECT_FALSE(fs::exists(dir_ / "obs.csv"));
  // ... and so does identify, given a file with a K_pp column (K_pp held at 0 when simulating it).
  std::string cfg = example_with("K3 = \"0.003 deg/s/g^3\"", "K_pp = \"0 deg/s/g^2\"");
  const auto at = cfg.find("fixed = [\"K1\"]");
  ASSERT_NE(at, std::string::npos);
  cfg.replace(at, 14, "fixed = [\"K1\", \"K_pp\"]");
  write("fixed_pp.toml", cfg);
  const Result made = run("simulate fixed_pp.toml --observations-out pp.csv");
  ASSERT_EQ(made.code, 0) << made.err;
  const Result i = run("identify pp.csv --terms K0,K2:K2,K3:K3,K_pp:K_pp --fix K1:K1=505.2097 -o fit.txt");
  expect_bad_input(i, {"pp.csv: ", "cannot separate K2 and K_pp", "runs with another mounting"});
  EXPECT_FALSE(fs::exists(dir_ / "fit.txt"));
  // Powers of the input alone in a plain table get the table's hint: x takes two values, so K0, K1, K2 are
  // dependent, and more distinct values of x would separate them (a plain table has no g-levels to add).
  write("two.csv", "x,y\n1,1\n1,1\n2,3\n2,3\n");
  expect_bad_input(run("identify two.csv --input-column x --output-column y --terms K0,K1,K2"),
                   {"two.csv: ", "cannot separate", "; accepted: rows at more distinct values of the input column (x)"});
}

TEST_F(Cli, OutputFilesOnlyOnSuccess) {
  const Result ok = run("simulate -o sim.txt --observations-out obs.csv");
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_TRUE(ok.out.empty());
  EXPECT_NE(read(dir_ / "sim.txt").find("identification"), std::string::npos);
  EXPECT_TRUE(read(dir_ / "obs.csv").starts_with("# ccal observations v1;"));
  const Result id = run("identify obs.csv -o fit.json --format json");
  ASSERT_EQ(id.code, 0) << id.err;
  EXPECT_TRUE(id.out.empty());
  EXPECT_EQ(nlohmann::json::parse(read(dir_ / "fit.json")).at("dof"), 3);

  write("bad.csv", "x,y\n0,1\n1,abc\n");
  expect_bad_input(run("identify bad.csv --input-column x --output-column y --terms K0 -o failed.json"), {"bad.csv:3:2"});
  EXPECT_FALSE(fs::exists(dir_ / "failed.json"));
  // An unwritable --observations-out fails the command before anything is renamed into place.
  expect_bad_input(run("simulate -o failed.txt --observations-out /nonexistent-dir/obs.csv"),
                   {"--observations-out", "/nonexistent-dir/obs.csv"});
  EXPECT_FALSE(fs::exists(dir_ / "failed.txt"));
  expect_bad_input(run("simulate -o same.csv --observations-out same.csv"), {"--observations-out"});
  EXPECT_FALSE(fs::exists(dir_ / "same.csv"));
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST_F(Cli, SimulateNoiseIsSeeded) {
  // White noise of 0.01 °/s/√Hz gives run means with σ = 0.01/√450 ≈ 4.7e-4 °/s (the scale of model.md §8's
  // run means).
  std::string cfg = read(kExample);
  const std::string quiet = "noise_density = \"0 deg/s/rtHz\"";
  ASSERT_NE(cfg.find(quiet), std::string::npos);
  cfg.replace(cfg.find(quiet), quiet.size(), "noise_density = \"0.01 deg/s/rtHz\"");
  write("n.toml", cfg);
  const Result a = run("simulate n.toml --format json");
  const Result b = run("simulate n.toml --format json --seed 1");
  const Result c = run("simulate n.toml --format json --seed 2");
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_EQ(a.out, b.out);  // the default seed is 1
  const nlohmann::json ja = nlohmann::json::parse(a.out), jc = nlohmann::json::parse(c.out);
  EXPECT_TRUE(ja.at("noise").at("applied").get<bool>());
  EXPECT_NE(ja["runs"][0]["output"].get<double>(), jc["runs"][0]["output"].get<double>());
  // The noise is at the configured scale. The difference of two draws of a run mean has σ√2 ≈ 6.7e-4 °/s, so
  // 9.4e-3 °/s is 14 of those: never reached by correct noise, while a wrong unit (×57 for rad) or a missing
  // 1/√T (×21) would exceed it. K0 comes back within 10 of its σ (7.7e-5 °/s per 1e-4 °/s of run noise,
  // model.md §8, so σ(K0) ≈ 3.6e-4 °/s here).
  for (std::size_t k = 0; k < 6; ++k)
    EXPECT_LT(std::abs(ja["runs"][k]["output"].get<double>() - jc["runs"][k]["output"].get<double>()),
              2 * 4.7e-3);
  const auto& id = ja.at("identification");
  const double se = id["coefficients"]["K0"]["std_error"].get<double>();
  EXPECT_GT(se, 0.0);
  EXPECT_LT(std::abs(coefficient(id, "K0") - kK0), 10 * 3.6e-4);
}

TEST_F(Cli, PaperModeAndCompensation) {
  // Paper mode from the option and from [identification]: with no errors the paper's reduction is as exact as
  // the exact chain's (model.md V1, 1e-9 absolute in °/s/gⁿ; relative 1e-6 on K3 = 0.003 is that bound).
  const Result p = run("simulate --mode paper --format json");
  ASSERT_EQ(p.code, 0) << p.err;
  const nlohmann::json jp = nlohmann::json::parse(p.out);
  EXPECT_EQ(jp.at("mode"), "paper");
  EXPECT_NEAR(coefficient(jp["identification"], "K3"), kK3, 1e-9);
  std::string cfg = read(kExample);
  cfg.replace(cfg.find("mode = \"exact\""), 14, "mode = \"paper\"");
  write("paper.toml", cfg);
  const Result q = run("simulate paper.toml --format json");
  ASSERT_EQ(q.code, 0) << q.err;
  EXPECT_EQ(nlohmann::json::parse(q.out).at("mode"), "paper");

  // A main-axis levelling error of 1e-5 rad biases K3 by ≈ −1.45e-3 °/s/g³ (model.md §11,
  // tests/reduction/observe_test.cpp); compensating recomputes the regressors with it and the bias is
  // round-off: 1e-12 °/s/g³ in the library test, and the 17-digit CSV and the rad/s → °/s conversion add a
  // few ulp of the run means (≈ 1e-12 °/s, see SimulateThenIdentifyRecoversTheCoefficients), so 1e-10 keeps a
  // margin of 100 while being 1e-7 of the uncompensated bias.
  write("lev.toml", example_with("[errors]", "dthx1t = \"1e-5 rad\""));
  const Result raw = run("simulate lev.toml --format json");
  ASSERT_EQ(raw.code, 0) << raw.err;
  const nlohmann::json jr = nlohmann::json::parse(raw.out);
  EXPECT_NEAR(coefficient(jr["identification"], "K3") - kK3, -1.45e-3, 0.02e-3);  // 3 digits quoted
  EXPECT_EQ(jr.at("errors_nonzero"), 1);
  std::string comp = example_with("[errors]", "dthx1t = \"1e-5 rad\"");
  comp.replace(comp.find("compensate = false"), 18, "compensate = true");
  write("comp.toml", comp);
  const Result c = run("simulate comp.toml --format json");
  ASSERT_EQ(c.code, 0) << c.err;
  const nlohmann::json jc = nlohmann::json::parse(c.out);
  EXPECT_TRUE(jc.at("compensate").get<bool>());
  EXPECT_NEAR(coefficient(jc["identification"], "K3"), kK3, 1e-10);
  EXPECT_NEAR(coefficient(jc["identification"], "K0"), kK0, 1e-10);
}

}  // namespace
