#include "result_checks.hpp"

#include <fmt/format.h>

#include <cmath>

#include "ccal/core/errors.hpp"

namespace ccal::verbs {
namespace {

bool finite(const Eigen::VectorXd& v) { return v.allFinite(); }

[[noreturn]] void refuse(const Config& cfg, std::string_view what, std::string_view source) {
  throw InputError(fmt::format(
      "{}: {} is not a finite number{}: the tolerances or errors are beyond what double precision can "
      "carry; accepted: tolerances and errors of a real centrifuge (e.g. micrometres, microradians)",
      cfg.source, what, source.empty() ? "" : fmt::format(" (first at tolerances.{})", source)));
}

}  // namespace

void check_finite(const Config& cfg, const ccal::BudgetDetail& b) {
  std::string first;
  for (const auto& s : b.sources)
    if (first.empty() &&
        !(std::isfinite(s.standard_uncertainty) && finite(s.effect) && finite(s.sensitivity)))
      first = s.id;
  for (std::size_t k = 0; k < b.coefficients.size(); ++k) {
    const auto i = Eigen::Index(k);
    if (std::isfinite(b.standard_uncertainty[i]) && std::isfinite(b.expanded_uncertainty[i])) continue;
    // Finite effects whose squares overflow: the largest is the culprit.
    std::string largest = first;
    double most = -1;
    if (first.empty())
      for (const auto& s : b.sources)
        if (s.effect.size() > i && std::abs(s.effect[i]) > most) {
          most = std::abs(s.effect[i]);
          largest = s.id;
        }
    refuse(cfg, fmt::format("the uncertainty of {}", b.coefficients[k]), largest);
  }
  if (!first.empty() || !b.covariance.allFinite()) refuse(cfg, "the budget", first);
}

void check_finite(const Config& cfg, const ccal::AllocationDetail& r) {
  for (const auto& s : r.sources)
    if (!std::isfinite(s.allocated_bound) || !std::isfinite(s.scale) || !(s.scale > 0))
      refuse(cfg, fmt::format("the allocated tolerance of {} ({})", s.id, s.allocated_bound), s.id);
  for (const auto& c : r.coefficients)
    if (!std::isfinite(c.allocated_expanded) || !std::isfinite(c.configured_expanded))
      refuse(cfg, fmt::format("the allocated uncertainty of {}", c.id), "");
  if (!std::isfinite(r.objective)) refuse(cfg, "the allocation's objective", "");
}

}  // namespace ccal::verbs
