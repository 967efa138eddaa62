#include "ccal/render/budget.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "ccal/core/units.hpp"
#include "ccal/render/table.hpp"
#include "ccal/version.hpp"
#include "parts.hpp"

namespace ccal::render {
namespace {

std::vector<std::size_t> by_rank(const BudgetResult& r) {
  std::vector<std::size_t> order(r.sources.size());
  for (std::size_t s = 0; s < order.size(); ++s) order[std::size_t(r.sources[s].rank - 1)] = s;
  return order;
}

std::string bound_text(const SourceBudget& s, const ErrorLayout& layout) {
  const SourceUnit unit = layout.parameter_unit(s.parameter);
  if (unit == SourceUnit::relative) return number(s.bound * 1e6, 4) + " ppm";  // a rate ripple
  return number(s.bound, 4) + " " + std::string(unit_symbol(unit));
}

std::string text_of(const Config& cfg, const BudgetResult& r,
                    const verbs::ObservabilityReport& observability) {
  const auto nk = r.coefficients.size();
  std::string out = fmt::format(
      "ccal budget: {}, {} mode, {} runs, {} sources; identified {} with {} fixed\n"
      "Effects are 1-sigma (standard uncertainty of each source); shares are of the variance.\n\n",
      cfg.source, std::string(mode_name(r.mode)), cfg.plan.runs.size(), r.sources.size(),
      fmt::join(r.coefficients, ", "),
      cfg.identification.fixed_terms.empty()
          ? std::string("nothing")
          : fmt::format("{}", fmt::join(
                                  [&] {
                                    std::vector<std::string> ids;
                                    for (const auto& [id, v] : cfg.identification.fixed_terms)
                                      ids.push_back(id);
                                    return ids;
                                  }(),
                                  ", ")));
  std::vector<std::string> header = {"rank", "source", "tolerance", "distribution"};
  for (std::size_t k = 0; k < nk; ++k)
    header.push_back(fmt::format("d{} [{}]", r.coefficients[k], r.units[k]));
  for (std::size_t k = 0; k < nk; ++k) header.push_back(fmt::format("share {} [%]", r.coefficients[k]));
  const bool paper =
      r.mode == ModelMode::exact && !r.sources.empty() && r.sources.front().paper_effect.size();
  if (paper) header.push_back("exact vs paper");
  Table table(header);
  for (std::size_t s : by_rank(r)) {
    const SourceBudget& b = r.sources[s];
    std::vector<std::string> row = {
        std::to_string(b.rank), b.id + (b.group.empty() ? "" : " (" + b.group + ")"),
        bound_text(b, cfg.centrifuge.layout), std::string(distribution_name(b.distribution))};
    for (std::size_t k = 0; k < nk; ++k)
      row.push_back(number(b.effect[Eigen::Index(k)] * r.display_scale[k], 4));
    for (std::size_t k = 0; k < nk; ++k) row.push_back(fmt::format("{:.2f}", 100 * b.share[Eigen::Index(k)]));
    if (paper) {
      std::string flags;
      for (std::size_t k = 0; k < nk; ++k)
        if (b.disagrees[k]) flags += (flags.empty() ? "differ on " : ", ") + r.coefficients[k];
      row.push_back(!b.paper_counterpart ? "no paper rule" : flags.empty() ? "agree" : flags);
    }
    table.add_row(row);
  }
  // The drives' rate noise (Type A, independent per run): u per coefficient, no sign.
  for (const RateNoiseBudget& n : r.rate_noise) {
    std::vector<std::string> row = {"", n.id + " (Type A)", number(n.density * 1e6, 4) + " ppm/rtHz",
                                    "normal"};
    for (std::size_t k = 0; k < nk; ++k)
      row.push_back("±" + number(n.effect[Eigen::Index(k)] * r.display_scale[k], 4));
    for (std::size_t k = 0; k < nk; ++k) row.push_back(fmt::format("{:.2f}", 100 * n.share[Eigen::Index(k)]));
    if (paper) row.push_back("no paper rule");
    table.add_row(row);
  }
  table.add_rule();
  std::vector<std::string> total = {"", "total u (LPU, k = 1)", "", ""};
  std::vector<std::string> expanded = {"", fmt::format("expanded U (k = {:g})", r.coverage_factor), "", ""};
  for (std::size_t k = 0; k < nk; ++k) {
    total.push_back(number(r.standard_uncertainty[Eigen::Index(k)] * r.display_scale[k], 4));
    expanded.push_back(number(r.expanded_uncertainty[Eigen::Index(k)] * r.display_scale[k], 4));
  }
  table.add_row(total);
  table.add_row(expanded);
  out += table.render();

  // The angular-rate path (the paper's Table 5) for the sources that have one.
  std::vector<std::string> rate_header = {"source", "path"};
  for (std::size_t k = 0; k < nk; ++k)
    rate_header.push_back(fmt::format("d{} [{}]", r.coefficients[k], r.units[k]));
  Table paths(rate_header);
  int with_rate = 0;
  for (std::size_t s : by_rank(r)) {
    const SourceBudget& b = r.sources[s];
    // Only where the rate path matters: ≥ 1e-3 of a coefficient's total standard uncertainty.
    if (!(b.effect_rate.cwiseAbs().array() >= 1e-3 * r.standard_uncertainty.array()).any()) continue;
    ++with_rate;
    std::vector<std::string> f = {b.id, "specific force"}, w = {"", "angular rate"};
    for (std::size_t k = 0; k < nk; ++k) {
      f.push_back(number(b.effect_force[Eigen::Index(k)] * r.display_scale[k], 4));
      w.push_back(number(b.effect_rate[Eigen::Index(k)] * r.display_scale[k], 4));
    }
    paths.add_row(f);
    paths.add_row(w);
  }
  if (with_rate)
    out += "\nSources whose angular-rate path reaches 1e-3 of a total (1-sigma effects by path):\n" +
           paths.render();

  if (!r.compensation.empty()) {
    std::vector<std::string> ch = {"choice", "model"};
    for (std::size_t k = 0; k < nk; ++k)
      ch.push_back(fmt::format("bias {} [{}]", r.coefficients[k], r.units[k]));
    Table comp(ch);
    for (const auto& c : r.compensation) {
      std::vector<std::string> row = {c.id + " left out", std::string(mode_name(r.mode))};
      for (std::size_t k = 0; k < nk; ++k)
        row.push_back(number(c.bias[Eigen::Index(k)] * r.display_scale[k], 4));
      comp.add_row(row);
      if (c.paper_bias.size()) {
        std::vector<std::string> p = {"", "paper"};
        for (std::size_t k = 0; k < nk; ++k)
          p.push_back(number(c.paper_bias[Eigen::Index(k)] * r.display_scale[k], 4));
        comp.add_row(p);
      }
    }
    out += "\nCompensation choices (systematic biases, not in the totals; model them to remove them):\n" +
           comp.render();
  }
  if (paper) {
    int flagged = 0;
    for (const auto& b : r.sources) flagged += std::count(b.disagrees.begin(), b.disagrees.end(), true) > 0;
    out += fmt::format(
        "\n{} source(s) differ between the exact model and the paper's first-order rules by more than a "
        "factor "
        "of 2 (or in sign) on at least one coefficient; see docs/model.md §10.\n",
        flagged);
  }
  return out + "\n" + observability_text(observability);
}

nlohmann::ordered_json per_coefficient(const BudgetResult& r, const Eigen::VectorXd& v, bool scale = true) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < r.coefficients.size(); ++k)
    j[r.coefficients[k]] = v[Eigen::Index(k)] * (scale ? r.display_scale[k] : 1.0);
  return j;
}

std::string json_of(const Config& cfg, const BudgetResult& r,
                    const verbs::ObservabilityReport& observability) {
  nlohmann::ordered_json j;
  j["ccal_version"] = version();
  j["config"] = cfg.source;
  j["mode"] = std::string(mode_name(r.mode));
  j["derivatives"] = r.derivatives == DerivativeMethod::automatic ? "automatic" : "linearised";
  j["coverage_factor"] = r.coverage_factor;
  j["coefficients"] = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < r.coefficients.size(); ++k)
    j["coefficients"].push_back(
        {{"id", r.coefficients[k]},
         {"unit", r.units[k]},
         {"standard_uncertainty", r.standard_uncertainty[Eigen::Index(k)] * r.display_scale[k]},
         {"expanded_uncertainty", r.expanded_uncertainty[Eigen::Index(k)] * r.display_scale[k]}});
  j["sources"] = nlohmann::ordered_json::array();
  for (std::size_t s : by_rank(r)) {
    const SourceBudget& b = r.sources[s];
    nlohmann::ordered_json o;
    o["id"] = b.id;
    o["rank"] = b.rank;
    o["unit_si"] = unit_symbol(cfg.centrifuge.layout.parameter_unit(b.parameter));
    o["bound_si"] = b.bound;
    o["distribution"] = distribution_name(b.distribution);
    o["group"] = b.group;
    o["standard_uncertainty_si"] = b.standard_uncertainty;
    o["effect"] = per_coefficient(r, b.effect);
    o["effect_specific_force"] = per_coefficient(r, b.effect_force);
    o["effect_angular_rate"] = per_coefficient(r, b.effect_rate);
    o["share"] = per_coefficient(r, b.share, false);
    nlohmann::ordered_json sens = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < r.coefficients.size(); ++k)
      sens[r.coefficients[k]] = b.sensitivity[Eigen::Index(k)] * r.display_scale[k];
    o["sensitivity_per_si_unit"] = sens;
    if (b.paper_effect.size()) {
      o["paper_effect"] = per_coefficient(r, b.paper_effect);
      nlohmann::ordered_json d = nlohmann::ordered_json::object();
      for (std::size_t k = 0; k < r.coefficients.size(); ++k) d[r.coefficients[k]] = bool(b.disagrees[k]);
      o["exact_paper_disagree"] = d;
      if (!b.paper_counterpart) o["paper_counterpart"] = false;  // the drives' ripple: no paper rule
    }
    j["sources"].push_back(o);
  }
  j["correlation"] = nlohmann::ordered_json::array();
  for (Eigen::Index a = 0; a < r.correlation.rows(); ++a) {
    nlohmann::ordered_json jr = nlohmann::ordered_json::array();
    for (Eigen::Index b = 0; b < r.correlation.cols(); ++b) jr.push_back(r.correlation(a, b));
    j["correlation"].push_back(jr);
  }
  if (!r.rate_noise.empty()) {
    j["rate_noise"] = nlohmann::ordered_json::array();
    for (const RateNoiseBudget& n : r.rate_noise) {
      nlohmann::ordered_json runs = nlohmann::ordered_json::object();
      for (std::size_t i = 0; i < cfg.plan.runs.size(); ++i)
        runs[cfg.plan.runs[i].name] = n.run_sd[Eigen::Index(i)] * r.display_scale.front();
      j["rate_noise"].push_back({{"id", n.id},
                                 {"type", "A"},
                                 {"density_per_rtHz", n.density},
                                 {"run_mean_sd", runs},
                                 {"u", per_coefficient(r, n.effect)},
                                 {"share", per_coefficient(r, n.share, false)}});
    }
  }
  j["compensation_choices"] = nlohmann::ordered_json::array();
  for (const auto& c : r.compensation) {
    nlohmann::ordered_json o{
        {"id", c.id}, {"description", c.description}, {"bias", per_coefficient(r, c.bias)}};
    if (c.paper_bias.size()) o["paper_bias"] = per_coefficient(r, c.paper_bias);
    j["compensation_choices"].push_back(o);
  }
  j["observability"] = observability_json(observability);
  return j.dump(2) + "\n";
}

std::string csv_of(const Config& cfg, const BudgetResult& r) {
  std::string out = "rank,source,group,distribution,bound_si,unit_si,standard_uncertainty_si";
  for (std::size_t k = 0; k < r.coefficients.size(); ++k)
    out +=
        fmt::format(",d{0} [{1}],d{0}_force [{1}],d{0}_rate [{1}],share_{0}", r.coefficients[k], r.units[k]);
  out += "\n";
  for (std::size_t s : by_rank(r)) {
    const SourceBudget& b = r.sources[s];
    out += fmt::format(
        "{},{},{},{},{:.17g},{},{:.17g}", b.rank, b.id, b.group, distribution_name(b.distribution), b.bound,
        unit_symbol(cfg.centrifuge.layout.parameter_unit(b.parameter)), b.standard_uncertainty);
    for (std::size_t k = 0; k < r.coefficients.size(); ++k) {
      const auto i = Eigen::Index(k);
      out += fmt::format(",{:.17g},{:.17g},{:.17g},{:.17g}", b.effect[i] * r.display_scale[k],
                         b.effect_force[i] * r.display_scale[k], b.effect_rate[i] * r.display_scale[k],
                         b.share[i]);
    }
    out += "\n";
  }
  return out;
}

}  // namespace

std::string text(const verbs::BudgetResult& r) { return text_of(r.config, r.budget, r.observability); }
std::string json(const verbs::BudgetResult& r) { return json_of(r.config, r.budget, r.observability); }
std::string csv(const verbs::BudgetResult& r) { return csv_of(r.config, r.budget); }

}  // namespace ccal::render
