#include "ccal/uncertainty/history_shared.hpp"

#include <algorithm>

namespace ccal {

namespace {

const SharedInput* find_input(const SharedPart& part, const std::string& id) {
  const auto it =
      std::find_if(part.inputs.begin(), part.inputs.end(), [&](const SharedInput& s) { return s.id == id; });
  return it == part.inputs.end() ? nullptr : &*it;
}

double effect_on(const SharedInput& input, const std::string& coefficient) {
  const auto it = input.effect.find(coefficient);
  return it == input.effect.end() ? 0.0 : it->second;
}

}  // namespace

double input_correlation(const SharedPart& part, const std::string& first, const std::string& second) {
  if (first == second) return 1;
  const SharedInput *a = find_input(part, first), *b = find_input(part, second);
  if (a && b && !a->group.empty() && a->group == b->group) return 1;
  for (const SharedCorrelation& c : part.correlations)
    if ((c.first == first && c.second == second) || (c.first == second && c.second == first)) return c.r;
  return 0;
}

double shared_covariance(const std::optional<SharedPart>& i, const std::optional<SharedPart>& j,
                         const std::string& coefficient) {
  if (!i || !j || i->setup_sha256.empty() || i->setup_sha256 != j->setup_sha256) return 0;
  // S: charged at its tolerance in both, with the effects e_i and e_j on the coefficient.
  struct Shared {
    std::string id;
    double in_i, in_j;
  };
  std::vector<Shared> common;
  for (const SharedInput& a : i->inputs) {
    const SharedInput* b = find_input(*j, a.id);
    if (a.measured || !b || b->measured) continue;
    common.push_back({a.id, effect_on(a, coefficient), effect_on(*b, coefficient)});
  }
  double covariance = 0;
  for (const Shared& a : common)
    for (const Shared& b : common) {
      const double r = input_correlation(*i, a.id, b.id);
      if (r != 0 && r == input_correlation(*j, a.id, b.id)) covariance += a.in_i * r * b.in_j;
    }
  return covariance;
}

Eigen::MatrixXd shared_covariance_matrix(const std::vector<const std::optional<SharedPart>*>& parts,
                                         const std::string& coefficient) {
  const auto n = Eigen::Index(parts.size());
  Eigen::MatrixXd c(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j <= i; ++j)
      c(i, j) = c(j, i) = shared_covariance(*parts[std::size_t(i)], *parts[std::size_t(j)], coefficient);
  return c;
}

}  // namespace ccal
