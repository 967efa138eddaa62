#include "ccal/reduction/quadrature.hpp"

#include <Eigen/Dense>
#include <boost/math/quadrature/gauss.hpp>
#include <stdexcept>
#include <string>

namespace ccal {

int fast_nodes_for(int polynomial_degree, int input_harmonics) {
  const int band = (std::max(polynomial_degree, 1) + 2) * std::max(input_harmonics, 1);
  const int M = 2 * band + 2;
  return std::max(12, (M + 3) / 4 * 4);
}

int slow_nodes_for(double drift, double tolerance) {
  // Smallest Q with drift^Q / Q! below the tolerance (the interpolation error relative to the swing
  // of the integrand), at most 10: beyond that the monomial Lagrange coefficients lose more to round-off; at
  // least 2, so that the first derivative with respect to ΔΩ stays exact at ΔΩ = 0.
  int Q = 2;
  double bound = drift * drift / 2;
  while (bound > tolerance && Q < 10) {
    ++Q;
    bound *= drift / Q;
  }
  return Q;
}

namespace detail {

FastPhaseTable::FastPhaseTable(int fast_nodes) : M(fast_nodes), cos_k(std::size_t(M)), sin_k(std::size_t(M)) {
  for (int k = 0; k < M; ++k) {
    cos_k[std::size_t(k)] = std::cos(2 * std::numbers::pi * k / M);
    sin_k[std::size_t(k)] = std::sin(2 * std::numbers::pi * k / M);
  }
}

Eigen::MatrixXd solve_lagrange(const std::vector<double>& nodes, int Q);

std::vector<double> slow_time_nodes(int Q) {
  if (Q == 1) return {0.0};
  std::vector<double> x(Q);
  for (int q = 0; q < Q; ++q) x[q] = -std::cos(std::numbers::pi * q / (Q - 1));
  return x;
}

const Eigen::MatrixXd& slow_lagrange_monomials(int Q) {
  if (Q < 1 || Q > kMaxSlowNodes)
    throw std::invalid_argument("slow_lagrange_monomials: Q must be 1 … " + std::to_string(kMaxSlowNodes));
  // The rule only ever asks for Chebyshev–Lobatto nodes of a given count: each basis solved once.
  static const std::vector<Eigen::MatrixXd> table = [] {
    std::vector<Eigen::MatrixXd> t(std::size_t(kMaxSlowNodes) + 1);
    for (int q = 1; q <= kMaxSlowNodes; ++q) t[std::size_t(q)] = solve_lagrange(slow_time_nodes(q), q);
    return t;
  }();
  return table[std::size_t(Q)];
}

Eigen::MatrixXd solve_lagrange(const std::vector<double>& nodes, int Q) {
  Eigen::MatrixXd V(Q, Q);  // V(q, p) = x_q^p
  for (int q = 0; q < Q; ++q)
    for (int p = 0; p < Q; ++p) V(q, p) = std::pow(nodes[q], p);
  // Row q of the result holds the coefficients of L_q: Σ_p a_qp x_r^p = δ_qr  ⇔  a V^T = I.
  return V.transpose().fullPivLu().solve(Eigen::MatrixXd::Identity(Q, Q));
}

}  // namespace detail

RunQuadrature<double> trapezoid_gauss_quadrature(const RunMotion<double>& motion, double duration,
                                                 int nodes_per_revolution, int gauss_nodes) {
  const double w = motion.theta1_rate;
  const double period = 2 * std::numbers::pi / std::abs(w);
  const double revolutions = std::floor(duration / period);
  const double full = revolutions * period, partial = duration - full;
  RunQuadrature<double> out;
  auto add = [&](double t, double weight) {
    out.nodes.push_back(motion.at(t));
    out.weights.push_back(weight / duration);
  };
  if (revolutions > 0)
    for (int j = 0; j < nodes_per_revolution; ++j)
      add(j * period / nodes_per_revolution, full / nodes_per_revolution);
  if (partial > 0) {
    // Gauss–Legendre on [full, T]: Boost gives the abscissae x_k ≥ 0 and weights of the symmetric rule.
    auto rule = [&](auto tag) {
      using Rule = decltype(tag);
      const auto& x = Rule::abscissa();
      const auto& wt = Rule::weights();
      const double mid = full + partial / 2, half = partial / 2;
      for (std::size_t k = 0; k < x.size(); ++k) {
        if (x[k] == 0.0) {
          add(mid, half * wt[k]);
        } else {
          add(mid + half * x[k], half * wt[k]);
          add(mid - half * x[k], half * wt[k]);
        }
      }
    };
    switch (gauss_nodes) {
      case 10:
        rule(boost::math::quadrature::gauss<double, 10>{});
        break;
      case 20:
        rule(boost::math::quadrature::gauss<double, 20>{});
        break;
      case 30:
        rule(boost::math::quadrature::gauss<double, 30>{});
        break;
      case 40:
        rule(boost::math::quadrature::gauss<double, 40>{});
        break;
      default:
        throw std::invalid_argument("gauss_nodes must be 10, 20, 30 or 40");
    }
  }
  return out;
}

}  // namespace ccal
