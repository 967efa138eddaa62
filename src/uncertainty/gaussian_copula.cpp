#include "ccal/uncertainty/gaussian_copula.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <tuple>

#include "ccal/core/errors.hpp"
#include "ccal/setup/input_correlation.hpp"
#include "ccal/uncertainty/montecarlo.hpp"
#include "draw_quantiles.hpp"

namespace ccal {

namespace {

constexpr int kDistributions = 4;

// The Hermite coefficients a_1, a_3, … a_K of one distribution's G_D / σ_D (index (k − 1)/2), and the samples
// of G_D at the quadrature's nodes, from which c_DE(1) is computed by the same rule.
struct HermiteExpansion {
  std::vector<double> odd;    // a_k, k = 1, 3, …, K
  std::vector<double> value;  // G_D(z_i)/σ_D at the nodes
};

// Composite Gauss–Legendre on [0, kUpper]: panels narrower than the shortest half-wave of h_K near 0
// (π/√K ≈ 0.18), 30 nodes each; the integrands are even (G_D and h_k are odd), so ∫_ℝ = 2 ∫_0^∞.
constexpr double kUpper = 14.0;
constexpr int kPanels = 112;
using Rule = boost::math::quadrature::gauss<double, 30>;

struct Nodes {
  std::vector<double> z, weight;  // weight includes 2φ(z)
};

const Nodes& nodes() {
  static const Nodes n = [] {
    Nodes out;
    const auto& x = Rule::abscissa();
    const auto& w = Rule::weights();
    const double half = 0.5 * kUpper / kPanels;
    for (int p = 0; p < kPanels; ++p) {
      const double centre = (2 * p + 1) * half;
      for (std::size_t i = 0; i < x.size(); ++i)
        for (const double sign : {-1.0, 1.0}) {
          const double z = centre + sign * half * x[i];
          out.z.push_back(z);
          out.weight.push_back(2 * half * w[i] * std::exp(-0.5 * z * z) / std::sqrt(2 * std::numbers::pi));
        }
    }
    return out;
  }();
  return n;
}

HermiteExpansion expand(Distribution d) {
  const Nodes& n = nodes();
  const double sigma = 1.0 / divisor(d);
  HermiteExpansion e;
  e.odd.assign((kCopulaHermiteTerms + 1) / 2, 0.0);
  for (std::size_t i = 0; i < n.z.size(); ++i) {
    const double z = n.z[i];
    const double g = standard_value_of_score(d, z) / sigma;
    e.value.push_back(g);
    // h_0 = 1, h_1 = z, h_{k+1} = (z h_k − √k h_{k−1}) / √(k + 1): orthonormal under φ, stable upward.
    double previous = 1, current = z;
    for (int k = 1; k <= kCopulaHermiteTerms; ++k) {
      if (k % 2 == 1) e.odd[std::size_t(k / 2)] += n.weight[i] * g * current;
      const double next = (z * current - std::sqrt(double(k)) * previous) / std::sqrt(double(k + 1));
      previous = current;
      current = next;
    }
  }
  return e;
}

const HermiteExpansion& expansion(Distribution d) {
  static const std::array<HermiteExpansion, kDistributions> all = [] {
    std::array<HermiteExpansion, kDistributions> out;
    for (int d = 0; d < kDistributions; ++d) out[std::size_t(d)] = expand(Distribution(d));
    return out;
  }();
  return all[std::size_t(d)];
}

// The series' coefficients a_k(D) a_k(E) and its remainder t = c_DE(1) − Σ a_k(D) a_k(E).
struct PearsonSeries {
  std::vector<double> coefficient;
  double remainder = 0;
  double at_one = 1;
};

PearsonSeries make_series(Distribution d, Distribution e) {
  const HermiteExpansion &a = expansion(d), &b = expansion(e);
  PearsonSeries s;
  double sum = 0;
  for (std::size_t k = 0; k < a.odd.size(); ++k) {
    s.coefficient.push_back(a.odd[k] * b.odd[k]);
    sum += s.coefficient.back();
  }
  if (d == Distribution::normal || e == Distribution::normal) {
    s.at_one = d == e ? 1.0 : (d == Distribution::normal ? b : a).odd[0];  // c_NE(1) = a_1(E): no remainder
    s.remainder = d == e ? 1.0 - sum : 0.0;
    return s;
  }
  const Nodes& n = nodes();
  double at_one = 0;
  for (std::size_t i = 0; i < n.z.size(); ++i) at_one += n.weight[i] * a.value[i] * b.value[i];
  s.at_one = d == e ? 1.0 : at_one;  // E[G_D²]/σ_D² = 1 exactly
  s.remainder = s.at_one - sum;
  return s;
}

// The series of every pair of distributions, made once.
const PearsonSeries& series(Distribution d, Distribution e) {
  static const std::array<PearsonSeries, kDistributions* kDistributions> all = [] {
    std::array<PearsonSeries, kDistributions * kDistributions> out;
    for (int a = 0; a < kDistributions; ++a)
      for (int b = 0; b < kDistributions; ++b)
        out[std::size_t(a * kDistributions + b)] = make_series(Distribution(a), Distribution(b));
    return out;
  }();
  return all[std::size_t(int(d) * kDistributions + int(e))];
}

// dc/dρ = Σ_j (2j + 1) c_j ρ^{2j} + (K + 2) t ρ^{K+1}, for Newton's method on c(ρ) = r.
double slope(const PearsonSeries& s, double rho) {
  const double rho2 = rho * rho;
  double sum = 0;
  for (std::size_t j = s.coefficient.size(); j-- > 0;)
    sum = sum * rho2 + double(2 * j + 1) * s.coefficient[j];
  return sum + (kCopulaHermiteTerms + 2) * s.remainder * std::pow(rho, kCopulaHermiteTerms + 1);
}

double evaluate(const PearsonSeries& s, double rho) {
  if (std::abs(rho) == 1) return rho * s.at_one;  // exact at the ends (1 for one distribution with itself)
  // Horner in ρ² over the odd powers: Σ_j c_j ρ^{2j+1}, then the remainder t ρ^{K+2}.
  const double rho2 = rho * rho;
  double sum = 0;
  for (std::size_t j = s.coefficient.size(); j-- > 0;) sum = sum * rho2 + s.coefficient[j];
  return rho * sum + s.remainder * std::pow(rho, kCopulaHermiteTerms + 2);
}

// "a normal 'dthy4'", "an arcsine 'ripple1_c1'".
std::string input_text(const Tolerance& t) {
  return fmt::format("{} {} '{}'", t.distribution == Distribution::arcsine ? "an" : "a",
                     distribution_name(t.distribution), t.id);
}

std::string pair_text(const Tolerance& a, const Tolerance& b, double r) {
  return fmt::format("between = [\"{}\", \"{}\"], r = {}", a.id, b.id, r);
}

std::size_t source_index(const std::vector<Tolerance>& sources, const std::string& id) {
  for (std::size_t s = 0; s < sources.size(); ++s)
    if (sources[s].id == id) return s;
  throw std::invalid_argument("correlation of '" + id + "', which names no source");
}

}  // namespace

double standard_value_of_score(Distribution d, double y) {
  switch (d) {
    case Distribution::normal:
      return y;
    case Distribution::uniform:
      return std::erf(y * std::numbers::sqrt2 / 2);  // 2Φ(y) − 1
    case Distribution::triangular: {
      const double tail = 0.5 * std::erfc(std::abs(y) * std::numbers::sqrt2 / 2);  // Φ(−|y|)
      return std::copysign(1.0 - std::sqrt(2.0 * tail), y);
    }
    case Distribution::arcsine:
      // sin(π(Φ − ½)) by the series of draw_quantiles.hpp, not the C library's sin, whose code differs on a
      // processor with fused multiply-add
      return draws::sin_pi(0.5 * std::erf(y * std::numbers::sqrt2 / 2));
  }
  return 0.0;
}

double copula_pearson(Distribution d, Distribution e, double rho) {
  if (!(rho >= -1 && rho <= 1))
    throw std::domain_error(fmt::format("score correlation {} outside [−1, 1]", rho));
  if (d == Distribution::normal && e == Distribution::normal) return rho;
  if (d == Distribution::uniform && e == Distribution::uniform)
    return 6 / std::numbers::pi * std::asin(rho / 2);  // Pearson's 1907 form for a normal pair's ranks
  return evaluate(series(d, e), rho);
}

double largest_pearson(Distribution d, Distribution e) { return copula_pearson(d, e, 1.0); }

double copula_score_correlation(Distribution d, Distribution e, double r) {
  if (!(r >= -1 && r <= 1)) throw std::domain_error(fmt::format("correlation {} outside [−1, 1]", r));
  if (std::abs(r) == 1) return r;  // the comonotone (or counter-monotone) draw, as a group's
  if (d == Distribution::normal && e == Distribution::normal) return r;
  if (d == Distribution::uniform && e == Distribution::uniform) return 2 * std::sin(std::numbers::pi * r / 6);
  const double largest = largest_pearson(d, e);
  if (std::abs(r) > largest)
    throw std::domain_error(fmt::format("correlation {} beyond the largest, {:.6g}, of a {} and a {} input",
                                        r, largest, distribution_name(d), distribution_name(e)));
  const PearsonSeries& s = series(d, e);
  // c is increasing and nearly linear: Newton's method from ρ = r inside a bracket that every evaluation
  // narrows, bisecting where a step would leave it; to the last bit (a step below 1e-16, or a bracket that
  // cannot be halved).
  double low = -1, high = 1, rho = r;
  for (int iteration = 0; iteration < 100; ++iteration) {
    const double value = evaluate(s, rho) - r;
    if (value == 0) return rho;
    (value < 0 ? low : high) = rho;
    double next = rho - value / slope(s, rho);
    if (!(next > low && next < high)) next = 0.5 * (low + high);
    if (std::abs(next - rho) <= 1e-16 || next <= low || next >= high) return next;
    rho = next;
  }
  return rho;
}

GaussianCopula gaussian_copula(const std::vector<Tolerance>& sources,
                               const std::vector<Correlation>& correlations) {
  const CorrelationGroups groups = correlation_groups(sources);
  GaussianCopula c;
  c.slot = groups.of;
  c.slots = groups.count;
  const auto m = Eigen::Index(c.slots);
  c.score_correlation = Eigen::MatrixXd::Identity(m, m);
  std::map<std::tuple<Distribution, Distribution, double>, double> solved;  // a dense R repeats its r
  for (const Correlation& pair : correlations) {
    const std::size_t a = source_index(sources, pair.first), b = source_index(sources, pair.second);
    const Tolerance &ta = sources[a], &tb = sources[b];
    double rho = 0;
    try {
      const auto key = std::make_tuple(ta.distribution, tb.distribution, pair.r);
      const auto known = solved.find(key);
      rho = known != solved.end()
                ? known->second
                : (solved[key] = copula_score_correlation(ta.distribution, tb.distribution, pair.r));
    } catch (const std::domain_error&) {
      const double largest = largest_pearson(ta.distribution, tb.distribution);
      throw InputError(fmt::format(
          "[[correlations]] {}: no joint distribution of {} and {} has a correlation beyond ±{:.4f} (the "
          "Monte Carlo keeps each input's distribution); accepted: |r| ≤ {:.4f}, or r = {} (fully "
          "correlated: "
          "one draw, as a group)",
          pair_text(ta, tb, pair.r), input_text(ta), input_text(tb), largest, std::floor(largest * 1e4) / 1e4,
          pair.r > 0 ? 1 : -1));
    }
    const auto sa = Eigen::Index(c.slot[a]), sb = Eigen::Index(c.slot[b]);
    c.score_correlation(sa, sb) = c.score_correlation(sb, sa) = rho;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(c.score_correlation);
  const Eigen::VectorXd& lambda = eigen.eigenvalues();  // ascending
  c.smallest_eigenvalue = m > 0 ? lambda[0] : 1.0;
  if (c.smallest_eigenvalue < kCorrelationEigenvalueFloor) {
    std::string along;
    const Eigen::VectorXd weakest = eigen.eigenvectors().col(0);
    for (std::size_t s = 0; s < sources.size(); ++s) {
      const double w = std::abs(weakest[Eigen::Index(c.slot[s])]);
      if (w >= 0.25 * weakest.cwiseAbs().maxCoeff()) along += (along.empty() ? "" : ", ") + sources[s].id;
    }
    throw InputError(fmt::format(
        "[[correlations]]: the normal scores that give these correlations with the inputs' distributions "
        "have "
        "a matrix with a negative eigenvalue, {:.3g}, along {}: the Monte Carlo cannot draw them although "
        "the "
        "budget can; accepted: weaker correlations among these sources, or normal distributions for them",
        c.smallest_eigenvalue, along));
  }
  // P R_z Pᵀ = L D Lᵀ (pivoted, so a semi-definite R_z of r = ±1 pairs factors too; D's round-off below 0
  // set to 0): the factor L √D is lower triangular, half the work per draw of a dense one.
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(c.score_correlation);
  c.factor = Eigen::MatrixXd(ldlt.matrixL()) * ldlt.vectorD().cwiseMax(0.0).cwiseSqrt().asDiagonal();
  const Eigen::VectorXd index = Eigen::VectorXd::LinSpaced(m, 0.0, double(m - 1));
  const Eigen::VectorXd row_of_slot = ldlt.transpositionsP().transpose() * index;  // y = Pᵀ (L √D z)
  c.row_of_slot.resize(std::size_t(m));
  for (Eigen::Index i = 0; i < m; ++i) c.row_of_slot[std::size_t(i)] = int(std::lround(row_of_slot[i]));
  return c;
}

GaussianCopula gaussian_copula(const Config& config) {
  try {
    return gaussian_copula(monte_carlo_sources(config), config.correlations);
  } catch (const InputError& e) {
    throw InputError(config.source + ": " + e.what());
  }
}

}  // namespace ccal
