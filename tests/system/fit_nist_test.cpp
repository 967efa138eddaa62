// The least-squares fit against NIST's Statistical Reference Datasets (certified values to 15 digits).
#include "fit_test_support.hpp"
#include "test_paths.hpp"

namespace {

using namespace ccal::fit_test;

// ---------------------------------------------------------------------------------------------------
// 3. NIST StRD certified linear regressions.

struct NistData {
  std::string name;
  VectorXd y;
  MatrixXd x;  // predictors, one column each
  VectorXd estimate, std_dev;
  double residual_sd = 0;
};

// Reads a NIST StRD linear-regression file, taking the line ranges of the certified values and of
// the data from the file's own header.
NistData read_nist(const std::string& name) {
  const std::string path = std::string(CCAL_SOURCE_DIR) + "/tests/data/nist/" + name + ".dat";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const std::regex range_re(R"(\(lines\s+(\d+)\s+to\s+(\d+)\))");
  std::smatch m;
  int cert_first = 0, cert_last = 0, data_first = 0, data_last = 0;
  for (const auto& line : lines) {
    if (line.find("Certified Values") != std::string::npos && std::regex_search(line, m, range_re)) {
      cert_first = std::stoi(m[1]);
      cert_last = std::stoi(m[2]);
    }
    if (line.find("Data ") != std::string::npos && std::regex_search(line, m, range_re)) {
      data_first = std::stoi(m[1]);
      data_last = std::stoi(m[2]);
    }
  }
  if (cert_first == 0 || data_first == 0) throw std::runtime_error("no line ranges in " + path);
  NistData d;
  d.name = name;
  std::vector<double> est, sd;
  for (int n = cert_first; n <= cert_last; ++n) {
    std::istringstream s(lines[static_cast<std::size_t>(n - 1)]);
    std::string first;
    s >> first;
    if (first.size() >= 2 && first[0] == 'B' && std::isdigit(static_cast<unsigned char>(first[1]))) {
      double e = 0, v = 0;
      s >> e >> v;
      est.push_back(e);
      sd.push_back(v);
    } else if (first == "Standard") {
      std::string deviation;
      s >> deviation >> d.residual_sd;
    }
  }
  std::vector<std::vector<double>> rows;
  for (int n = data_first; n <= data_last; ++n) {
    std::istringstream s(lines[static_cast<std::size_t>(n - 1)]);
    std::vector<double> row;
    for (double v; s >> v;) row.push_back(v);
    rows.push_back(row);
  }
  const auto nrows = static_cast<Eigen::Index>(rows.size());
  const auto ncols = static_cast<Eigen::Index>(rows.front().size());
  d.y.resize(nrows);
  d.x.resize(nrows, ncols - 1);
  for (Eigen::Index i = 0; i < nrows; ++i) {
    d.y(i) = rows[static_cast<std::size_t>(i)][0];
    for (Eigen::Index k = 1; k < ncols; ++k)
      d.x(i, k - 1) = rows[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)];
  }
  d.estimate = Eigen::Map<VectorXd>(est.data(), static_cast<Eigen::Index>(est.size()));
  d.std_dev = Eigen::Map<VectorXd>(sd.data(), static_cast<Eigen::Index>(sd.size()));
  return d;
}

// Log relative error (number of correct significant digits), as NIST defines it: -log10(|e - c| / |c|),
// or -log10(|e|) when the certified value c is 0. Capped at 15 (an exact match).
double lre(double estimate, double certified) {
  const double err =
      certified == 0 ? std::abs(estimate) : std::abs(estimate - certified) / std::abs(certified);
  return err == 0 ? 15.0 : std::min(15.0, -std::log10(err));
}

struct NistCase {
  std::string name;
  bool polynomial;      // design x^0..x^p; otherwise intercept + the predictors
  double required_lre;  // minimum digits for every coefficient and standard error
};

void PrintTo(const NistCase& c, std::ostream* os) { *os << c.name; }

class NistStrd : public ::testing::TestWithParam<NistCase> {};

TEST_P(NistStrd, MatchesCertifiedValues) {
  const NistCase& c = GetParam();
  const NistData d = read_nist(c.name);
  const auto params = d.estimate.size();
  MatrixXd h;
  std::vector<std::string> names;
  if (c.polynomial) {
    ASSERT_EQ(d.x.cols(), 1);
    h = ccal::polynomial_design(d.x.col(0), static_cast<int>(params - 1));
    names = ccal::polynomial_term_names(static_cast<int>(params - 1));
  } else {
    h.resize(d.y.size(), params);
    h.col(0).setOnes();
    h.rightCols(params - 1) = d.x;
    names = names_of(static_cast<int>(params));
  }
  FitProblem p{names, h, d.y, {}, {}, {}};
  FitOptions o;
  for (const auto method : {FitMethod::qr, FitMethod::svd}) {
    // Without refinement the plain factorisation is shown for comparison; the assertions are on the
    // default (one step of refinement).
    for (const int refinement : {0, 1}) {
      o.method = method;
      o.refinement_steps = refinement;
      const FitResult r = ccal::fit(p, o);
      double min_value = 15, min_error = 15;
      for (Eigen::Index k = 0; k < params; ++k) {
        min_value = std::min(min_value, lre(r.value(k), d.estimate(k)));
        min_error = std::min(min_error, lre(r.std_error(k), d.std_dev(k)));
      }
      const double rsd = lre(r.residual_std, d.residual_sd);
      const std::string tag =
          fmt::format("{}{}", method == FitMethod::qr ? "qr" : "svd", refinement ? "+refined" : " plain");
      std::cout << fmt::format(
          "[ LRE      ] {:>9} {:<11} coefficients {:4.1f}  std errors {:4.1f}  residual SD "
          "{:4.1f}  (condition {:.2e})\n",
          c.name, tag, min_value, min_error, rsd, r.condition_number);
      if (refinement == 0) continue;
      if (method == FitMethod::qr) {
        RecordProperty("min_lre_coefficients", fmt::format("{:.1f}", min_value));
        RecordProperty("min_lre_std_errors", fmt::format("{:.1f}", min_error));
      }
      // At least 9 correct digits (7 for Filip: its scaled design has condition ~5e9, and merely storing
      // the design in double, each entry correctly rounded, moves the exact solution by ~2e-8 relative,
      // so no double-precision H can carry more than ~7.6 of the certified digits).
      EXPECT_GE(min_value, c.required_lre) << c.name;
      EXPECT_GE(rsd, c.required_lre) << c.name;
      // Standard errors from R^-1 R^-T (QR) keep ~1 digit more on Filip than V S^-2 V^T (SVD), which
      // squares the condition number in its small entries: 8.4 against 7.1 digits. The SVD path is held
      // to one digit less so that this known, harmless difference does not make the test fragile.
      EXPECT_GE(min_error, method == FitMethod::qr ? c.required_lre : c.required_lre - 1) << c.name;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Certified, NistStrd,
                         ::testing::Values(NistCase{"Wampler1", true, 9}, NistCase{"Wampler2", true, 9},
                                           NistCase{"Wampler3", true, 9}, NistCase{"Wampler4", true, 9},
                                           NistCase{"Wampler5", true, 9}, NistCase{"Pontius", true, 9},
                                           NistCase{"Longley", false, 9}, NistCase{"Filip", true, 7}),
                         [](const auto& info) { return info.param.name; });

}  // namespace
