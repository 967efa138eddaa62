#pragma once
// Internals of the spectral run-mean rule (quadrature.hpp, docs/model.md §8): the oscillatory moments J_p,
// the slow-time Lagrange basis and the DFT that turns them into node weights. Not part of ccal's API: they
// are here only because run_quadrature<S> is a template over the scalar type and instantiates them.

#include <Eigen/Core>
#include <cmath>
#include <numbers>
#include <type_traits>
#include <vector>

#include "ccal/core/value_of.hpp"

// GCC notes that passing a 64-byte vector changes the ABI in baseline code (-Wpsabi); S is such a vector only
// within one file's inlined clones (run_means_nodes.cpp), so the note is moot (core/cloned_loops.hpp). Silenced
// for this header's templates too, for a unity batch that instantiates them before including cloned_loops.hpp.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace ccal {

namespace detail {
inline constexpr int kMaxSlowNodes = 16;
// J_p for p = 0..P−1 by the forward recursion J_p = (e^{iκ} − (−1)^p e^{−iκ}) / (2iκ) − p J_{p−1} / (iκ),
// stable while p < |κ| (oscillatory_moments' branch for |κ| ≥ 4 + P). S may also be a SIMD vector of doubles
// (run_means_nodes.cpp: eight harmonics at once, each lane this function's operations).
// Zero of S: S(0.0), or every lane 0 for a SIMD vector (which no scalar converts to).
template <class S>
S zero_of() {
  if constexpr (std::is_constructible_v<S, double>)
    return S(0.0);
  else
    return S{};
}

template <class S>
void oscillatory_recursion(const S& kappa, const S& cos_kappa, const S& sin_kappa, int P, S* re, S* im) {
  for (int p = 0; p < P; ++p) {
    // (e^{iκ} − (−1)^p e^{−iκ}) / 2 is i·sin κ for even p and cos κ for odd p.
    S xr = p % 2 == 0 ? zero_of<S>() : cos_kappa;
    S xi = p % 2 == 0 ? sin_kappa : zero_of<S>();
    if (p > 0) {
      xr -= double(p) * re[p - 1];
      xi -= double(p) * im[p - 1];
    }
    // dividing by iκ maps (x + iy) to (y − ix)/κ
    re[p] = xi / kappa;
    im[p] = -xr / kappa;
  }
}
// J_p(κ) = ½ ∫₋₁¹ x^p e^{iκx} dx for p = 0..P−1 (real and imaginary parts, into re[0..P) and im[0..P)),
// given cos κ and sin κ: the Taylor series
// Σ_n (iκ)^n/n! · (1 + (−1)^{n+p}) / (2(n+p+1)) for |κ| < 4 + P, otherwise oscillatory_recursion.
template <class S>
void oscillatory_moments(const S& kappa, const S& cos_kappa, const S& sin_kappa, int P, S* re, S* im) {
  using std::abs;
  for (int p = 0; p < P; ++p) re[p] = im[p] = S(0);
  if (abs(kappa) < 4.0 + P) {
    // Terms until |κ|^n/n! < 1e-20 (at most 80: (4+P)^n/n! has fallen below that by then for P ≤ 24); only
    // the n = 0 term when κ = 0, where J_p = (1 + (−1)^p) / (2(p+1)).
    const double k_abs = std::abs(value_of(kappa));
    int terms = 1;
    for (double t = 1.0; terms < 80 && t >= 1e-20; ++terms) t *= k_abs / terms;
    for (int p = 0; p < P; ++p) {
      S term_re{1}, term_im{0};  // (iκ)^n / n!
      for (int n = 0; n < terms; ++n) {
        if ((n + p) % 2 == 0) {
          re[p] += term_re / double(n + p + 1);
          im[p] += term_im / double(n + p + 1);
        }
        const S next_re = -term_im * kappa / double(n + 1);
        term_im = term_re * kappa / double(n + 1);
        term_re = next_re;
      }
    }
    return;
  }
  oscillatory_recursion(kappa, cos_kappa, sin_kappa, P, re, im);
}
// Monomial coefficients a_qp of the Lagrange basis on the Q nodes slow_time_nodes(Q): L_q(x) = Σ_p a_qp x^p,
// for Q = 1 … kMaxSlowNodes, solved once for the process (a table of kMaxSlowNodes entries, built on first
// use, read-only after: safe from any thread).
const Eigen::MatrixXd& slow_lagrange_monomials(int Q);
// Chebyshev–Lobatto points on [−1, 1] (well-conditioned interpolation), or {0} for Q = 1.
std::vector<double> slow_time_nodes(int Q);
// The M equispaced fast phases θ_j = 2πj/M, with cos and sin of mθ_j = 2π (m j mod M)/M from one table.
struct FastPhaseTable {
  explicit FastPhaseTable(int fast_nodes);
  double phase(int j) const { return 2 * std::numbers::pi * j / M; }
  int M;
  std::vector<double> cos_k, sin_k;  // cos(2πk/M), sin(2πk/M), k = 0..M−1
};
// ν_q = e^{iκ/2} Σ_p a_qp J_p (q = 0..Q−1, into nu_re[q], nu_im[q]) from J_p(κ/2), cos κ/2 and sin κ/2 (c, s)
// and the Lagrange monomials a (Q × Q). S may also be a SIMD vector of doubles, as in oscillatory_recursion.
template <class S>
void slow_moments_of(const S& c, const S& s, const Eigen::MatrixXd& a, const S* mu_re, const S* mu_im,
                     S* nu_re, S* nu_im) {
  const int Q = int(a.rows());
  for (int q = 0; q < Q; ++q) {
    S sr{0}, si{0};
    for (int p = 0; p < Q; ++p) {
      sr += a(q, p) * mu_re[p];
      si += a(q, p) * mu_im[p];
    }
    nu_re[q] = c * sr - s * si;
    nu_im[q] = s * sr + c * si;
  }
}
// ν_mq = e^{iκ/2} Σ_p a_qp J_p(κ/2) (q = 0..Q−1, into nu_re[q], nu_im[q]) for one harmonic m, given κ/2 =
// mΩT/2 and its cosine and sine, and the Lagrange monomials a (Q × Q).
template <class S>
void harmonic_slow_moments(const S& half_kappa, const S& c, const S& s, const Eigen::MatrixXd& a, S* nu_re,
                           S* nu_im) {
  S mu_re[kMaxSlowNodes], mu_im[kMaxSlowNodes];
  oscillatory_moments<S>(half_kappa, c, s, int(a.rows()), mu_re, mu_im);
  slow_moments_of(c, s, a, mu_re, mu_im, nu_re, nu_im);
}
// The weights w[q·M + j] of the rule from ν (stored [m·Q + q], m = 0..M/2):
//     w_jq = (1/M) Σ_{m=−M/2+1}^{M/2} e^{−imθ_j} ν_mq,
// real because ν_{−m} = conj(ν_m); the Nyquist term is taken once (symmetric convention, M even).
// With it the rule is exact for cos(Mθ/2) as well as for every harmonic below M/2 (tests/reduction/quadrature_test.cpp
// checks each against its closed form; sin(Mθ/2) vanishes at every node). ccal sizes M so that its integrands
// are band-limited below M/2 (fast_nodes_for); for them the Nyquist term multiplies Σ_j (−1)^j Φ(θ_j), which
// vanishes up to their aliasing error, so it moves no ccal result beyond that error: only a direct test of
// the rule can see it.
template <class S>
void dft_weights(const FastPhaseTable& table, int Q, const S* nu_re, const S* nu_im, S* weights) {
  const int M = table.M, half = M / 2;
  for (int q = 0; q < Q; ++q)
    for (int j = 0; j < M; ++j) {
      S w = nu_re[q];
      for (int m = 1; m <= half; ++m) {
        const int k = (m * j) % M;
        const S term = table.cos_k[k] * nu_re[m * Q + q] + table.sin_k[k] * nu_im[m * Q + q];
        w += (m == half ? 1.0 : 2.0) * term;
      }
      weights[q * M + j] = w / double(M);
    }
}
}  // namespace detail

}  // namespace ccal

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
