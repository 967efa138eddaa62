#include "ccal/reduction/fit.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "text_lists.hpp"

namespace ccal {
namespace {

using Index = Eigen::Index;

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A sum accumulated in twice the working precision (Ogita, Rump & Oishi, "Accurate sum and dot
// product", SIAM J. Sci. Comput. 26, 2005): TwoSum and the fma-based TwoProduct are error-free
// transformations, so the result is as accurate as if computed in double-double and then rounded, on
// every platform (no reliance on an extended long double).
class CompensatedSum {
 public:
  CompensatedSum() = default;
  explicit CompensatedSum(double v) : hi_(v) {}
  void add(double v) {
    const double s = hi_ + v;
    const double v_part = s - hi_;
    lo_ += (hi_ - (s - v_part)) + (v - v_part);
    hi_ = s;
  }
  void add_product(double a, double b) {
    const double product = a * b;
    add(product);
    lo_ += std::fma(a, b, -product);
  }
  double value() const { return hi_ + lo_; }
  // The sum as an unevaluated pair: value() and the part of the sum that value() rounded away.
  std::pair<double, double> split() const {
    const double s = hi_ + lo_;
    return {s, lo_ - (s - hi_)};
  }

 private:
  double hi_ = 0;
  double lo_ = 0;
};

std::string row_text(const FitProblem& p, Index row) {
  std::string text = fmt::format("row {}", row + 1);
  if (!p.row_labels.empty()) text += fmt::format(" ({})", p.row_labels[static_cast<std::size_t>(row)]);
  return text;
}

// The term names: none empty, none twice, each fixed term one of them with a finite value.
void validate_terms(const FitProblem& p) {
  std::set<std::string> seen;
  for (const auto& name : p.term_names) {
    if (name.empty()) throw std::invalid_argument("fit: a term name is empty; accepted: a name for each column");
    if (!seen.insert(name).second) {
      throw std::invalid_argument(
          fmt::format("fit: duplicate term name \"{}\"; accepted: a name of its own for each column", name));
    }
  }
  for (const auto& [name, value] : p.fixed) {
    if (seen.count(name) == 0) {
      throw std::invalid_argument(
          fmt::format("fit: fixed term \"{}\" is not a term of the model; valid names: {}", name,
                      fmt::join(p.term_names, ", ")));
    }
    if (!std::isfinite(value)) {
      throw std::invalid_argument(
          fmt::format("fit: fixed term \"{}\" has the non-finite value {}; accepted: a finite number", name, value));
    }
  }
}

// Every value of y, H and the weights finite (the weights positive too), named by its row.
void validate_values(const FitProblem& p) {
  const Index rows = p.H.rows();
  const Index cols = p.H.cols();
  for (Index i = 0; i < rows; ++i) {
    if (!std::isfinite(p.y(i))) {
      throw std::invalid_argument(fmt::format("fit: non-finite value {} in y at {}; accepted: finite numbers",
                                              p.y(i), row_text(p, i)));
    }
    for (Index k = 0; k < cols; ++k) {
      if (!std::isfinite(p.H(i, k))) {
        throw std::invalid_argument(fmt::format("fit: non-finite value {} in H at {}, column {} ({}); accepted: "
                                                "finite numbers",
                                                p.H(i, k), row_text(p, i), k + 1,
                                                p.term_names[static_cast<std::size_t>(k)]));
      }
    }
    if (p.weights.size() != 0 && !(std::isfinite(p.weights(i)) && p.weights(i) > 0)) {
      throw std::invalid_argument(
          fmt::format("fit: weight {} at {} is not positive and finite; accepted: weights 1/σ² > 0 (leave a row out "
                      "rather than weigh it 0)",
                      p.weights(i), row_text(p, i)));
    }
  }
}

void validate(const FitProblem& p, const FitOptions& o) {
  const Index rows = p.H.rows();
  const Index cols = p.H.cols();
  if (static_cast<Index>(p.term_names.size()) != cols) {
    throw std::invalid_argument(
        fmt::format("fit: {} term names for a design with {} columns; accepted: one name per column of the design",
                    p.term_names.size(), cols));
  }
  if (p.y.size() != rows) {
    throw std::invalid_argument(
        fmt::format("fit: the design has {} rows but y has {} entries; accepted: one y per row of the design",
                    rows, p.y.size()));
  }
  if (p.weights.size() != 0 && p.weights.size() != rows) {
    throw std::invalid_argument(fmt::format(
        "fit: {} weights for {} rows (leave weights empty for unit weights)", p.weights.size(), rows));
  }
  if (!p.row_labels.empty() && static_cast<Index>(p.row_labels.size()) != rows) {
    throw std::invalid_argument(fmt::format("fit: {} row labels for {} rows", p.row_labels.size(), rows));
  }
  validate_terms(p);
  validate_values(p);
  if (!(std::isfinite(o.rank_tolerance) && o.rank_tolerance >= 0)) {
    throw std::invalid_argument("fit: rank_tolerance must be finite and >= 0");
  }
  if (!(o.alias_correlation > 0 && o.alias_correlation <= 1)) {
    throw std::invalid_argument("fit: alias_correlation must lie in (0, 1]");
  }
  if (!(o.max_condition >= 1)) throw std::invalid_argument("fit: max_condition must be >= 1");
  if (o.refinement_steps < 0) throw std::invalid_argument("fit: refinement_steps must be >= 0");
}

// Correlation matrix of a covariance matrix (any positive scale factor cancels).
Eigen::MatrixXd correlation_of(const Eigen::MatrixXd& cov) {
  const Index m = cov.rows();
  Eigen::MatrixXd corr(m, m);
  for (Index i = 0; i < m; ++i) {
    for (Index j = 0; j < m; ++j) {
      const double denom = std::sqrt(cov(i, i) * cov(j, j));
      corr(i, j) = (i == j) ? 1.0 : (denom > 0 ? cov(i, j) / denom : 0.0);
    }
  }
  return corr;
}

// The pair with the largest |correlation|; m >= 2.
std::pair<Index, Index> most_correlated_pair(const Eigen::MatrixXd& corr) {
  std::pair<Index, Index> best{0, 1};
  double best_value = -1;
  for (Index i = 0; i < corr.rows(); ++i) {
    for (Index j = i + 1; j < corr.cols(); ++j) {
      if (std::abs(corr(i, j)) > best_value) {
        best_value = std::abs(corr(i, j));
        best = {i, j};
      }
    }
  }
  return best;
}

// Names the terms taking part in each (numerical) null vector of the scaled design.
[[noreturn]] void throw_rank_deficient(const Eigen::VectorXd& sigma, const Eigen::MatrixXd& v,
                                       double tolerance, const std::vector<std::string>& names) {
  std::vector<std::string> groups, all_involved;
  for (Index i = 0; i < sigma.size(); ++i) {
    if (sigma(i) > tolerance) continue;
    const Eigen::VectorXd null_vector = v.col(i);
    const double largest = null_vector.cwiseAbs().maxCoeff();
    std::vector<std::string> involved;
    for (Index k = 0; k < null_vector.size(); ++k) {
      // A dependency among q columns has components of order 1/sqrt(q); bystanders are near zero.
      if (std::abs(null_vector(k)) > 0.1 * largest) involved.push_back(names[static_cast<std::size_t>(k)]);
    }
    all_involved.insert(all_involved.end(), involved.begin(), involved.end());
    if (involved.size() == 1) {
      groups.push_back(
          fmt::format("the plan cannot determine {}: its column is (numerically) zero "
                      "(singular value {:.3g} of the scaled design)",
                      involved.front(), sigma(i)));
    } else {
      groups.push_back(
          fmt::format("the plan cannot separate {}: their columns are linearly dependent "
                      "(singular value {:.3g} of the scaled design)",
                      detail::join_names(involved), sigma(i)));
    }
  }
  std::string message = "fit: ";
  for (std::size_t g = 0; g < groups.size(); ++g) message += (g ? "; " : "") + groups[g];
  throw IllPosedFit(message, all_involved);
}

}  // namespace

namespace {

// The scaled least-squares problem min |A z − b| (A: the weighted design with columns scaled by `scale`):
// the solution z refined on the augmented system, and (AᵀA)⁻¹.
struct ScaledSolution {
  Eigen::VectorXd z;
  Eigen::MatrixXd cov_z;
};

// Rank and conditioning of A from its singular values (always computed: they are the diagnostics). Fills
// result.rank and result.condition_number; throws IllPosedFit for a rank-deficient design or one whose
// condition number exceeds max_condition. Returns (AᵀA)⁻¹ = V S⁻² Vᵀ.
Eigen::MatrixXd rank_and_conditioning(const Eigen::JacobiSVD<Eigen::MatrixXd>& svd, Index rows,
                                      const FitOptions& o, FitResult& result) {
  const Eigen::VectorXd sigma = svd.singularValues();
  const Index m = svd.cols();
  const double tolerance =
      o.rank_tolerance > 0 ? o.rank_tolerance : static_cast<double>(std::max(rows, m)) * kEps * sigma(0);
  result.rank = static_cast<int>((sigma.array() > tolerance).count());
  if (result.rank < m) throw_rank_deficient(sigma, svd.matrixV(), tolerance, result.names);
  result.condition_number = sigma(0) / sigma(m - 1);

  // (A^T A)^-1 for the scaled unknowns z (x = scale .* z), from V and the singular values.
  const Eigen::MatrixXd v_over_s = svd.matrixV() * sigma.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd cov_z_svd = v_over_s * v_over_s.transpose();
  if (result.condition_number > o.max_condition) {
    const Eigen::MatrixXd corr = correlation_of(cov_z_svd);
    const auto [i, j] = most_correlated_pair(corr);
    throw IllPosedFit(
        fmt::format("fit: the design is too ill-conditioned: condition number {:.3g} of the column-scaled "
                    "design exceeds "
                    "max_condition {:.3g}; the most correlated pair is {} and {} (correlation {:.10g})",
                    result.condition_number, o.max_condition, result.names[static_cast<std::size_t>(i)],
                    result.names[static_cast<std::size_t>(j)], corr(i, j)),
        {result.names[static_cast<std::size_t>(i)], result.names[static_cast<std::size_t>(j)]});
  }
  return cov_z_svd;
}

// Refinement of the augmented system [I A; A^T 0] [r; z] = [b; 0] (Bjorck): r is carried in
// double-double, both residuals of the system are accumulated in double-double and each correction
// comes from the same factorisation (`correction(f, g)` solves [I A; A^T 0] [dr; dz] = [f; g]). Unlike
// refining z alone with b - A z, this also removes the error that a large least-squares residual r induces
// in z (the cond^2 * eps * |r| term), which dominates for noisy data such as NIST's Wampler4/5.
template <class Correction>
void refine_augmented(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, int steps, Eigen::VectorXd& z,
                      const Correction& correction) {
  const Index rows = a.rows(), m = a.cols();
  Eigen::VectorXd r_hi(rows), r_lo(rows), f(rows), g(m);
  for (Index i = 0; i < rows; ++i) {
    CompensatedSum sum(b(i));
    for (Index k = 0; k < m; ++k) sum.add_product(-a(i, k), z(k));
    std::tie(r_hi(i), r_lo(i)) = sum.split();
  }
  for (int step = 0; step < steps; ++step) {
    for (Index i = 0; i < rows; ++i) {  // f = b - r - A z
      CompensatedSum sum(b(i));
      sum.add(-r_hi(i));
      sum.add(-r_lo(i));
      for (Index k = 0; k < m; ++k) sum.add_product(-a(i, k), z(k));
      f(i) = sum.value();
    }
    for (Index k = 0; k < m; ++k) {  // g = -A^T r
      CompensatedSum sum;
      for (Index i = 0; i < rows; ++i) {
        sum.add_product(-a(i, k), r_hi(i));
        sum.add_product(-a(i, k), r_lo(i));
      }
      g(k) = sum.value();
    }
    const auto [dr, dz] = correction(f, g);
    for (Index i = 0; i < rows; ++i) {
      CompensatedSum sum(r_hi(i));
      sum.add(r_lo(i));
      sum.add(dr(i));
      std::tie(r_hi(i), r_lo(i)) = sum.split();
    }
    z += dz;
  }
}

// The solution by column-pivoted QR, A = Q [R; 0] P^T, refined; (A^T A)^-1 = P R^-1 R^-T P^T.
ScaledSolution refined_qr_solution(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, int refinement_steps) {
  const Index rows = a.rows(), m = a.cols();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  // Full rank was established from the singular values; let QR use every pivot.
  qr.setThreshold(std::numeric_limits<double>::min());
  Eigen::VectorXd z = qr.solve(b);
  const auto r_factor = qr.matrixR().topLeftCorner(m, m).triangularView<Eigen::Upper>();
  // Correction of [I A; A^T 0] [dr; dz] = [f; g]:
  //   R^T u = P^T g,  c = Q^T f,  dr = Q [u; c_2],  R P^T dz = c_1 - u.
  refine_augmented(a, b, refinement_steps, z, [&](const Eigen::VectorXd& f, const Eigen::VectorXd& g) {
    const Eigen::VectorXd c = qr.householderQ().adjoint() * f;
    const Eigen::VectorXd u = r_factor.transpose().solve(qr.colsPermutation().transpose() * g);
    Eigen::VectorXd w(rows);
    w << u, c.tail(rows - m);
    const Eigen::VectorXd dr = qr.householderQ() * w;
    const Eigen::VectorXd dz = qr.colsPermutation() * r_factor.solve(c.head(m) - u);
    return std::pair{dr, dz};
  });
  const Eigen::MatrixXd r_inv = r_factor.solve(Eigen::MatrixXd::Identity(m, m));
  const Eigen::MatrixXd permuted = r_inv * r_inv.transpose();
  return {z, qr.colsPermutation() * permuted * qr.colsPermutation().transpose()};
}

// The solution by the thin SVD A = U S V^T, refined. Correction: u = S^-1 V^T g, dr = U u + (f - U U^T f),
// dz = V S^-1 (U^T f - u). The covariance is the one rank_and_conditioning formed.
ScaledSolution refined_svd_solution(const Eigen::JacobiSVD<Eigen::MatrixXd>& svd, const Eigen::MatrixXd& a,
                                    const Eigen::VectorXd& b, int refinement_steps, Eigen::MatrixXd cov_z) {
  const Eigen::VectorXd sigma = svd.singularValues();
  Eigen::VectorXd z = svd.solve(b);
  refine_augmented(a, b, refinement_steps, z, [&](const Eigen::VectorXd& f, const Eigen::VectorXd& g) {
    const Eigen::VectorXd u = (svd.matrixV().transpose() * g).cwiseQuotient(sigma);
    const Eigen::VectorXd utf = svd.matrixU().transpose() * f;
    const Eigen::VectorXd dr = svd.matrixU() * (u - utf) + f;
    const Eigen::VectorXd dz = svd.matrixV() * (utf - u).cwiseQuotient(sigma);
    return std::pair{dr, dz};
  });
  return {z, std::move(cov_z)};
}

// Rank and conditioning from the singular values (throws IllPosedFit), then the solution by the chosen
// method. Fills result.rank and result.condition_number.
ScaledSolution solve_scaled(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, const FitOptions& o,
                            FitResult& result) {
  const unsigned svd_options =
      o.method == FitMethod::svd ? (Eigen::ComputeThinU | Eigen::ComputeThinV) : Eigen::ComputeThinV;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, svd_options);
  Eigen::MatrixXd cov_z_svd = rank_and_conditioning(svd, a.rows(), o, result);
  if (o.method == FitMethod::qr) return refined_qr_solution(a, b, o.refinement_steps);
  return refined_svd_solution(svd, a, b, o.refinement_steps, std::move(cov_z_svd));
}

// The pairs of estimates the data cannot separate (refused) or barely separate (a warning).
void check_correlations(const FitOptions& o, FitResult& result) {
  const Index m = result.correlation.rows();
  for (Index i = 0; i < m; ++i) {
    for (Index j = i + 1; j < m; ++j) {
      if (std::abs(result.correlation(i, j)) > o.refuse_correlation) {
        throw IllPosedFit(
            fmt::format("the plan cannot separate {} and {}: the correlation of their estimates is {:.8g} "
                        "(beyond {:.8g}), so "
                        "the data determine only a combination of the two",
                        result.names[static_cast<std::size_t>(i)], result.names[static_cast<std::size_t>(j)],
                        result.correlation(i, j), o.refuse_correlation),
            {result.names[static_cast<std::size_t>(i)], result.names[static_cast<std::size_t>(j)]});
      }
      if (std::abs(result.correlation(i, j)) > o.alias_correlation) {
        result.warnings.push_back(
            fmt::format("{} and {} are nearly aliased: correlation {:.6g} of their estimates exceeds {:.6g}; "
                        "the plan barely "
                        "separates them",
                        result.names[static_cast<std::size_t>(i)], result.names[static_cast<std::size_t>(j)],
                        result.correlation(i, j), o.alias_correlation));
      }
    }
  }
}

// The free terms (their columns, and their names in result order) and the fixed ones with their values.
struct TermSplit {
  std::vector<Index> free_cols;
  std::vector<std::pair<Index, double>> fixed_cols;
};
TermSplit split_terms(const FitProblem& p, std::vector<std::string>& free_names) {
  TermSplit split;
  for (std::size_t k = 0; k < p.term_names.size(); ++k) {
    const auto found = p.fixed.find(p.term_names[k]);
    const Index col = static_cast<Index>(k);
    if (found == p.fixed.end()) {
      split.free_cols.push_back(col);
      free_names.push_back(p.term_names[k]);
    } else {
      split.fixed_cols.emplace_back(col, found->second);
    }
  }
  return split;
}

// y_i minus the fixed contributions Σ H_ik x_k, accumulated accurately.
CompensatedSum reduced_y(const FitProblem& p, const std::vector<std::pair<Index, double>>& fixed_cols,
                         Index i) {
  CompensatedSum sum(p.y(i));
  for (const auto& [col, value] : fixed_cols) sum.add_product(-p.H(i, col), value);
  return sum;
}

// Weighted design A = sqrt(W) H and right-hand side b = sqrt(W) (y − fixed contributions), the latter from
// the double-double reduced y.
struct WeightedSystem {
  Eigen::MatrixXd a;
  Eigen::VectorXd b;
};
WeightedSystem weighted_system(const FitProblem& p, const Eigen::MatrixXd& h_free,
                               const std::vector<std::pair<Index, double>>& fixed_cols) {
  const Index rows = p.H.rows();
  const bool weighted = p.weights.size() != 0;
  const Eigen::VectorXd sqrt_w = weighted ? p.weights.cwiseSqrt().eval() : Eigen::VectorXd::Ones(rows).eval();
  WeightedSystem s{weighted ? (sqrt_w.asDiagonal() * h_free).eval() : h_free, Eigen::VectorXd(rows)};
  for (Index i = 0; i < rows; ++i) {
    const auto [hi, lo] = reduced_y(p, fixed_cols, i).split();
    s.b(i) = weighted ? sqrt_w(i) * hi + sqrt_w(i) * lo : hi;
  }
  return s;
}

// Scales each column of `a` by a power of two close to 1/norm: exact, so the scaled problem is the same
// problem. Returns the scales; throws IllPosedFit for a zero column.
Eigen::VectorXd scale_columns(Eigen::MatrixXd& a, const std::vector<std::string>& names) {
  Eigen::VectorXd scale(a.cols());
  for (Index k = 0; k < a.cols(); ++k) {
    const double norm = a.col(k).stableNorm();
    if (!(norm > 0)) {
      const std::string& name = names[static_cast<std::size_t>(k)];
      throw IllPosedFit(
          fmt::format("fit: the plan cannot determine {}: its column is zero in every run", name), {name});
    }
    scale(k) = std::ldexp(1.0, -std::ilogb(norm));
    a.col(k) *= scale(k);
  }
  return scale;
}

// Residuals in the units of y and chi2 = Σ w_i r_i², accumulated accurately.
void residuals_and_chi2(const FitProblem& p, const Eigen::MatrixXd& h_free,
                        const std::vector<std::pair<Index, double>>& fixed_cols, FitResult& result) {
  const Index rows = p.H.rows(), m = h_free.cols();
  const bool weighted = p.weights.size() != 0;
  result.residuals.resize(rows);
  CompensatedSum chi2;
  for (Index i = 0; i < rows; ++i) {
    CompensatedSum sum = reduced_y(p, fixed_cols, i);
    for (Index k = 0; k < m; ++k) sum.add_product(-h_free(i, k), result.value(k));
    const double r = sum.value();
    result.residuals(i) = r;
    chi2.add_product(weighted ? p.weights(i) * r : r, r);
  }
  result.chi2 = chi2.value();
}

// The covariance from (HᵀWH)⁻¹: as it is with weights (they state the scale), scaled by chi2/dof without;
// with no degrees of freedom only the weights can give it.
void covariance_from_scale(const Eigen::MatrixXd& cov_unit, bool weighted, FitResult& result) {
  if (result.dof > 0) {
    result.chi2_per_dof = result.chi2 / result.dof;
    result.residual_std = std::sqrt(result.chi2_per_dof);
    result.covariance = weighted ? cov_unit : (result.chi2_per_dof * cov_unit).eval();
  } else if (weighted) {
    result.covariance = cov_unit;
    result.warnings.push_back(
        "no degrees of freedom: the residual scale is undefined (residual_std and chi2_per_dof are reported "
        "as "
        "0); the covariance comes from the weights");
  } else {
    result.warnings.push_back(
        "no degrees of freedom: standard errors are undefined (std_error and covariance are reported as 0)");
  }
  result.std_error = result.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
}

// Finite data can still overflow in the solution (values near 1e308 square to infinity in the norms and in
// chi2): a fit whose estimates, standard errors or chi2 are not finite is refused, not returned as NaN.
void check_finite_result(const FitProblem& p, const FitResult& r) {
  std::string bad;
  for (Index k = 0; k < r.value.size() && bad.empty(); ++k)
    if (!std::isfinite(r.value(k)) || !std::isfinite(r.std_error(k)))
      bad = fmt::format("the estimate of {} or its standard error", r.names[static_cast<std::size_t>(k)]);
  if (bad.empty() && !std::isfinite(r.chi2)) bad = "chi2, the sum of the squared residuals,";
  if (bad.empty()) return;
  const double y_max = p.y.size() ? p.y.cwiseAbs().maxCoeff() : 0.0;
  const double h_max = p.H.size() ? p.H.cwiseAbs().maxCoeff() : 0.0;
  // A fixed term of a far larger size than the data (K1 = 1e308 given for a table of y near 1) overflows the
  // output less its contribution: said of that term, not of the data. 1e150: its square still near 1e300.
  for (const auto& [name, value] : p.fixed) {
    const auto at = std::find(p.term_names.begin(), p.term_names.end(), name);
    if (at == p.term_names.end() || p.H.rows() == 0) continue;
    const double column_max = p.H.col(at - p.term_names.begin()).cwiseAbs().maxCoeff();
    if (std::abs(value) * column_max > 1e150)
      throw InputError(fmt::format(
          "fit: {} is not a finite number: the fixed term {} = {:.6g}, times its regressor (up to {:.3g}), is far "
          "beyond data of largest |y| = {:.3g} and overflows the arithmetic; accepted: a fixed value of the size "
          "the term has in these data's units",
          bad, name, value, column_max, y_max));
  }
  throw InputError(
      fmt::format("fit: {} is not a finite number: the data overflow the arithmetic of the least-squares "
                  "solution (largest |y| = {:.3g}, largest regressor {:.3g}); accepted: data whose squares and "
                  "products stay finite: scale y or the input column (e.g. other units) towards magnitudes "
                  "near 1",
                  bad, y_max, h_max));
}

}  // namespace

FitResult fit(const FitProblem& p, const FitOptions& o) {
  validate(p, o);
  const Index rows = p.H.rows();
  const bool weighted = p.weights.size() != 0;

  // Split free and fixed terms; the fixed contributions move to the left-hand side.
  FitResult result;
  const TermSplit split = split_terms(p, result.names);
  const Index m = static_cast<Index>(split.free_cols.size());
  if (rows < m) {
    throw IllPosedFit(
        fmt::format("fit: {} observation{} cannot determine {} free terms ({}); the plan needs at "
                    "least {} runs",
                    rows, rows == 1 ? "" : "s", m, detail::join_names(result.names), m),
        result.names);
  }
  Eigen::MatrixXd h_free(rows, m);
  for (Index k = 0; k < m; ++k) h_free.col(k) = p.H.col(split.free_cols[static_cast<std::size_t>(k)]);
  WeightedSystem system = weighted_system(p, h_free, split.fixed_cols);
  const Eigen::VectorXd scale = scale_columns(system.a, result.names);

  result.value = Eigen::VectorXd::Zero(m);
  result.std_error = Eigen::VectorXd::Zero(m);
  result.covariance = Eigen::MatrixXd::Zero(m, m);
  result.correlation = Eigen::MatrixXd::Identity(m, m);
  result.dof = static_cast<int>(rows - m);

  Eigen::MatrixXd cov_unit = Eigen::MatrixXd::Zero(m, m);  // (H^T W H)^-1
  if (m > 0) {
    const ScaledSolution solved = solve_scaled(system.a, system.b, o, result);
    result.value = solved.z.cwiseProduct(scale);
    cov_unit = scale.asDiagonal() * solved.cov_z * scale.asDiagonal();
    result.correlation = correlation_of(cov_unit);
  }
  residuals_and_chi2(p, h_free, split.fixed_cols, result);
  covariance_from_scale(cov_unit, weighted, result);
  check_finite_result(p, result);
  check_correlations(o, result);
  return result;
}

Eigen::MatrixXd polynomial_design(const Eigen::VectorXd& x, int degree) {
  if (degree < 0) throw std::invalid_argument(fmt::format("polynomial_design: negative degree {}", degree));
  Eigen::MatrixXd h(x.size(), degree + 1);
  for (Index i = 0; i < x.size(); ++i) {
    // x^k carried as a double-double pair (hi, lo) and rounded once per entry.
    double hi = 1.0, lo = 0.0;
    for (int k = 0; k <= degree; ++k) {
      h(i, k) = hi + lo;
      const double product = hi * x(i);
      const double error = std::fma(hi, x(i), -product) + lo * x(i);
      hi = product + error;
      lo = error - (hi - product);
    }
  }
  return h;
}

IllPosedFit plan_cannot_identify(const IllPosedFit& e) {
  return IllPosedFit(std::string("the test plan cannot identify the configured terms: ") + e.what(),
                     e.terms());
}

std::vector<std::string> polynomial_term_names(int degree) {
  if (degree < 0)
    throw std::invalid_argument(fmt::format("polynomial_term_names: negative degree {}", degree));
  std::vector<std::string> names;
  for (int k = 0; k <= degree; ++k) names.push_back(fmt::format("K{}", k));
  return names;
}

}  // namespace ccal
