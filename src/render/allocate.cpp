#include "ccal/render/allocate.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "budget_parts.hpp"
#include "ccal/core/units.hpp"
#include "ccal/render/table.hpp"
#include "ccal/setup/input_description.hpp"
#include "ccal/version.hpp"
#include "text_lines.hpp"

namespace ccal::render {
namespace {

using budget_parts::source_label;


// v rounded down to 4 significant digits, so that a pasted tolerance is never looser than the allocated one.
double round_down(double v) {
  if (!(v > 0) || !std::isfinite(v)) return v;
  const double step = std::pow(10.0, std::floor(std::log10(v)) - 3);
  const double r = std::floor(v / step * (1 + 1e-15)) * step;
  return r > v ? v : r;
}

std::string quantity_text(const Config& cfg, int parameter, double si, const std::string& unit) {
  return input_quantity_text(describe_input(cfg, parameter), round_down(si), unit);
}

// One [tolerances] entry for the allocated tolerance (defaults left out), in the unit it was written in.
std::string toml_entry(const AllocatedSource& s, const Config& cfg) {
  const std::string bound = quantity_text(cfg, s.parameter, s.allocated_bound, tolerance_display_unit(cfg, s.parameter));
  if (s.distribution == Distribution::normal && s.group.empty() && s.cost == 1.0 && s.floor == 0)
    return fmt::format("{} = \"{}\"", s.id, bound);
  std::string e = fmt::format("{} = {{ bound = \"{}\"", s.id, bound);
  if (s.distribution != Distribution::normal)
    e += fmt::format(", distribution = \"{}\"", distribution_name(s.distribution));
  if (!s.group.empty()) e += fmt::format(", group = \"{}\"", s.group);
  if (s.cost != 1.0) e += fmt::format(", cost = {}", s.cost);
  if (s.floor > 0)
    e += fmt::format(", floor = \"{}\"", quantity_text(cfg, s.parameter, s.floor, tolerance_display_unit(cfg, s.parameter)));
  return e + " }";
}

std::string coefficient_cell(const AllocatedCoefficient& c) { return c.id + " [" + c.unit + "]"; }

// The coefficients without a target that the allocation made worse (only with --let-others-grow), or the
// statement that they are held.
std::string grown_text(const AllocationDetail& r, std::size_t width) {
  std::vector<std::string> grown;
  for (const AllocatedCoefficient& c : r.coefficients)
    if (c.grew)
      grown.push_back(fmt::format("{} from {} to {} {} ({:.3g} x)", c.id,
                                  number(c.configured_expanded * c.display_scale, 4),
                                  number(c.allocated_expanded * c.display_scale, 4), c.unit,
                                  c.allocated_expanded / c.configured_expanded));
  if (!grown.empty())
    return wrap_words(
        fmt::format("WARNING: without a target (--let-others-grow), U grew: {}.", fmt::join(grown, "; ")),
        width);
  if (r.let_others_grow) return "";
  return wrap_words(
      "Coefficients without a target are held at their configured U (--let-others-grow lets them grow).",
      width);
}

std::string coefficients_table(const AllocationDetail& r, std::size_t width) {
  Table t({"coefficient", "target U", "configured U", "allocated U", "one-scale U", "target", "price"});
  t.gap(2);
  for (const AllocatedCoefficient& c : r.coefficients) {
    const double f = c.display_scale;
    t.add_row({coefficient_cell(c), c.has_target ? number(c.target * f, 4) : "-",
               number(c.configured_expanded * f, 4), number(c.allocated_expanded * f, 6),
               number(c.common_expanded * f, 4),
               c.has_target ? (c.active ? "active" : "inactive")
               : c.held     ? "held"
               : c.grew     ? "grew"
                            : "none",
               c.has_target ? number(c.price, 4) : ""});
  }
  std::string out = t.render("  ", width);
  out += wrap_words(
      "  (one-scale U: every tolerance scaled by one common lambda; price: d objective / d ln "
      "target, what loosening the target saves; held: no target, held at its configured U)",
      width, "   ");
  out += grown_text(r, width);
  return out;
}

std::string sources_table(const Config& cfg, const AllocationDetail& r, const AllocateTextOptions& o) {
  bool costs = false;
  for (const AllocatedSource& a : r.sources) costs = costs || a.cost != 1.0;
  std::vector<std::string> header = {"source", "name", "PDF"};
  if (costs || o.wide) header.push_back("cost");
  bool floors = false;
  for (const AllocatedSource& a : r.sources) floors = floors || a.floor > 0;
  for (const char* h : {"unit", "configured", "allocated", "lambda"}) header.push_back(h);
  if (floors) header.push_back("floor");
  for (std::size_t t : r.targets) header.push_back("share " + r.coefficients[t].id);
  Table sources(header);
  sources.align_left(1);
  sources.align_left(costs || o.wide ? 4 : 3);  // the unit
  sources.gap(2);
  if (!o.wide) sources.shrink(1);
  for (const AllocatedSource& a : r.sources) {
    const std::string unit = tolerance_display_unit(cfg, a.parameter);
    std::vector<std::string> row = {source_label(a.id, a.group),
                                    describe_input(cfg, a.parameter).name,
                                    std::string(distribution_name(a.distribution))};
    if (costs || o.wide) row.push_back(number(a.cost, 4));
    const double unit_si = unit_in_si(describe_input(cfg, a.parameter), unit);
    row.push_back(unit);
    row.push_back(number(a.bound / unit_si, 4));
    row.push_back(number(round_down(a.allocated_bound / unit_si), 4));  // as pasted below
    row.push_back(number(a.scale, 4));
    if (floors) row.push_back(a.floor > 0 ? number(a.floor / unit_si, 4) + (a.at_floor ? " (at)" : "") : "-");
    for (Eigen::Index i = 0; i < a.share.size(); ++i)
      row.push_back(fmt::format("{:.1f} %", 100 * a.share[i]));
    sources.add_row(row);
  }
  // The cross terms of correlated sources, as the budget's line of them, when they reach 0.05 % of a target's
  // u² (shown as 0.1 %): the sources' shares and this line add to 100 % but for the rate noise.
  bool crossed = false;
  for (std::size_t t : r.targets) crossed = crossed || std::abs(r.coefficients[t].correlation_share) >= 5e-4;
  std::string out = sources.render("  ", o.wide ? 0 : o.width);
  if (crossed) {
    out += fmt::format("  {} (their cross terms at the allocated tolerances):", budget_parts::kCrossTermsLabel);
    for (std::size_t t : r.targets)
      out += fmt::format(" share {} {:.1f} %", r.coefficients[t].id, 100 * r.coefficients[t].correlation_share);
    out += "\n";
  }
  return out;
}

std::string verification_text(const AllocationDetail& r, const std::string& pct, std::size_t width) {
  const AllocationVerification& v = r.verification;
  if (v.trials == 0) return "\nNo Monte Carlo verification (--verify-trials 0).\n";
  Table check({"coefficient", "target U", "MC mean", "half-width", "/target", "MC std", "/LPU u", "verdict"});
  check.gap(2);
  for (std::size_t t : r.targets) {
    const AllocatedCoefficient& c = r.coefficients[t];
    const double f = c.display_scale;
    check.add_row({coefficient_cell(c), number(c.target * f, 4), number(c.mc_mean * f, 4),
                   number(c.mc_half_width * f, 4),
                   fmt::format("{:.3f}", c.target > 0 ? c.mc_half_width / c.target : 0.0),
                   number(c.mc_std * f, 4), fmt::format("{:.3f}", c.lpu_std > 0 ? c.mc_std / c.lpu_std : 0.0),
                   std::string(verdict_name(c.verdict))});
  }
  std::string out = "\n";
  out += wrap_words(fmt::format("Monte Carlo verification on the allocated tolerances (JCGM "
                                "101, {} mode nonlinear pipeline, M = {}, seed {}, {:.3g} s): "
                                "half-width = max(y_high - y, y - y_low) of the symmetric {} "
                                "interval about the MC mean y.",
                                mode_name(r.mode), v.trials, v.seed, v.seconds, pct),
                    width);
  out += check.render("  ", width);
  out += wrap_words(
      fmt::format("The check has sampling error: relative standard error ~{:.2g} of a half-width "
                  "and ~1/sqrt(2M) = {:.2g} of a standard deviation (normal output). 'pass within "
                  "sampling' = half-width at most target x (1 + {:.3g}), 3 standard errors. "
                  "Verification {}.",
                  v.half_width_rel_error, v.std_rel_error, v.allowance, v.passed ? "PASSED" : "FAILED"),
      width);
  return out;
}

std::string text_of(const Config& cfg, const AllocationDetail& r, const AllocateTextOptions& o) {
  const std::size_t width = o.wide ? 0 : o.width;
  const std::string pct = fmt::format("{:g} %", 100 * r.coverage_probability);
  std::string out = fmt::format("ccal allocate: {}\n", cfg.source);
  out += wrap_words(
      fmt::format("{} sources; LPU with {} mode sensitivities at the configured errors. Targets are expanded "
                  "uncertainties U = k_p u (half-widths of the {} interval), k_p = {:.5f} (the normal "
                  "quantile of (1 + p)/2, p = {:g}). Allocation: minimise sum cost_s / lambda_s (tolerance_s "
                  "= lambda_s x configured) subject to every target{}, floor_s/bound_s <= lambda_s <= {:g}.",
                  r.sources.size(), mode_name(r.mode), pct, r.coverage_factor, r.coverage_probability,
                  r.let_others_grow ? "" : ", U <= configured U of every other coefficient", r.max_scale),
      width);
  out += '\n';
  out += coefficients_table(r, width);
  out += '\n';
  out += wrap_words(
      "Allocated tolerances, tightened most first (in the units of the configuration; "
      "shares of the targets' variances at the allocated tolerances):",
      width);
  out += sources_table(cfg, r, o);
  out += '\n';
  out += wrap_words(fmt::format("Objective sum cost/lambda: {:.6g} allocated; {:.6g} at the configured "
                                "tolerances; {:.6g} with one common scale lambda = {:.4g} = min(max "
                                "scale, min over targets of target/U) for every source.",
                                r.objective, r.configured_objective, r.common_objective, r.common_scale),
                    width);
  out += wrap_words(fmt::format("Solved by {} ({} Newton iteration{} on the dual; {}; duality gap {:.2g}).",
                                r.method, r.iterations, r.iterations == 1 ? "" : "s",
                                r.converged ? "converged" : "NOT converged", r.dual_gap),
                    width);
  out += verification_text(r, pct, width);
  out += "\nAllocated [tolerances] in configuration style (bounds rounded down to 4 digits):\n";
  for (const AllocatedSource& a : r.sources) out += "  " + toml_entry(a, cfg) + "\n";
  return out;
}

// A coefficient in its display unit: its target, U configured, allocated and at one common scale, and the
// cross terms' share of u² at the allocated tolerances; held or grown without a target, active with its price
// with one; the Monte Carlo's figures when the verification ran (and its verdict on a target).
nlohmann::ordered_json allocated_coefficient_json(const AllocatedCoefficient& c, bool verified) {
  const double f = c.display_scale;
  nlohmann::ordered_json o;
  o["unit"] = c.unit;
  o["target"] = c.has_target ? nlohmann::ordered_json(c.target * f) : nlohmann::ordered_json(nullptr);
  o["configured_expanded"] = c.configured_expanded * f;
  o["allocated_expanded"] = c.allocated_expanded * f;
  o["common_scale_expanded"] = c.common_expanded * f;
  o["allocated_std_uncertainty"] = c.lpu_std * f;
  o["correlation_share"] = c.correlation_share;  // the cross terms' share of u² at the allocated tolerances
  if (!c.has_target) {
    o["held"] = c.held;
    o["grew"] = c.grew;
  }
  if (c.has_target) {
    o["active"] = c.active;
    o["multiplier"] = c.multiplier;
    o["objective_per_ln_target"] = c.price;
  }
  if (verified) {
    o["mc"] = {{"mean", c.mc_mean * f},
               {"std_dev", c.mc_std * f},
               {"symmetric_interval", {c.mc_low * f, c.mc_high * f}},
               {"half_width", c.mc_half_width * f}};
    if (c.has_target) o["verdict"] = verdict_name(c.verdict);
  }
  return o;
}

// The coefficients without a target whose U grew (--let-others-grow), configured and allocated.
nlohmann::ordered_json allocation_grown_json(const AllocationDetail& r) {
  nlohmann::ordered_json grown = nlohmann::ordered_json::array();
  for (const AllocatedCoefficient& c : r.coefficients)
    if (c.grew)
      grown.push_back({{"id", c.id},
                       {"unit", c.unit},
                       {"configured_expanded", c.configured_expanded * c.display_scale},
                       {"allocated_expanded", c.allocated_expanded * c.display_scale}});
  return grown;
}

// The source of rank `rank` (0-based): its bounds and uncertainties in SI, its scale, its [tolerances] entry
// and its share of each target's variance.
nlohmann::ordered_json allocated_source_json(const Config& cfg, const AllocationDetail& r, std::size_t rank) {
  const AllocatedSource& a = r.sources[rank];
  nlohmann::ordered_json o;
  o["id"] = a.id;
  o["rank"] = rank + 1;
  o["unit_si"] = describe_input(cfg, a.parameter).si_unit;
  o["distribution"] = distribution_name(a.distribution);
  o["group"] = a.group;
  o["cost"] = a.cost;
  o["bound_si"] = a.bound;
  o["allocated_bound_si"] = a.allocated_bound;
  o["standard_uncertainty_si"] = a.standard_uncertainty;
  o["allocated_standard_uncertainty_si"] = a.allocated_standard_uncertainty;
  o["scale"] = a.scale;
  o["floor_si"] = a.floor;
  o["at_floor"] = a.at_floor;
  o["toml"] = toml_entry(a, cfg);
  nlohmann::ordered_json share = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < r.targets.size(); ++i)
    share[r.coefficients[r.targets[i]].id] = a.share[Eigen::Index(i)];
  o["share"] = share;
  return o;
}

// The Monte Carlo verification, null when it did not run.
nlohmann::ordered_json allocation_verification_json(const AllocationVerification& v) {
  if (v.trials == 0) return nullptr;
  return {{"trials", v.trials},
          {"seed", v.seed},
          {"threads", v.threads},
          {"wall_time_s", v.seconds},
          {"half_width_rel_error", v.half_width_rel_error},
          {"std_rel_error", v.std_rel_error},
          {"allowance", v.allowance},
          {"passed", v.passed},
          {"notes", detail::lines_of(v.notes)}};
}

std::string json_of(const Config& cfg, const AllocationDetail& r) {
  nlohmann::ordered_json j;
  j["command"] = "allocate";
  j["ccal_version"] = version();
  j["config"] = cfg.source;
  j["mode"] = mode_name(r.mode);
  j["coverage_probability"] = r.coverage_probability;
  j["coverage_factor"] = r.coverage_factor;
  j["max_scale"] = r.max_scale;
  j["let_others_grow"] = r.let_others_grow;
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  for (std::size_t t : r.targets) targets.push_back(r.coefficients[t].id);
  j["targets"] = targets;
  j["objective"] = {{"allocated", r.objective},
                    {"configured", r.configured_objective},
                    {"common_scale", r.common_objective}};
  j["common_scale"] = r.common_scale;
  j["solver"] = {{"method", r.method},
                 {"iterations", r.iterations},
                 {"converged", r.converged},
                 {"dual_gap", r.dual_gap}};
  nlohmann::ordered_json coefficients = nlohmann::ordered_json::object();
  for (const AllocatedCoefficient& c : r.coefficients)
    coefficients[c.id] = allocated_coefficient_json(c, r.verification.trials > 0);
  j["coefficients"] = coefficients;
  j["grown"] = allocation_grown_json(r);
  nlohmann::ordered_json sources = nlohmann::ordered_json::array();
  for (std::size_t s = 0; s < r.sources.size(); ++s) sources.push_back(allocated_source_json(cfg, r, s));
  j["sources"] = sources;
  j["verification"] = allocation_verification_json(r.verification);
  return j.dump(2) + "\n";
}

std::string csv_of(const Config& cfg, const AllocationDetail& r) {
  // The coefficients without a target that grew, as comment lines ahead of the table (--let-others-grow).
  std::string out;
  for (const AllocatedCoefficient& c : r.coefficients)
    if (c.grew)
      out += fmt::format("# grew without a target: {} configured U {:.17g} {}, allocated U {:.17g} {}\n",
                         c.id, c.configured_expanded * c.display_scale, c.unit,
                         c.allocated_expanded * c.display_scale, c.unit);
  out += "rank,source,group,distribution,cost,unit_si,bound_si,allocated_bound_si,scale,floor_si";
  for (std::size_t t : r.targets) out += ",share_" + r.coefficients[t].id;
  out += "\n";
  for (std::size_t s = 0; s < r.sources.size(); ++s) {
    const AllocatedSource& a = r.sources[s];
    out += fmt::format("{},{},{},{},{:.17g},{},{:.17g},{:.17g},{:.17g}", s + 1, a.id, a.group,
                       distribution_name(a.distribution), a.cost,
                       describe_input(cfg, a.parameter).si_unit, a.bound,
                       a.allocated_bound, a.scale);
    out += fmt::format(",{:.17g}", a.floor);
    for (Eigen::Index i = 0; i < a.share.size(); ++i) out += fmt::format(",{:.17g}", a.share[i]);
    out += "\n";
  }
  return out;
}

}  // namespace

std::string tolerance_display_unit(const Config& cfg, int parameter) {
  for (const Tolerance& t : cfg.tolerances)
    if (t.parameter == parameter && !t.unit.empty()) return t.unit;
  return describe_input(cfg, parameter).display_unit;
}

std::string text(const verbs::AllocateResult& r, const AllocateTextOptions& o) {
  return text_of(r.config, r.allocation, o);
}
std::string json(const verbs::AllocateResult& r) { return json_of(r.config, r.allocation); }
std::string csv(const verbs::AllocateResult& r) { return csv_of(r.config, r.allocation); }

}  // namespace ccal::render
