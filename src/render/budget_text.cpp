// The text of `ccal budget`: the answer per coefficient in one line, then a GUM budget table per coefficient
// (source, name, tolerance, distribution and divisor, u(x_i), c_i, u_i(y), share; round-off below the floor
// as 0) with its largest sources and the rest summed, the bias of known errors, and what to do next; --wide
// adds the type, x_i, ν_i and the unit of c_i (every column of EA-4/02) and everything else.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "budget_parts.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/intake/measured_inputs.hpp"
#include "ccal/render/budget.hpp"
#include "ccal/render/table.hpp"
#include "parts.hpp"

namespace ccal::render {
namespace {

using namespace budget_parts;

std::string percent(double share) { return fmt::format("{:.1f} %", 100 * share); }

std::string heading(const Config& cfg, const ccal::BudgetDetail& r, std::size_t width) {
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
std::string answer(const ccal::BudgetDetail& r, std::size_t width) {
  std::string out = "The answer (the sources that make 90 % of each u²):\n";
  for (std::size_t k = 0; k < r.coefficients.size(); ++k) {
    const auto i = Eigen::Index(k);
    std::vector<std::string> items;
    for (const Contribution& c : answer_contributions(r, k))
      items.push_back(fmt::format("{} {}", c.label, percent(c.share)));
    out += wrap_items(fmt::format("  {}: U = {} {};", r.coefficients[k],
                                  number(r.expanded_uncertainty[i] * r.display_scale[k], 4), r.units[k]),
                      items, width == 0 ? std::size_t(-1) : width, "      ");
  }
  out += '\n';
  return out;
}

// A number of a table, or "0" for a contribution below the round-off floor (and its c_i).
std::string shown(double value, bool round_off) { return round_off ? "0" : number(value, 4); }

std::string with_unit(double value, const std::string& unit) {
  return fmt::format("{} {}", number(value, 4), unit);
}

// The cells of one line. The compact table (the default): source, name, tolerance, PDF, divisor, u(x_i), c_i,
// u_i(y), share, within 100 columns; a type column would leave the names 4 characters there, so a rate
// noise's name says "Type A" (every other line is a tolerance, Type B). --wide: every column of EA-4/02
// (type, x_i, ν_i, the unit of c_i) and the exact-vs-paper flag.
std::vector<std::string> cells_of(const ccal::BudgetDetail& r, std::size_t k, const BudgetLine& l, bool wide,
                                  bool paper) {
  const std::string contribution = l.round_off   ? "0"
                                   : l.tolerance ? number(l.contribution, 4)
                                                 : fmt::format("±{}", number(l.contribution, 4));
  const std::string share = l.round_off ? "0 %" : percent(l.share);
  if (!wide)
    return {l.source,
            l.x.type == 'A' ? fmt::format("Type A: {}", l.x.name) : l.x.name,
            with_unit(l.x.bound, l.x.unit),
            l.distribution,
            divisor_text(l.x.divisor),
            number(l.x.u, 4),
            shown(l.sensitivity, l.round_off),
            contribution,
            share};
  std::vector<std::string> cells = {l.source,
                                    l.x.name,
                                    std::string(1, l.x.type),
                                    with_unit(l.x.estimate, l.x.unit),
                                    with_unit(l.x.bound, l.x.unit),
                                    l.distribution,
                                    divisor_text(l.x.divisor),
                                    number(l.x.u, 4),
                                    std::isinf(l.x.dof) ? "∞" : number(l.x.dof, 4),
                                    shown(l.sensitivity, l.round_off),
                                    sensitivity_unit(r, k, l.x),
                                    contribution,
                                    share};
  if (paper)
    cells.push_back(!l.tolerance || !l.tolerance->paper_counterpart ? "no paper rule"
                    : l.tolerance->disagrees[k]                     ? "differ"
                                                                    : "agree");
  return cells;
}

std::string coefficient_table(const verbs::BudgetResult& v, std::size_t k, std::size_t top,
                              const BudgetTextOptions& o) {
  const Config& cfg = v.config;
  const ccal::BudgetDetail& r = v.budget;
  const auto i = Eigen::Index(k);
  const double u = r.standard_uncertainty[i] * r.display_scale[k];
  const bool paper =
      o.wide && r.mode == ModelMode::exact && !r.sources.empty() && r.sources.front().paper_effect.size();
  std::string out =
      fmt::format("{} [{}]: u = {}, U = {} ({})\n", r.coefficients[k], r.units[k], number(u, 4),
                  number(r.expanded_uncertainty[i] * r.display_scale[k], 4), coverage_text(r.coverage));
  std::vector<std::string> header =
      o.wide ? std::vector<std::string>{"source", "name", "type", "x_i",         "tolerance", "PDF",  "÷",
                                        "u(x_i)", "ν_i",  "c_i",  "unit of c_i", "u_i(y)",    "share"}
             : std::vector<std::string>{"source", "name", "tolerance", "PDF",  "÷",
                                        "u(x_i)", "c_i",  "u_i(y)",    "share"};
  if (paper) header.push_back("exact vs paper");
  // The spanning rows' cells: the label over source and name, blanks up to u_i(y) (column 11 or 7), its
  // value and the share.
  const std::size_t blanks = (o.wide ? 11 : 7) - 2;
  const auto spanning = [&](std::string label, std::string value, std::string share) {
    std::vector<std::string> cells(1, std::move(label));
    cells.resize(1 + blanks);
    cells.push_back(std::move(value));
    cells.push_back(std::move(share));
    return cells;
  };
  Table table(header);
  table.align_left(1);
  if (o.wide) table.align_left(10);
  table.gap(2);
  if (!o.wide) {
    table.shrink(1);
    table.optional(4);  // ÷: tolerance / u(x_i); a 90-column terminal leaves it out
  }
  const std::vector<BudgetLine> lines = budget_lines(cfg, r, k);
  const std::size_t shown_lines = o.wide ? lines.size() : std::min(top, lines.size());
  for (std::size_t s = 0; s < shown_lines; ++s) table.add_row(cells_of(r, k, lines[s], o.wide, paper));
  if (shown_lines < lines.size()) {
    double share = 0, variance = 0;  // of the lines above the round-off floor
    for (std::size_t s = shown_lines; s < lines.size(); ++s)
      if (!lines[s].round_off) {
        share += lines[s].share;
        variance += lines[s].contribution * lines[s].contribution;
      }
    table.add_spanning_row(spanning(fmt::format("{} more, root-sum-square", lines.size() - shown_lines),
                                    number(std::sqrt(variance), 4), percent(share)));
  }
  table.add_rule();
  table.add_spanning_row(spanning("u: combined standard uncertainty", number(u, 4), ""));
  table.add_spanning_row(spanning(fmt::format("U: expanded uncertainty, {}", coverage_text(r.coverage)),
                                  number(r.expanded_uncertainty[i] * r.display_scale[k], 4), ""));
  if (v.known_error_bias.size())
    table.add_spanning_row(spanning("bias of known [errors], not compensated, not in u",
                                    number(v.known_error_bias[i] * r.display_scale[k], 4), ""));
  out += table.render("  ", o.wide ? 0 : o.width);
  return out;
}

std::string quoted_config(const Config& cfg) {
  if (cfg.source == kBundledExampleName) return "";
  return cfg.source.find_first_of(" '\"") == std::string::npos ? " " + cfg.source : " '" + cfg.source + "'";
}

// What to do next, with the coefficient of the largest U relative to its configured value as the example
// (U itself where that value is 0; coefficients of different units are compared only through the ratio).
std::string next_steps(const Config& cfg, const ccal::BudgetDetail& r) {
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
  // An instrument of a test of several: allocate and montecarlo answer for one instrument; design for all.
  if (cfg.instruments.empty() && !cfg.instrument_id.empty())
    return fmt::format("Next: a test plan that sees {} better, for every instrument:  ccal design{}\n", id, c);
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
  if (!v.instruments.empty()) {  // a test of several: each instrument's budget, then their correlation
    std::string out = fmt::format("ccal budget: a test of {} instruments ({})\n\n", v.instruments.size(),
                                  v.config.source);
    for (const verbs::BudgetResult& one : v.instruments)
      out += fmt::format("=== instrument {} ===\n", one.config.instrument_id) + text(one, o) + "\n";
    if (v.covariance) out += covariance_text(*v.covariance);
    return out;
  }
  const Config& cfg = v.config;
  const ccal::BudgetDetail& r = v.budget;
  const std::size_t nk = std::max<std::size_t>(1, r.coefficients.size());
  // A screen: the heading (4 lines), the answer (nk + 2), per coefficient its title, header, rules, the
  // rest, u, U and the bias (8) and a blank line, the next steps (3).
  const std::size_t fixed = 4 + nk + 2 + 9 * nk + 3;
  const std::size_t top =
      o.top > 0 ? o.top : std::max<std::size_t>(5, o.screen_rows > fixed ? (o.screen_rows - fixed) / nk : 0);
  std::string out = heading(cfg, r, o.wide ? 0 : o.width);
  out += answer(r, o.width);
  out +=
      wrap_words(
          fmt::format("Per coefficient, a GUM budget (JCGM 100; {}): {}the tolerance as configured, PDF and "
                      "divisor ÷, u(x_i) = tolerance/÷ in its unit, c_i per that unit, u_i(y) = c_i u(x_i) "
                      "(signed), share of u²; tolerances are Type B, rate noise Type A, ν_i = ∞; |u_i(y)| < "
                      "{:g} u is round-off, shown as 0{}.",
                      o.wide ? "EA-4/02's columns" : "EA-4/02's columns with --wide",
                      o.wide ? "x_i the [errors] value (where c_i is evaluated), " : "", kRoundOffFloor,
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
  // Before a test the tolerances stand; what the declared encoders will measure is said, with its consequence.
  if (const std::vector<MeasuredInput> m = expected_measured_inputs(cfg); !m.empty()) {
    std::vector<std::string> ids;
    for (const MeasuredInput& x : m) ids.push_back(x.id);
    out += wrap_words(fmt::format("A test with the declared encoders ([centrifuge] encoders) measures {}: its "
                                  "calibration statement charges those measurements instead of the tolerances "
                                  "above (docs/model.md §13.3), as `ccal design`'s expected U does.",
                                  fmt::join(ids, ", ")),
                      o.wide ? 0 : o.width);
  }
  out += next_steps(cfg, r);
  return out;
}

namespace {

// --wide: the paths of each source, the compensation choices, the exact-vs-paper count, observability.
std::string wide_sections(const verbs::BudgetResult& v) {
  const ccal::BudgetDetail& r = v.budget;
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
