// The text of `ccal budget`: the answer per coefficient in one line, then a JCGM 100 table per coefficient
// (source, name, tolerance, distribution, u(x_i), c_i, u_i(y), share) with its largest sources and the rest
// summed, the bias of known errors, and what to do next; --wide adds everything else.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "budget_parts.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/render/budget.hpp"
#include "ccal/render/table.hpp"
#include "parts.hpp"

namespace ccal::render {
namespace {

using namespace budget_parts;

std::string percent(double share) { return fmt::format("{:.1f} %", 100 * share); }

std::string heading(const Config& cfg, const ccal::BudgetResult& r, std::size_t width) {
  std::vector<std::string> fixed;
  for (const auto& [id, v] : cfg.identification.fixed_terms) fixed.push_back(id);
  std::string out = fmt::format("ccal budget: {}\n", cfg.source);
  out += wrap_words(
      fmt::format("{} mode, {} runs, {} sources{}; identified {}{}", mode_name(r.mode), cfg.plan.runs.size(),
                  r.sources.size(),
                  r.rate_noise.empty() ? "" : fmt::format(" and {} drive rate noise(s)", r.rate_noise.size()),
                  fmt::join(r.coefficients, ", "),
                  fixed.empty() ? "" : fmt::format("; {} fixed", fmt::join(fixed, ", "))),
      width);
  out += wrap_words(fmt::format("Effects are 1-sigma, shares are of the variance u²; U = k u, {} (the LPU "
                                "total, normal).",
                                coverage_text(r.coverage)),
                    width);
  out += '\n';
  return out;
}

// Items joined by ", " after a prefix, broken between items (never inside one) before `width` columns.
std::string wrap_items(std::string line, const std::vector<std::string>& items, std::size_t width,
                       const std::string& indent) {
  std::string out;
  for (std::size_t n = 0; n < items.size(); ++n) {
    const std::string item = items[n] + (n + 1 < items.size() ? "," : "");
    if (display_width(line) + 1 + display_width(item) > width && display_width(line) > indent.size()) {
      out += line;
      out += '\n';
      line = indent + item;
    } else {
      line += ' ';
      line += item;
    }
  }
  out += line;
  out += '\n';
  return out;
}

// "K3: U = 0.04702 deg/s/g^3; ripple1_c1 54.2 %, ripple1_s1 43.8 %"
std::string answer(const ccal::BudgetResult& r, std::size_t width) {
  std::string out = "The answer (the sources that make 90 % of each u²):\n";
  for (std::size_t k = 0; k < r.coefficients.size(); ++k) {
    const auto i = Eigen::Index(k);
    std::vector<std::string> items;
    double sum = 0;
    for (const Contribution& c : contributions(r, k)) {
      if (sum >= 0.9) break;
      sum += c.share;
      items.push_back(fmt::format("{} {}", c.label, percent(c.share)));
    }
    out += wrap_items(fmt::format("  {}: U = {} {};", r.coefficients[k],
                                  number(r.expanded_uncertainty[i] * r.display_scale[k], 4), r.units[k]),
                      items, width == 0 ? std::size_t(-1) : width, "      ");
  }
  out += '\n';
  return out;
}

// One row of a coefficient's table: a source, or a drive's rate noise (Type A, no sign).
struct Row {
  std::vector<std::string> cells;
  double share = 0;
  double effect = 0;  // signed u_i(y) in the display unit
};

std::vector<Row> rows_of(const Config& cfg, const ccal::BudgetResult& r, std::size_t k, bool paper) {
  const auto i = Eigen::Index(k);
  std::vector<Row> rows;
  for (const SourceBudget& s : r.sources) {
    const SourceView v = source_view(cfg, s);
    const double effect = s.effect[i] * r.display_scale[k];
    Row row{{source_label(s.id, s.group), v.name, fmt::format("{} {}", number(v.bound, 4), v.unit),
             std::string(distribution_name(s.distribution)), number(v.u, 4),
             number(sensitivity_per_unit(r, s, v, k), 4), number(effect, 4), percent(s.share[i])},
            s.share[i],
            effect};
    if (paper)
      row.cells.push_back(!s.paper_counterpart ? "no paper rule" : s.disagrees[k] ? "differ" : "agree");
    rows.push_back(std::move(row));
  }
  for (const RateNoiseBudget& n : r.rate_noise) {
    const double effect = n.effect[i] * r.display_scale[k];
    const double density = n.density * 1e6;  // ppm/rtHz
    Row row{
        {n.id, "Type A: the drive's random rate noise, independent per run", number(density, 4) + " ppm/rtHz",
         "normal", number(density, 4), number(density > 0 ? effect / density : 0.0, 4),
         fmt::format("±{}", number(effect, 4)), percent(n.share[i])},
        n.share[i],
        effect};
    if (paper) row.cells.push_back("no paper rule");
    rows.push_back(std::move(row));
  }
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) { return a.share > b.share; });
  return rows;
}

std::string coefficient_table(const verbs::BudgetResult& v, std::size_t k, std::size_t top,
                              const BudgetTextOptions& o) {
  const Config& cfg = v.config;
  const ccal::BudgetResult& r = v.budget;
  const auto i = Eigen::Index(k);
  const double u = r.standard_uncertainty[i] * r.display_scale[k];
  const bool paper =
      o.wide && r.mode == ModelMode::exact && !r.sources.empty() && r.sources.front().paper_effect.size();
  std::string out =
      fmt::format("{} [{}]: u = {}, U = {} ({})\n", r.coefficients[k], r.units[k], number(u, 4),
                  number(r.expanded_uncertainty[i] * r.display_scale[k], 4), coverage_text(r.coverage));
  std::vector<std::string> header = {"source", "name", "tolerance", "PDF",
                                     "u(x_i)", "c_i",  "u_i(y)",    "share"};
  if (paper) header.push_back("exact vs paper");
  Table table(header);
  table.align_left(1);
  table.gap(2);
  if (!o.wide) table.shrink(1);
  const std::vector<Row> rows = rows_of(cfg, r, k, paper);
  const std::size_t shown = o.wide ? rows.size() : std::min(top, rows.size());
  for (std::size_t s = 0; s < shown; ++s) table.add_row(rows[s].cells);
  if (shown < rows.size()) {
    double share = 0, variance = 0;
    for (std::size_t s = shown; s < rows.size(); ++s) {
      share += rows[s].share;
      variance += rows[s].effect * rows[s].effect;
    }
    table.add_spanning_row({fmt::format("{} more, root-sum-square", rows.size() - shown), "", "", "", "",
                            number(std::sqrt(variance), 4), percent(share)});
  }
  table.add_rule();
  table.add_spanning_row({"u: combined standard uncertainty", "", "", "", "", number(u, 4), ""});
  table.add_spanning_row({fmt::format("U: expanded uncertainty, {}", coverage_text(r.coverage)), "", "", "", "",
                          number(r.expanded_uncertainty[i] * r.display_scale[k], 4), ""});
  if (v.known_error_bias.size())
    table.add_spanning_row({"bias of known [errors], not compensated, not in u", "", "", "", "",
                            number(v.known_error_bias[i] * r.display_scale[k], 4), ""});
  out += table.render("  ", o.wide ? 0 : o.width);
  return out;
}

std::string quoted_config(const Config& cfg) {
  if (cfg.source == kBundledExampleName) return "";
  return cfg.source.find_first_of(" '\"") == std::string::npos ? " " + cfg.source : " '" + cfg.source + "'";
}

// What to do next, with the coefficient of the largest U relative to its configured value as the example
// (U itself where that value is 0; coefficients of different units are compared only through the ratio).
std::string next_steps(const Config& cfg, const ccal::BudgetResult& r) {
  const auto relative = [&](std::size_t k) {
    const double U = r.expanded_uncertainty[Eigen::Index(k)];
    const double value = std::abs(cfg.instrument.coefficient(r.coefficients[k]).value_or(0.0));
    return value > 0 ? U / value : U * r.display_scale[k];
  };
  std::size_t worst = 0;
  for (std::size_t k = 1; k < r.coefficients.size(); ++k)
    if (relative(k) > relative(worst)) worst = k;
  const std::string c = quoted_config(cfg);
  const std::string& id = r.coefficients[worst];
  const double half = r.expanded_uncertainty[Eigen::Index(worst)] * r.display_scale[worst] / 2;
  const std::string labels[] = {
      "tolerances for a smaller U:", fmt::format("a test plan that sees {} better:", id),
      "the LPU checked by Monte Carlo:"};
  std::size_t w = 0;
  for (const std::string& l : labels) w = std::max(w, display_width(l));
  return fmt::format(
      "Next: {}  ccal allocate{} --target {}={}\n      {}  ccal design{}\n      {}  ccal montecarlo{} "
      "--digits 2\n",
      pad_to_width(labels[0], w, true), c, id, number(half, 2), pad_to_width(labels[1], w, true), c,
      pad_to_width(labels[2], w, true), c);
}

std::string wide_sections(const verbs::BudgetResult& v);

}  // namespace

std::string text(const verbs::BudgetResult& v, const BudgetTextOptions& o) {
  const Config& cfg = v.config;
  const ccal::BudgetResult& r = v.budget;
  const std::size_t nk = std::max<std::size_t>(1, r.coefficients.size());
  // A screen: the heading (4 lines), the answer (nk + 2), per coefficient its title, header, rules, the
  // rest, u, U and the bias (8) and a blank line, the next steps (3).
  const std::size_t fixed = 4 + nk + 2 + 9 * nk + 3;
  const std::size_t top =
      o.top > 0 ? o.top : std::max<std::size_t>(5, o.screen_rows > fixed ? (o.screen_rows - fixed) / nk : 0);
  std::string out = heading(cfg, r, o.wide ? 0 : o.width);
  out += answer(r, o.width);
  out +=
      wrap_words(fmt::format("Per coefficient: the tolerance as configured and its PDF (distribution), "
                             "u(x_i) in the tolerance's unit, c_i in the coefficient's unit per that unit, "
                             "u_i(y) = c_i u(x_i) (signed), share = u_i(y)²/u²{}.",
                             o.wide ? "" : fmt::format("; the {} largest sources, the rest in one row", top)),
                 o.wide ? 0 : o.width) +
      "\n";
  for (std::size_t k = 0; k < r.coefficients.size(); ++k) {
    out += coefficient_table(v, k, top, o);
    out += '\n';
  }
  for (const auto& w : v.observability.warnings)
    out += wrap_words("warning: " + w, o.wide ? 0 : o.width, "  ");
  if (o.wide) out += wide_sections(v);
  out += next_steps(cfg, r);
  return out;
}

namespace {

// --wide: the paths of each source, the compensation choices, the exact-vs-paper count, observability.
std::string wide_sections(const verbs::BudgetResult& v) {
  const ccal::BudgetResult& r = v.budget;
  const auto nk = r.coefficients.size();
  std::string out;
  std::vector<std::string> rate_header = {"source", "path"};
  for (std::size_t k = 0; k < nk; ++k)
    rate_header.push_back(fmt::format("d{} [{}]", r.coefficients[k], r.units[k]));
  Table paths(rate_header);
  int with_rate = 0;
  for (const SourceBudget& b : r.sources) {
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
  if (with_rate) {
    out += "Sources whose angular-rate path reaches 1e-3 of a total (1-sigma effects by path):\n";
    out += paths.render();
    out += '\n';
  }
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
    out += "Compensation choices (systematic biases, not in the totals; model them to remove them):\n";
    out += comp.render();
    out += '\n';
  }
  if (r.mode == ModelMode::exact && !r.sources.empty() && r.sources.front().paper_effect.size()) {
    int flagged = 0;
    for (const auto& b : r.sources) flagged += std::count(b.disagrees.begin(), b.disagrees.end(), true) > 0;
    out += fmt::format(
        "{} source(s) differ between the exact model and the paper's first-order rules by more than a "
        "factor of 2 (or in sign) on at least one coefficient; see docs/model.md §10.\n\n",
        flagged);
  }
  out += observability_text(v.observability);
  out += '\n';
  return out;
}

}  // namespace
}  // namespace ccal::render
