#pragma once
// Partly correlated draws that keep every source's own distribution (JCGM 101 §6.4.8; docs/model.md §10.2): a
// Gaussian copula. Each draw slot s (a lone source, or a group whose members share one draw, montecarlo.hpp)
// takes a standard normal score y_s; the scores are jointly normal with correlation matrix R_z, y = L z with
// L Lᵀ = R_z (a pivoted Cholesky factor) and z independent standard normals (Φ⁻¹ of the
// trial's uniforms, one per slot); a source of distribution D and bound b in slot s is
//     x = b · G_D(y_s),   G_D(y) = F_D⁻¹(Φ(y)) (bound 1; G = identity for the normal),
// so that every source keeps its marginal exactly. Two sources whose slots have score correlation ρ have the
// Pearson correlation (Mehler's formula: the orthonormal Hermite polynomials h_k are the eigenfunctions of
// the bivariate normal with eigenvalues ρᵏ)
//     c_DE(ρ) = Σ_k a_k(D) a_k(E) ρᵏ,   a_k(D) = E[G_D(Z) h_k(Z)] / σ_D,   Σ_k a_k(D)² = 1,
// k odd (every G_D is odd). c is odd and increasing in ρ; c_NN(ρ) = ρ, c_NE(ρ) = a_1(E) ρ with a_1(uniform) =
// √(3/π) = 0.977, c_UU(ρ) = (6/π) arcsin(ρ/2). Each [[correlations]] pair's ρ solves c_DE(ρ) = r for the two
// sources it names, so each configured Pearson r holds. c_DE(±1) = ±E[G_D(Z) G_E(Z)]/(σ_D σ_E) is the largest
// correlation that any joint distribution with these two marginals has (the comonotone one,
// Fréchet–Hoeffding): a pair asking more is refused, except r = ±1, which is the comonotone draw of a group
// (one draw, Spearman ρ = ±1). R_z is checked as a whole: the scores that give a valid Pearson matrix need
// not have one.
//
// The series is summed to k = kCopulaHermiteTerms with the a_k computed once by composite Gauss–Legendre
// quadrature on [0, 14] (the integrand is below e^{-49} beyond), and the remainder is taken as t ρ^{K+2} with
// t from the exact c_DE(1) by the same quadrature, so c is exact at ±1 and the omitted terms' error is below
// |t| ρ^{K+2} (t = 1e-8 for two triangular sources, less for the others).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "ccal/setup/config.hpp"
#include "ccal/setup/tolerance.hpp"

namespace ccal {

// The highest Hermite degree kept in c_DE (odd degrees 1 … K).
inline constexpr int kCopulaHermiteTerms = 301;

// G_D(y) = F_D⁻¹(Φ(y)) for bound 1, exactly odd in y, from the tail probability Φ(−|y|) so that no digits are
// lost for large |y|.
double standard_value_of_score(Distribution d, double y);

// c_DE(ρ) for ρ in [−1, 1]: the Pearson correlation of G_D(y_1) and G_E(y_2) with corr(y_1, y_2) = ρ.
double copula_pearson(Distribution d, Distribution e, double rho);
// c_DE(1): the largest Pearson correlation of the two marginals (1 for two of one distribution).
double largest_pearson(Distribution d, Distribution e);
// The score correlation ρ with c_DE(ρ) = r; r = ±1 gives ±1 whatever the marginals. std::domain_error for
// 1 > |r| > largest_pearson(d, e) or an r outside [−1, 1].
double copula_score_correlation(Distribution d, Distribution e, double r);

struct GaussianCopula {
  std::vector<int>
      slot;  // per source: its draw slot (groups share one), as the independent sampling numbers them
  int slots = 0;
  Eigen::MatrixXd score_correlation;  // R_z, slots × slots
  // R_z's pivoted Cholesky factor: `factor` is lower triangular (slots × slots), and the scores y = L z are
  // y_s = (factor · z)[row_of_slot[s]], so that L = Pᵀ factor with L Lᵀ = R_z.
  Eigen::MatrixXd factor;
  std::vector<int> row_of_slot;
  double smallest_eigenvalue = 1;  // of R_z
};

// The copula of the sources and the configuration's pairs (ids of sources; a pair naming a grouped source
// applies to its whole group). Throws InputError beginning with "[[correlations]]" for a pair beyond the
// largest correlation of its marginals or an R_z that is not positive semi-definite (below
// kCorrelationEigenvalueFloor), saying what would be accepted; std::invalid_argument for an id that names no
// source.
GaussianCopula gaussian_copula(const std::vector<Tolerance>& sources,
                               const std::vector<Correlation>& correlations);

// The same for a configuration's Monte Carlo sources, the message located at config.source.
GaussianCopula gaussian_copula(const Config& config);

}  // namespace ccal
