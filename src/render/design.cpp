// The reports of `ccal design` (render/design.hpp).
#include "ccal/render/design.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>

#include "budget_parts.hpp"
#include "ccal/core/constants.hpp"
#include "ccal/render/run_sheet.hpp"
#include "ccal/render/table.hpp"
#include "ccal/version.hpp"

namespace ccal::render {

namespace {

// U of coefficient k of a plan if run as written, in the budget's display unit: its expected statement's (by the
// budget's coefficient name), else the full budget's (a stated coverage factor).
double expected_u(const std::optional<verbs::CalibrationStatement>& st, const ccal::BudgetDetail& b, std::size_t k) {
  if (st)
    for (const CoefficientStatement& c : st->coefficients)
      if (c.input.coefficient == b.coefficients[k]) return c.expanded;
  return b.expanded_uncertainty[Eigen::Index(k)] * b.display_scale[k];
}

int credited_count(const verbs::CalibrationStatement& st) {
  int n = 0;
  for (const verbs::StatementSource& s : st.inputs) n += s.measured;
  return n;
}

std::string_view objective_name(DesignObjective o) { return design_objective_name(o); }

std::string plan_table(const Config& config) {
  Table t({"run", "g-level [g]", "duration [s]", "turns", "phi0 [deg]", "psi [deg]", "arm az. [deg]",
           "mounting", "platform"});
  // Turns, φ0 and ψ = γ(T) as the run sheet has them (model/run_sheet.hpp).
  const RunSheet sheet = run_sheet(config.plan, config.centrifuge.geometry, config.site);
  const double total = sheet.total_duration;
  for (const RunSheetLine& l : sheet.lines)
    t.add_row({l.run, number(l.g_level, 6), number(l.duration, 7), number(l.turns, 7),
               number(l.start_phase * constants::degrees_per_rad, 5),
               number(l.stop_phase * constants::degrees_per_rad, 5),
               number(l.arm_azimuth * constants::degrees_per_rad, 5), std::string(mounting_name(l.mounting)),
               std::string(platform_mode_name(l.mode))});
  return t.render() + fmt::format("  total {} s\n", number(total, 7));
}

std::string comparison_table(const verbs::DesignResult& r) {
  const ccal::BudgetDetail& b0 = r.before.budget;
  const ccal::BudgetDetail& b1 = r.after.budget;
  Table t({"coefficient", "unit", "u configured", "u designed", "U configured", "U designed", "ratio",
           "U tol. configured", "U tol. designed", "ratio"});
  for (std::size_t k = 0; k < b0.coefficients.size(); ++k) {
    const auto kk = Eigen::Index(k);
    const double f = b0.display_scale[k];
    const double ratio = b1.expanded_uncertainty[kk] / b0.expanded_uncertainty[kk];
    const double tol = r.tolerance_after[kk] / r.tolerance_before[kk];
    t.add_row({b0.coefficients[k] + (r.targets[k].weight > 0 ? " *" : ""), b0.units[k],
               number(b0.standard_uncertainty[kk] * f, 4), number(b1.standard_uncertainty[kk] * f, 4),
               number(b0.expanded_uncertainty[kk] * f, 4), number(b1.expanded_uncertainty[kk] * f, 4),
               number(ratio, 3), number(r.tolerance_before[kk] * f, 4), number(r.tolerance_after[kk] * f, 4),
               number(tol, 3)});
  }
  return t.render();
}

// The leading sources of a coefficient in the configured plan and in the designed one.
std::string leading_sources(const verbs::DesignResult& r, std::size_t k) {
  const ccal::BudgetDetail& b0 = r.before.budget;
  const ccal::BudgetDetail& b1 = r.after.budget;
  const auto kk = Eigen::Index(k);
  auto top = [&](const ccal::BudgetDetail& b) {
    std::vector<std::size_t> order(b.sources.size());
    for (std::size_t s = 0; s < order.size(); ++s) order[s] = s;
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t c) {
      return std::abs(b.sources[a].effect[kk]) > std::abs(b.sources[c].effect[kk]);
    });
    order.resize(std::min<std::size_t>(5, order.size()));
    return order;
  };
  const double f = b0.display_scale[k];
  Table t({"rank", "configured: source", "1-sigma effect", "share", "designed: source", "1-sigma effect", "share"});
  const auto a = top(b0), b = top(b1);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const SourceBudget& s0 = b0.sources[a[i]];
    const SourceBudget& s1 = b1.sources[b[i]];
    t.add_row({std::to_string(i + 1), s0.id, number(s0.effect[kk] * f, 3), number(s0.share[kk], 3), s1.id,
               number(s1.effect[kk] * f, 3), number(s1.share[kk], 3)});
  }
  return fmt::format("\nLeading sources of {} [{}]:\n", b0.coefficients[k], b0.units[k]) + t.render();
}

// The designed plan's U if run as written, per coefficient, with its coverage.
nlohmann::ordered_json expected_json(const verbs::DesignResult& r) {
  const ccal::BudgetDetail& b = r.after.budget;
  nlohmann::ordered_json expected = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < b.coefficients.size(); ++k)
    expected[b.coefficients[k]] = {{"unit", b.units[k]}, {"expanded", expected_u(r.expected_after, b, k)}};
  return {{"coverage_factor", b.coverage.factor},
          {"coverage_probability", b.coverage.probability},
          {"expected_if_run_as_written", expected}};
}

// The run sheet in the units it is printed in, with the resolution it is rounded to and its expected U.
nlohmann::ordered_json run_sheet_json(const verbs::DesignResult& r) {
  const SettingResolution res = setting_resolution(r.config.design);
  nlohmann::ordered_json lines = nlohmann::ordered_json::array();
  for (const RunSheetLine& l : r.sheet.lines)
    lines.push_back({{"order", l.order},
                     {"run", l.run},
                     {"g_level_g", l.g_level},
                     {"main_speed_rpm", l.main_rate / constants::rpm},
                     {"platform", platform_mode_name(l.mode)},
                     {"platform_speed_rpm", l.platform_rate / constants::rpm},
                     {"duration_s", l.duration},
                     {"turns", l.turns},
                     {"arm_azimuth_deg", l.arm_azimuth * constants::degrees_per_rad},
                     {"start_phase_deg", l.start_phase * constants::degrees_per_rad},
                     {"stop_phase_deg", l.stop_phase * constants::degrees_per_rad},
                     {"sets", l.terminal_phase ? "stop_phase" : "start_phase"},
                     {"mounting", mounting_name(l.mounting)},
                     {"mounting_axes", mounting_axes(l.mounting)}});
  nlohmann::ordered_json sheet = {{"resolution",
                                   {{"g_level_g", res.g},
                                    {"duration_s", res.duration},
                                    {"angle_deg", res.angle * constants::degrees_per_rad}}},
                                  {"runs", lines},
                                  {"total_duration_s", r.sheet.total_duration}};
  if (r.instruments.empty()) sheet.update(expected_json(r));  // a test of several: each instrument's
  return sheet;
}

// The designed plan's U if run as the sheet says (the plan as rounded), beside the configured plan's.
std::string expected_line(const verbs::DesignResult& r) {
  const ccal::BudgetDetail& b0 = r.before.budget;
  const ccal::BudgetDetail& b1 = r.after.budget;
  std::vector<std::string> designed, configured;
  for (std::size_t k = 0; k < b1.coefficients.size(); ++k) {
    designed.push_back(
        fmt::format("U({}) = {} {}", b1.coefficients[k], number(expected_u(r.expected_after, b1, k), 3), b1.units[k]));
    configured.push_back(number(expected_u(r.expected_before, b0, k), 3));
  }
  const std::string method =
      r.expected_after
          ? fmt::format("the calibration statement's method: Type A from the noise, Type B from {}, {}",
                        credited_count(*r.expected_after) == 0
                            ? std::string("the tolerances (no encoders declared)")
                            : fmt::format("the inputs, {} of them measured by the declared encoders",
                                          credited_count(*r.expected_after)),
                        coverage_text(b1.coverage))
                       : fmt::format("full budget of the sheet's values, {}", coverage_text(b1.coverage));
  return wrap_words(fmt::format("Expected if run as written ({}): {} (configured plan: {})", method,
                                fmt::join(designed, ", "), fmt::join(configured, ", ")),
                    110, "  ");
}

}  // namespace

namespace {

// The objective's line: what it counts, with each coefficient's weight and reference.
std::string objective_line(const verbs::DesignResult& r) {
  std::vector<std::string> counted;
  for (const auto& t : r.targets)
    if (t.weight > 0)
      counted.push_back(fmt::format("{} (w = {}, {} = {})", t.coefficient, number(t.weight, 3),
                                    t.is_target ? "target" : "reference", number(t.reference * r.before.budget.display_scale[&t - r.targets.data()], 4)));
  return fmt::format("Objective: {} of {}\n", objective_name(r.objective), fmt::join(counted, ", "));
}

// The design space, the objective (`objective`: its line), the search, the plans and the run sheet.
std::string head_text(const verbs::DesignResult& r, const std::string& title, const std::string& objective) {
  std::string out = title + "\n\nDesign space\n";
  for (const auto& s : r.space.free) out += "  free:  " + s + "\n";
  for (const auto& s : r.space.fixed) out += "  kept:  " + s + "\n";
  out += objective;
  out += fmt::format(
      "Search: {} candidate runs {} in {} s; {} plans scored, {} runs refined in {} s; best from start {}\n",
      r.candidates, r.candidates_from_cache ? "read from the cache" : "cached", number(r.cache_seconds, 3),
      r.search.evaluations, r.search.row_evaluations, number(r.search_seconds, 3), r.search.start + 1);
  out += fmt::format("Objective: configured {}, designed {} (grid {})\n\n", number(r.configured_objective, 6),
                     number(r.designed_objective, 6), number(r.search.grid_objective, 6));
  out += "Configured plan\n" + plan_table(r.config) + "\nDesigned plan\n" + plan_table(r.designed);
  return out + "\nRun sheet: the designed plan as the operator runs it\n" +
         text(r.sheet, setting_resolution(r.config.design));
}

// One instrument's plans compared: full budgets, leading sources, the mechanism, the trade-off, the Monte Carlo.
std::string comparison_text(const verbs::DesignResult& r) {
  std::string out =
      fmt::format("\nConfigured against designed (full budget, {}; 'U tol.': the tolerances alone; * counted)\n",
                  coverage_text(r.before.budget.coverage));
  out += comparison_table(r);
  for (std::size_t k = 0; k < r.targets.size(); ++k)
    if (r.targets[k].weight > 0) out += leading_sources(r, k);
  if (!r.mechanism.empty()) {
    out += "\nMechanism\n";
    for (std::size_t start = 0; start < r.mechanism.size();) {
      const std::size_t end = std::min(r.mechanism.find('\n', start), r.mechanism.size());
      out += wrap_words(std::string_view(r.mechanism).substr(start, end - start), 110, "  ");
      start = end + 1;
    }
  }
  if (!r.tradeoff.empty()) {
    std::vector<std::string> header{"total time [s]", "used [s]"};
    for (std::size_t k = 0; k < r.targets.size(); ++k)
      header.push_back("U " + r.targets[k].coefficient);
    Table curve(header);
    for (const auto& p : r.tradeoff) {
      std::vector<std::string> row{number(p.total_time, 6), number(p.used_time, 6)};
      for (std::size_t k = 0; k < r.targets.size(); ++k)
        row.push_back(number(p.expanded[Eigen::Index(k)] * r.before.budget.display_scale[k], 4));
      curve.add_row(row);
    }
    out += "\nTrade-off: total test time against U (full budget of each designed plan)\n" + curve.render();
  }
  if (r.verification) {
    const auto& mc = r.verification->monte_carlo;
    out += fmt::format("\nMonte Carlo check of the designed plan ({} trials): u by Monte Carlo / u by LPU:", mc.trials);
    for (std::size_t k = 0; k < r.after.budget.coefficients.size(); ++k) {
      const auto kk = Eigen::Index(k);
      out += fmt::format(" {} {}", r.after.budget.coefficients[k],
                         number(mc.outputs[k].std_dev / mc.outputs[k].lpu_std, 4));
      (void)kk;
    }
    out += "\n";
  }
  return out;
}

}  // namespace


std::string text(const verbs::DesignResult& r) {
  if (r.instruments.empty())
    return head_text(r, fmt::format("Test-plan design (docs/model.md §15) of {}", r.config.source),
                     objective_line(r)) +
           expected_line(r) + comparison_text(r);
  // A test of several instruments: the one plan, then each instrument's objective and budgets.
  std::vector<std::string> ids;
  for (const verbs::DesignResult& one : r.instruments) ids.push_back(one.config.instrument_id);
  std::string out = head_text(
      r,
      fmt::format("Test-plan design (docs/model.md §15) of {}: one plan for its {} instruments ({}), run together",
                  r.config.source, r.instruments.size(), fmt::join(ids, ", ")),
      wrap_words(fmt::format("Objective: {}, each instrument's (below); the plan's: {} (§15.4)",
                             objective_name(r.objective),
                             r.objective == DesignObjective::d_optimal
                                 ? "the sum of the instruments' objectives"
                                 : "the largest of the instruments' objectives, each divided by the sum of its "
                                   "weights (1: every counted U at its reference)"),
                 110, ""));
  for (const verbs::DesignResult& one : r.instruments)
    out += fmt::format("\n=== instrument {} ===\n", one.config.instrument_id) + objective_line(one) +
           fmt::format("Objective: configured {}, designed {}\n", number(one.configured_objective, 6),
                       number(one.designed_objective, 6)) +
           expected_line(one) + comparison_text(one);
  return out;
}

namespace {

// The designed plan's runs: g-level, duration, the initial and terminal phase and the arm's azimuth (rad).
nlohmann::ordered_json designed_runs_json(const verbs::DesignResult& r) {
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (const Run& run : r.designed.plan.runs) {
    nlohmann::ordered_json o;
    o["name"] = run.name;
    o["g_level_g"] = run.g_level;
    o["duration_s"] = run.duration;
    o["initial_phase_rad"] = initial_phase(run, r.designed.centrifuge.geometry, r.designed.site);
    if (run.terminal_phase) o["terminal_phase_rad"] = *run.terminal_phase;
    o["arm_azimuth_rad"] = run.arm_azimuth;
    o["mounting"] = mounting_name(run.mounting);
    o["platform"] = platform_mode_name(run.mode);
    runs.push_back(o);
  }
  return runs;
}

// Per coefficient in its display unit: its weight and reference in the objective, u and U of the configured
// and the designed plan by the full budget, and U of the tolerances alone.
nlohmann::ordered_json design_coefficients_json(const verbs::DesignResult& r) {
  nlohmann::ordered_json coefficients = nlohmann::ordered_json::object();
  const ccal::BudgetDetail& b0 = r.before.budget;
  const ccal::BudgetDetail& b1 = r.after.budget;
  for (std::size_t k = 0; k < b0.coefficients.size(); ++k) {
    const auto kk = Eigen::Index(k);
    const double f = b0.display_scale[k];
    nlohmann::ordered_json o;
    o["unit"] = b0.units[k];
    o["weight"] = r.targets[k].weight;
    o["reference"] = r.targets[k].reference * f;
    o["is_target"] = r.targets[k].is_target;
    o["configured_std_uncertainty"] = b0.standard_uncertainty[kk] * f;
    o["designed_std_uncertainty"] = b1.standard_uncertainty[kk] * f;
    o["configured_expanded"] = b0.expanded_uncertainty[kk] * f;
    o["designed_expanded"] = b1.expanded_uncertainty[kk] * f;
    o["configured_tolerance_expanded"] = r.tolerance_before[kk] * f;
    o["designed_tolerance_expanded"] = r.tolerance_after[kk] * f;
    coefficients[b0.coefficients[k]] = o;
  }
  return coefficients;
}

// The trade-off curve: per total time limit, the time the plan uses and each coefficient's U (display unit).
nlohmann::ordered_json design_tradeoff_json(const verbs::DesignResult& r) {
  const ccal::BudgetDetail& b0 = r.before.budget;
  nlohmann::ordered_json curve = nlohmann::ordered_json::array();
  for (const auto& p : r.tradeoff) {
    nlohmann::ordered_json o;
    o["total_time_s"] = p.total_time;
    o["used_time_s"] = p.used_time;
    nlohmann::ordered_json u = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < b0.coefficients.size(); ++k)
      u[b0.coefficients[k]] = p.expanded[Eigen::Index(k)] * b0.display_scale[k];
    o["expanded"] = u;
    curve.push_back(o);
  }
  return curve;
}

// The Monte Carlo check of the designed plan: M, and per coefficient its u against the LPU's.
nlohmann::ordered_json design_verification_json(const verbs::DesignResult& r) {
  const ccal::BudgetDetail& b1 = r.after.budget;
  nlohmann::ordered_json v = nlohmann::ordered_json::object();
  const auto& mc = r.verification->monte_carlo;
  v["trials"] = mc.trials;
  for (std::size_t k = 0; k < b1.coefficients.size(); ++k)
    v[b1.coefficients[k]] = {{"mc_std_uncertainty", mc.outputs[k].std_dev * b1.display_scale[k]},
                             {"lpu_std_uncertainty", mc.outputs[k].lpu_std * b1.display_scale[k]}};
  return v;
}

nlohmann::ordered_json json_object(const verbs::DesignResult& r) {
  nlohmann::ordered_json j;
  j["command"] = "design";
  j["ccal_version"] = version();
  j["config"] = r.config.source;
  j["objective"] = objective_name(r.objective);
  j["candidates"] = r.candidates;
  j["free"] = r.space.free;
  j["kept"] = r.space.fixed;
  j["total_time_limit_s"] = r.space.total_time;
  j["objective_value"] = {{"configured", r.configured_objective},
                          {"designed", r.designed_objective},
                          {"grid", r.search.grid_objective}};
  j["search"] = {
      {"starts", r.search.start_objectives.size()}, {"best_start", r.search.start + 1},
      {"plans_scored", r.search.evaluations},       {"runs_refined", r.search.row_evaluations},
      {"cache_seconds", r.cache_seconds},           {"candidates_from_cache", r.candidates_from_cache},
      {"search_seconds", r.search_seconds}};
  j["designed_plan"] = designed_runs_json(r);
  j["run_sheet"] = run_sheet_json(r);
  j["coefficients"] = design_coefficients_json(r);
  j["mechanism"] = r.mechanism;
  j["tradeoff"] = design_tradeoff_json(r);
  if (r.verification) j["verification"] = design_verification_json(r);
  return j;
}

}  // namespace

std::string json(const verbs::DesignResult& r) {
  if (r.instruments.empty()) return json_object(r).dump(2) + "\n";
  // A test of several instruments: the one plan and the search as for one; per instrument, its objective, its
  // coefficients before and after, its expected U, its mechanism and its Monte Carlo check.
  nlohmann::ordered_json j = json_object(r);
  for (const char* key : {"coefficients", "mechanism", "tradeoff"}) j.erase(key);
  j["joint_objective"] = r.objective == DesignObjective::d_optimal
                             ? "the sum of the instruments' objectives"
                             : "the largest of the instruments' objectives, each divided by the sum of its weights";
  nlohmann::ordered_json each = nlohmann::ordered_json::array();
  for (const verbs::DesignResult& one : r.instruments) {
    const nlohmann::ordered_json whole = json_object(one);
    nlohmann::ordered_json x;
    x["id"] = one.config.instrument_id;
    x["objective_value"] = {{"configured", one.configured_objective}, {"designed", one.designed_objective}};
    x.update(expected_json(one));
    for (const char* key : {"coefficients", "mechanism", "verification"})
      if (whole.contains(key)) x[key] = whole[key];
    each.push_back(std::move(x));
  }
  j["instruments"] = std::move(each);
  return j.dump(2) + "\n";
}

// The run sheet, one row per run in the order it is run, with the columns of the JSON's run_sheet.runs (speeds
// in rpm, durations in s, angles in degrees, as rounded to the settings' resolution), so that the operator's
// sheet and a spreadsheet read the same numbers; shortest digits that read back as the same doubles.
std::string csv(const verbs::DesignResult& r) {
  const nlohmann::ordered_json runs = run_sheet_json(r)["runs"];
  if (runs.empty()) return "";
  std::string out;
  for (const auto& [key, value] : runs.front().items()) {
    if (!out.empty()) out += ',';
    out += key;
  }
  out += '\n';
  for (const auto& run : runs) {
    bool first = true;
    for (const auto& [key, value] : run.items()) {
      if (!first) out += ',';
      first = false;
      out += budget_parts::csv_field(value.is_string() ? value.get<std::string>() : value.dump());
    }
    out += '\n';
  }
  return out;
}

}  // namespace ccal::render
