#include "budget_parts.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "ccal/core/units.hpp"

namespace ccal::render::budget_parts {

SourceView source_view(const Config& cfg, const SourceBudget& s) {
  SourceView v;
  const ErrorLayout& layout = cfg.centrifuge.layout;
  v.name = layout.parameter_name(s.parameter);
  v.unit = s.unit;
  const SourceUnit si = layout.parameter_unit(s.parameter);
  if (v.unit.empty()) v.unit = si == SourceUnit::relative ? "ppm" : std::string(unit_symbol(si));
  v.unit_si = parse_unit(v.unit).value_si;
  v.bound = s.bound / v.unit_si;
  v.u = s.standard_uncertainty / v.unit_si;
  return v;
}

double sensitivity_per_unit(const ccal::BudgetResult& r, const SourceBudget& s, const SourceView& view,
                            std::size_t k) {
  return s.sensitivity[Eigen::Index(k)] * r.display_scale[k] * view.unit_si;
}

std::vector<Contribution> contributions(const ccal::BudgetResult& r, std::size_t k) {
  const auto i = Eigen::Index(k);
  const double variance = r.standard_uncertainty[i] * r.standard_uncertainty[i];
  const CorrelationGroups groups = correlation_groups(r.sources);
  std::vector<double> effect(std::size_t(groups.count), 0.0);
  std::vector<std::string> members(std::size_t(groups.count));
  for (std::size_t s = 0; s < r.sources.size(); ++s) {
    const auto g = std::size_t(groups.of[s]);
    effect[g] += r.sources[s].effect[i];  // fully correlated, same sign: effects add (model.md §10.1)
    members[g] += (members[g].empty() ? "" : ", ") + r.sources[s].id;
  }
  std::vector<Contribution> out;
  for (std::size_t g = 0; g < effect.size(); ++g) {
    std::string label = members[g];
    for (std::size_t s = 0; s < r.sources.size(); ++s)
      if (std::size_t(groups.of[s]) == g && !r.sources[s].group.empty()) {
        label = r.sources[s].group + " (" + members[g] + ")";
        break;
      }
    out.push_back({label, variance > 0 ? effect[g] * effect[g] / variance : 0.0});
  }
  for (const RateNoiseBudget& n : r.rate_noise) out.push_back({n.id, n.share[i]});
  std::stable_sort(out.begin(), out.end(),
                   [](const Contribution& a, const Contribution& b) { return a.share > b.share; });
  return out;
}

std::string source_label(const std::string& id, const std::string& group) {
  return group.empty() ? id : fmt::format("{} ({})", id, group);
}

std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace ccal::render::budget_parts
