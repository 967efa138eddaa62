#include "design_mechanism.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "ccal/setup/input_description.hpp"

namespace ccal::verbs {

Eigen::VectorXd tolerance_expanded(const ccal::BudgetDetail& b) {
  return b.coverage.factor * independent_effects(b).rowwise().norm();
}

double heading_imbalance(const Config& c) {
  double worst = 0;
  std::vector<bool> done(c.plan.runs.size(), false);
  for (std::size_t a = 0; a < c.plan.runs.size(); ++a) {
    if (done[a]) continue;
    double x = 0, y = 0;
    int n = 0;
    for (std::size_t b = a; b < c.plan.runs.size(); ++b) {
      if (c.plan.runs[b].g_level != c.plan.runs[a].g_level) continue;
      done[b] = true;
      const double psi = initial_ia_azimuth(c.plan.runs[b], c.centrifuge.geometry, c.site);
      x += std::cos(psi);
      y += std::sin(psi);
      ++n;
    }
    worst = std::max(worst, std::hypot(x, y) / n);
  }
  return worst;
}

namespace {

// The sources by the size of their effect on coefficient k in budget b, largest first.
std::vector<std::size_t> by_effect(const ccal::BudgetDetail& b, Eigen::Index k) {
  std::vector<std::size_t> order(b.sources.size());
  for (std::size_t s = 0; s < order.size(); ++s) order[s] = s;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t c) {
    return std::abs(b.sources[a].effect[k]) > std::abs(b.sources[c].effect[k]);
  });
  return order;
}

// One coefficient's paragraph. U ∝ (the errors' leak projected on the coefficient's column) / s², s the part
// of the column no other free term explains (model.md §14): a column s times larger divides every leak's cost
// by about s; what is left of the change is the leaks cancelling between runs (model.md §15.3).
std::string coefficient_paragraph(const DesignResult& r, std::size_t k) {
  const ccal::BudgetDetail& b0 = r.before.budget;
  const ccal::BudgetDetail& b1 = r.after.budget;
  const auto kk = Eigen::Index(k);
  const double f = b0.display_scale[k];
  const double u0 = r.tolerance_before[kk], u1 = r.tolerance_after[kk];
  const double signal =
      r.after.observability.result.terms[k].sensitivity / r.before.observability.result.terms[k].sensitivity;
  const std::string& id = r.targets[k].coefficient;
  std::vector<std::string> leading;
  const std::vector<std::size_t> order = by_effect(b0, kk);
  for (std::size_t i = 0; i < std::min<std::size_t>(4, order.size()); ++i) {
    const SourceBudget& s0 = b0.sources[order[i]];
    leading.push_back(
        fmt::format("{} ({}) {:.2g} -> {:.2g}", describe_input(r.config, s0.parameter).name,
                    s0.id, std::abs(s0.effect[kk]) * f, std::abs(b1.sources[order[i]].effect[kk]) * f));
  }
  const double rest = (u1 / u0) * signal;
  const std::string cancel =
      std::abs(rest - 1) < 0.05
          ? fmt::format("the errors' effects on {} cancelling between the runs about as before (x{:.3g})", id,
                        rest)
      : rest < 1
          ? fmt::format("the errors' effects on {} cancelling between the runs better (x{:.2g})", id, rest)
          : fmt::format("the errors' effects on {} cancelling between the runs less well (x{:.2g})", id,
                        rest);
  const std::string strength =
      std::abs(signal - 1) < 0.05
          ? fmt::format(
                "The designed runs show the part of {}'s signal that no other coefficient can imitate about "
                "as strongly as the configured ones (x{:.3g}); the change is {}.",
                id, signal, cancel)
          : fmt::format(
                "The designed runs make the part of {}'s signal that no other coefficient can imitate "
                "{:.2g} times {}, which alone {} every error's cost by about that factor; the rest is {}.",
                id, signal >= 1 ? signal : 1 / signal, signal >= 1 ? "larger" : "smaller",
                signal >= 1 ? "divides" : "multiplies", cancel);
  return fmt::format(
      "{0}: the inputs' tolerances cost U = {1:.3g} {3} with the configured plan and {2:.3g} {3} with "
      "the "
      "designed one (x{4:.2g}). {5} Largest contributors (1-sigma effect on {0}, configured -> designed): "
      "{6}.\n",
      id, u0 * f, u1 * f, b0.units[k], u1 / u0, strength, fmt::join(leading, "; "));
}

}  // namespace

std::string mechanism_text(const DesignResult& r) {
  std::string out;
  for (std::size_t k = 0; k < r.targets.size(); ++k) {
    const auto kk = Eigen::Index(k);
    if (r.targets[k].weight > 0 && r.tolerance_before[kk] > 0 && r.tolerance_after[kk] > 0)
      out += coefficient_paragraph(r, k);
  }
  const double before = heading_imbalance(r.config), after = heading_imbalance(r.designed);
  if (after < 0.05 && after < before)
    out += fmt::format(
        "At each g-level the designed runs point the input axis in opposite directions in pairs (its heading "
        "at "
        "the start, arm azimuth + platform phase, is balanced to {:.2f}; configured plan {:.2f}, 1 when all "
        "runs "
        "of a level point alike): an error whose effect follows that heading - the tilt of the main axis and "
        "the "
        "first harmonic of its rate ripple - cancels in each g-level's mean instead of reaching the "
        "coefficients.\n",
        after, before);
  return out;
}

}  // namespace ccal::verbs
