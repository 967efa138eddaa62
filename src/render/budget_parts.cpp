#include "budget_parts.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "ccal/core/units.hpp"
#include "ccal/setup/input_description.hpp"

namespace ccal::render::budget_parts {

SourceView source_view(const Config& cfg, const SourceBudget& s) {
  SourceView v;
  const InputDescription d = describe_input(cfg, s.parameter);
  v.name = d.name;
  v.unit = s.unit;
  if (v.unit.empty())
    v.unit = d.si_unit == "1" || d.display_unit == "ppm" || is_chain_parameter(s.parameter) ? d.display_unit
                                                                                              : d.si_unit;
  v.unit_si = unit_in_si(d, v.unit);
  v.estimate_si = d.estimate_si;
  v.estimate = v.estimate_si / v.unit_si;
  v.bound = s.bound / v.unit_si;
  v.divisor = divisor(s.distribution);
  v.u = s.standard_uncertainty / v.unit_si;
  return v;
}

SourceView rate_noise_view(const RateNoiseBudget& n) {
  SourceView v;
  v.unit = "ppm/rtHz";
  v.unit_si = 1e-6;
  v.bound = v.u = n.density / v.unit_si;
  v.type = 'A';
  v.name = fmt::format("{} drive's random rate noise, independent per run",
                       n.id.starts_with("platform") ? "the platform" : "the main-axis");
  return v;
}

double sensitivity_per_unit(const ccal::BudgetDetail& r, const SourceBudget& s, const SourceView& view,
                            std::size_t k) {
  return s.sensitivity[Eigen::Index(k)] * r.display_scale[k] * view.unit_si;
}

double sensitivity_per_unit(const ccal::BudgetDetail& r, const RateNoiseBudget& n, const SourceView& view,
                            std::size_t k) {
  return view.u > 0 ? n.effect[Eigen::Index(k)] * r.display_scale[k] / view.u : 0.0;
}

std::string sensitivity_unit(const ccal::BudgetDetail& r, std::size_t k, const SourceView& view) {
  return fmt::format("{} per {}", r.units[k], view.unit);
}

std::string divisor_text(double divisor) {
  const double square = std::round(divisor * divisor);
  return square == 1 ? "1" : fmt::format("√{}", square);
}

double round_off_floor(const ccal::BudgetDetail& r, std::size_t k) {
  return kRoundOffFloor * r.standard_uncertainty[Eigen::Index(k)] * r.display_scale[k];
}

bool below_round_off_floor(const ccal::BudgetDetail& r, double contribution_si, std::size_t k) {
  return std::abs(contribution_si) < kRoundOffFloor * r.standard_uncertainty[Eigen::Index(k)];
}

std::vector<BudgetLine> budget_lines(const Config& cfg, const ccal::BudgetDetail& r, std::size_t k) {
  const auto i = Eigen::Index(k);
  std::vector<BudgetLine> lines;
  for (const SourceBudget& s : r.sources) {
    BudgetLine l{&s, source_label(s.id, s.group), source_view(cfg, s),
                 std::string(distribution_name(s.distribution))};
    l.sensitivity = sensitivity_per_unit(r, s, l.x, k);
    l.contribution = s.effect[i] * r.display_scale[k];
    l.share = s.share[i];
    l.round_off = below_round_off_floor(r, s.effect[i], k);
    lines.push_back(std::move(l));
  }
  for (const RateNoiseBudget& n : r.rate_noise) {
    BudgetLine l{nullptr, n.id, rate_noise_view(n), std::string(distribution_name(Distribution::normal))};
    l.sensitivity = sensitivity_per_unit(r, n, l.x, k);
    l.contribution = n.effect[i] * r.display_scale[k];
    l.share = n.share[i];
    l.round_off = below_round_off_floor(r, n.effect[i], k);
    lines.push_back(std::move(l));
  }
  std::stable_sort(lines.begin(), lines.end(),
                   [](const BudgetLine& a, const BudgetLine& b) { return a.share > b.share; });
  return lines;
}

std::vector<Contribution> contributions(const ccal::BudgetDetail& r, std::size_t k) {
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
  if (r.input_factor.size() > 0) {
    // Partly correlated sources: each its own share c²u²/u_c², and the cross terms Σ_{s≠t} c_s u_s r_st c_t
    // u_t as one more line (negative where the correlations cancel), so that the shares add to 1.
    for (const SourceBudget& s : r.sources)
      out.push_back({s.group.empty() ? s.id : s.group + " (" + s.id + ")",
                     variance > 0 ? s.effect[i] * s.effect[i] / variance : 0.0});
    out.push_back(
        {std::string(kCrossTermsLabel), variance > 0 ? correlation_variance(r)[i] / variance : 0.0});
    effect.clear();
  }
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

std::vector<Contribution> answer_contributions(const ccal::BudgetDetail& r, std::size_t k) {
  const std::vector<Contribution> all = contributions(r, k);
  std::vector<Contribution> out, cancelling;
  double sum = 0;
  for (const Contribution& c : all)
    if (c.share < 0) {
      sum += c.share;
      if (c.share <= -0.01) cancelling.push_back(c);
    }
  for (const Contribution& c : all) {
    if (sum >= 0.9) break;
    if (c.share < 0) continue;
    sum += c.share;
    out.push_back(c);
  }
  out.insert(out.end(), cancelling.begin(), cancelling.end());
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

std::string csv_column(std::string_view name, std::string_view unit) {
  std::string word;
  for (std::size_t i = 0; i < unit.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(unit[i]);
    const std::string_view rest = unit.substr(i);
    if (std::isalnum(c)) {
      word += char(c);
    } else if (c == '^') {
      continue;
    } else if (rest.starts_with("\u00b5") || rest.starts_with("\u03bc")) {  // µ (micro sign, Greek mu)
      word += 'u';
      ++i;
    } else if (rest.starts_with("\u00b0")) {  // °
      word += "deg";
      ++i;
    } else if (c == '%') {
      word += "pct";
    } else if (c >= 0x80) {  // another non-ASCII character: one '_' for all its bytes
      if (word.empty() || word.back() != '_') word += '_';
      while (i + 1 < unit.size() && (static_cast<unsigned char>(unit[i + 1]) & 0xc0) == 0x80) ++i;
    } else if (!word.empty() && word.back() != '_') {
      word += '_';
    }
  }
  while (!word.empty() && word.back() == '_') word.pop_back();
  return word.empty() ? std::string(name) : std::string(name) + "_" + word;
}

nlohmann::ordered_json input_correlation_json(const ccal::BudgetDetail& r) {
  if (r.input_correlation.size() == 0) return nullptr;
  // The inputs' correlation matrix ([[correlations]] and the groups' r = 1), in tolerance order, and the
  // part of each coefficient's u² its cross terms make (negative where they cancel).
  nlohmann::ordered_json ids = nlohmann::ordered_json::array(), rows = nlohmann::ordered_json::array();
  for (Eigen::Index a = 0; a < r.input_correlation.rows(); ++a) {
    ids.push_back(r.sources[std::size_t(a)].id);
    nlohmann::ordered_json row = nlohmann::ordered_json::array();
    for (Eigen::Index b = 0; b < r.input_correlation.cols(); ++b) row.push_back(r.input_correlation(a, b));
    rows.push_back(row);
  }
  const Eigen::VectorXd cross = correlation_variance(r);
  nlohmann::ordered_json share = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < r.coefficients.size(); ++k) {
    const double u = r.standard_uncertainty[Eigen::Index(k)];
    share[r.coefficients[k]] = u > 0 ? cross[Eigen::Index(k)] / (u * u) : 0.0;
  }
  return {{"sources", ids}, {"matrix", rows}, {"share_of_variance", share}};
}

}  // namespace ccal::render::budget_parts
