#include "ccal/setup/tolerance.hpp"

#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <map>
#include <numbers>

namespace ccal {

std::string_view distribution_name(Distribution d) noexcept {
  switch (d) {
    case Distribution::normal:
      return "normal";
    case Distribution::uniform:
      return "uniform";
    case Distribution::triangular:
      return "triangular";
    case Distribution::arcsine:
      return "arcsine";
  }
  return "normal";
}

double divisor(Distribution d) noexcept {
  switch (d) {
    case Distribution::normal:
      return 1.0;
    case Distribution::uniform:
      return std::sqrt(3.0);
    case Distribution::triangular:
      return std::sqrt(6.0);
    case Distribution::arcsine:
      return std::numbers::sqrt2;
  }
  return 1.0;
}

double standard_uncertainty(double bound, Distribution d) noexcept { return bound / divisor(d); }

CorrelationGroups correlation_groups(const std::vector<std::string>& group_of_each, std::size_t sources) {
  CorrelationGroups g;
  std::map<std::string, int> named;
  for (std::size_t s = 0; s < sources; ++s) {
    const std::string& name = s < group_of_each.size() ? group_of_each[s] : std::string();
    if (name.empty()) {
      g.of.push_back(g.count++);
      continue;
    }
    const auto [it, inserted] = named.try_emplace(name, g.count);
    if (inserted) {
      ++g.count;
      ++g.named;
    }
    g.of.push_back(it->second);
  }
  return g;
}

// erf⁻¹ in double precision (no promotion to long double: the rational approximations for 64-bit precision
// are already more accurate than double).
double normal_erf_quantile(double x) {
  using Policy = boost::math::policies::policy<boost::math::policies::promote_double<false>>;
  return std::numbers::sqrt2 * boost::math::erf_inv(x, Policy());
}

}  // namespace ccal
