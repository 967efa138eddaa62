#include "ccal/render/budget.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "budget_parts.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/core/units.hpp"
#include "ccal/render/table.hpp"
#include "ccal/setup/input_description.hpp"
#include "ccal/version.hpp"
#include "parts.hpp"

namespace ccal::render {
namespace {

using namespace budget_parts;

std::vector<std::size_t> by_rank(const BudgetDetail& r) {
  std::vector<std::size_t> order(r.sources.size());
  for (std::size_t s = 0; s < order.size(); ++s) order[std::size_t(r.sources[s].rank - 1)] = s;
  return order;
}

nlohmann::ordered_json per_coefficient(const BudgetDetail& r, const Eigen::VectorXd& v, bool scale = true) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < r.coefficients.size(); ++k)
    j[r.coefficients[k]] = v[Eigen::Index(k)] * (scale ? r.display_scale[k] : 1.0);
  return j;
}

// The EA-4/02 fields of a line, after those it shares with the older fields: x_i, the divisor, the type, ν_i,
// the unit of c_i and, per coefficient, whether the contribution is below the round-off floor.
void add_gum_fields(nlohmann::ordered_json& o, const BudgetDetail& r, const SourceView& view,
                    const Eigen::VectorXd& effect) {
  o["estimate"] = view.estimate;
  o["estimate_si"] = view.estimate_si;
  o["divisor"] = view.divisor;
  o["type"] = std::string(1, view.type);
  o["dof"] = dof_json(view.dof);
  nlohmann::ordered_json unit = nlohmann::ordered_json::object(), floor = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < r.coefficients.size(); ++k) {
    unit[r.coefficients[k]] = sensitivity_unit(r, k, view);
    floor[r.coefficients[k]] = below_round_off_floor(r, effect[Eigen::Index(k)], k);
  }
  o["sensitivity_unit"] = unit;
  o["below_round_off_floor"] = floor;
}

// A source's line: its tolerance in SI, its effects and shares, the same as the configuration wrote it, the
// columns of EA-4/02, and the paper's effect where computed.
nlohmann::ordered_json source_json(const Config& cfg, const BudgetDetail& r, const SourceBudget& b) {
  nlohmann::ordered_json o;
  const SourceView view = source_view(cfg, b);
  o["id"] = b.id;
  o["name"] = view.name;
  o["rank"] = b.rank;
  o["unit_si"] = describe_input(cfg, b.parameter).si_unit;
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
  // The same source as the configuration wrote it: c_i per that unit, so that u_i(y) = c_i u(x_i).
  o["unit"] = view.unit;
  o["bound"] = view.bound;
  o["standard_uncertainty"] = view.u;
  nlohmann::ordered_json c = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < r.coefficients.size(); ++k)
    c[r.coefficients[k]] = sensitivity_per_unit(r, b, view, k);
  o["sensitivity"] = c;
  add_gum_fields(o, r, view, b.effect);
  if (b.paper_effect.size()) {
    o["paper_effect"] = per_coefficient(r, b.paper_effect);
    nlohmann::ordered_json d = nlohmann::ordered_json::object();
    for (std::size_t k = 0; k < r.coefficients.size(); ++k) d[r.coefficients[k]] = bool(b.disagrees[k]);
    o["exact_paper_disagree"] = d;
    if (!b.paper_counterpart) o["paper_counterpart"] = false;  // the drives' ripple: no paper rule
  }
  return o;
}

// A drive's rate noise: its density, each run mean's σ, u and share per coefficient; then the same line as a
// source's: x_i = 0 and u(x_i) = N in ppm/rtHz, normal, c_i = u_i(y) / u(x_i).
nlohmann::ordered_json rate_noise_json(const Config& cfg, const BudgetDetail& r, const RateNoiseBudget& n) {
  nlohmann::ordered_json runs = nlohmann::ordered_json::object();
  for (std::size_t i = 0; i < cfg.plan.runs.size(); ++i)
    runs[cfg.plan.runs[i].name] = n.run_sd[Eigen::Index(i)] * r.display_scale.front();
  nlohmann::ordered_json o = {{"id", n.id},
                              {"type", "A"},
                              {"density_per_rtHz", n.density},
                              {"run_mean_sd", runs},
                              {"u", per_coefficient(r, n.effect)},
                              {"share", per_coefficient(r, n.share, false)}};
  const SourceView view = rate_noise_view(n);
  o["name"] = view.name;
  o["distribution"] = distribution_name(Distribution::normal);
  o["unit"] = view.unit;
  o["standard_uncertainty"] = view.u;
  nlohmann::ordered_json c = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < r.coefficients.size(); ++k)
    c[r.coefficients[k]] = sensitivity_per_unit(r, n, view, k);
  o["sensitivity"] = c;
  add_gum_fields(o, r, view, n.effect);
  return o;
}

std::string json_of(const Config& cfg, const BudgetDetail& r, const verbs::ObservabilityReport& observability,
                    const Eigen::VectorXd& known_bias) {
  nlohmann::ordered_json j;
  j["ccal_version"] = version();
  j["config"] = cfg.source;
  j["mode"] = std::string(mode_name(r.mode));
  j["derivatives"] = r.derivatives == DerivativeMethod::automatic ? "automatic" : "linearised";
  j["coverage_factor"] = r.coverage.factor;
  j["coverage_probability"] = r.coverage.probability;
  j["coverage_method"] = std::string(coverage_method_name(r.coverage.method));
  // A contribution below this fraction of its coefficient's u is round-off (uncertainty/budget.hpp): the
  // tables show it as 0, the numbers here keep it; each coefficient's "round_off_floor" is the absolute one.
  j["round_off_floor_relative"] = kRoundOffFloor;
  j["coefficients"] = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < r.coefficients.size(); ++k)
    j["coefficients"].push_back(
        {{"id", r.coefficients[k]},
         {"unit", r.units[k]},
         {"standard_uncertainty", r.standard_uncertainty[Eigen::Index(k)] * r.display_scale[k]},
         {"expanded_uncertainty", r.expanded_uncertainty[Eigen::Index(k)] * r.display_scale[k]},
         {"round_off_floor", round_off_floor(r, k)}});
  j["sources"] = nlohmann::ordered_json::array();
  for (std::size_t s : by_rank(r)) j["sources"].push_back(source_json(cfg, r, r.sources[s]));
  j["correlation"] = nlohmann::ordered_json::array();
  for (Eigen::Index a = 0; a < r.correlation.rows(); ++a) {
    nlohmann::ordered_json jr = nlohmann::ordered_json::array();
    for (Eigen::Index b = 0; b < r.correlation.cols(); ++b) jr.push_back(r.correlation(a, b));
    j["correlation"].push_back(jr);
  }
  if (nlohmann::ordered_json ic = budget_parts::input_correlation_json(r); !ic.is_null())
    j["input_correlation"] = std::move(ic);
  if (!r.rate_noise.empty()) {
    j["rate_noise"] = nlohmann::ordered_json::array();
    for (const RateNoiseBudget& n : r.rate_noise) j["rate_noise"].push_back(rate_noise_json(cfg, r, n));
  }
  j["compensation_choices"] = nlohmann::ordered_json::array();
  for (const auto& c : r.compensation) {
    nlohmann::ordered_json o{
        {"id", c.id}, {"description", c.description}, {"bias", per_coefficient(r, c.bias)}};
    if (c.paper_bias.size()) o["paper_bias"] = per_coefficient(r, c.paper_bias);
    j["compensation_choices"].push_back(o);
  }
  j["known_error_bias"] =
      known_bias.size() ? per_coefficient(r, known_bias) : nlohmann::ordered_json(nullptr);
  j["answer"] = nlohmann::ordered_json::object();  // per coefficient: the contributions that make 90 % of u²
  for (std::size_t k = 0; k < r.coefficients.size(); ++k) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const Contribution& c : answer_contributions(r, k))
      list.push_back({{"source", c.label}, {"share", c.share}});
    j["answer"][r.coefficients[k]] = list;
  }
  j["observability"] = observability_json(observability);
  return j.dump(2) + "\n";
}

// The CSV's header: per coefficient its d<K> columns (total, force and rate parts) and share; the source as
// configured with c_i per its unit (u_i(y) = c_i u(x_i)); the further columns of EA-4/02 (the evaluation's
// type, ν_i ("inf"), the divisor, x_i in that unit and in SI, the unit of each c_i); with [[correlations]]
// the inputs' correlation matrix, a column r_<id> per source (tolerance order).
std::string budget_csv_header(const BudgetDetail& r, std::size_t correlation_columns) {
  const std::size_t nk = r.coefficients.size();
  std::string out = "rank,source,group,distribution,bound_si,unit_si,standard_uncertainty_si";
  for (std::size_t k = 0; k < nk; ++k)
    out += fmt::format(",{},{},{},share_{}", csv_column("d" + r.coefficients[k], r.units[k]),
                       csv_column("d" + r.coefficients[k] + "_force", r.units[k]),
                       csv_column("d" + r.coefficients[k] + "_rate", r.units[k]), r.coefficients[k]);
  out += ",name,unit,bound,u_x";
  for (std::size_t k = 0; k < nk; ++k) {
    out += ',';  // (not "," + …: GCC 12 warns of an overlap in that concatenation, -Wrestrict, falsely)
    out += csv_column("c_" + r.coefficients[k], r.units[k] + " per unit");
  }
  out += ",type,dof,divisor,estimate,estimate_si";
  for (std::size_t k = 0; k < nk; ++k) out += fmt::format(",c_{}_unit", r.coefficients[k]);
  for (std::size_t s = 0; s < correlation_columns; ++s) out += ",r_" + r.sources[s].id;
  return out + "\n";
}

// The columns from `name` on, of a source or a drive's rate noise; sensitivity(k) is c_i of coefficient k.
template <class Sensitivity>
std::string as_configured_columns(const BudgetDetail& r, const SourceView& view,
                                  const Sensitivity& sensitivity) {
  const std::size_t nk = r.coefficients.size();
  std::string line =
      fmt::format(",{},{},{:.17g},{:.17g}", csv_field(view.name), csv_field(view.unit), view.bound, view.u);
  for (std::size_t k = 0; k < nk; ++k) line += fmt::format(",{:.17g}", sensitivity(k));
  line += fmt::format(",{},{:.17g},{:.17g},{:.17g},{:.17g}", view.type, view.dof, view.divisor, view.estimate,
                      view.estimate_si);
  for (std::size_t k = 0; k < nk; ++k) line += fmt::format(",{}", csv_field(sensitivity_unit(r, k, view)));
  return line;
}

// A source's line: its d<K> columns in the display units, as configured, and its row of the correlation
// matrix (the first `correlation_columns` of it: none without [[correlations]]).
std::string budget_source_csv_line(const Config& cfg, const BudgetDetail& r, std::size_t s,
                                   std::size_t correlation_columns) {
  const SourceBudget& b = r.sources[s];
  const SourceView view = source_view(cfg, b);
  std::string out = fmt::format("{},{},{},{},{:.17g},{},{:.17g}", b.rank, b.id, csv_field(b.group),
                                distribution_name(b.distribution), b.bound,
                                describe_input(cfg, b.parameter).si_unit, b.standard_uncertainty);
  for (std::size_t k = 0; k < r.coefficients.size(); ++k) {
    const auto i = Eigen::Index(k);
    out += fmt::format(",{:.17g},{:.17g},{:.17g},{:.17g}", b.effect[i] * r.display_scale[k],
                       b.effect_force[i] * r.display_scale[k], b.effect_rate[i] * r.display_scale[k],
                       b.share[i]);
  }
  out += as_configured_columns(r, view, [&](std::size_t k) { return sensitivity_per_unit(r, b, view, k); });
  for (std::size_t t = 0; t < correlation_columns; ++t)
    out += fmt::format(",{:.17g}", r.input_correlation(Eigen::Index(s), Eigen::Index(t)));
  return out + "\n";
}

// A line of per-coefficient values in the d<K> columns (display units), with their shares when given; the
// columns up to the first d<K> hold the name and the distribution.
std::string budget_value_row(const BudgetDetail& r, const std::string& source,
                             const std::string& distribution, const Eigen::VectorXd& v,
                             const Eigen::VectorXd* share) {
  std::string line = fmt::format(",{},,{},,,", source, distribution);
  for (std::size_t k = 0; k < r.coefficients.size(); ++k) {
    const auto i = Eigen::Index(k);
    line += fmt::format(",{:.17g},,,", v[i] * r.display_scale[k]);
    if (share) line += fmt::format("{:.17g}", (*share)[i]);
  }
  return line;
}

// After the sources: the drives' rate noise (Type A: u, no sign), the cross terms' part of u² in the share
// columns with [[correlations]] (negative where effects cancel), then the totals and the round-off floor in
// the d<K> columns, each line's further columns empty.
std::string budget_closing_csv_lines(const BudgetDetail& r, const Eigen::VectorXd& known_bias,
                                     std::size_t correlation_columns) {
  const std::size_t nk = r.coefficients.size();
  const std::string no_correlations(correlation_columns, ',');
  const std::string blank = std::string(4 + nk + 5 + nk, ',') + no_correlations + "\n";  // name …: empty
  std::string out;
  for (const RateNoiseBudget& n : r.rate_noise) {
    const SourceView view = rate_noise_view(n);
    out +=
        budget_value_row(r, n.id, "normal (Type A)", n.effect, &n.share) +
        as_configured_columns(r, view, [&](std::size_t k) { return sensitivity_per_unit(r, n, view, k); }) +
        no_correlations + "\n";
  }
  if (r.input_correlation.size() > 0) {
    const Eigen::VectorXd cross = correlation_variance(r);
    std::string line = ",correlations_between_sources,,,,,";
    for (std::size_t k = 0; k < nk; ++k) {
      const double u = r.standard_uncertainty[Eigen::Index(k)];
      line += fmt::format(",,,,{:.17g}", u > 0 ? cross[Eigen::Index(k)] / (u * u) : 0.0);
    }
    out += line + blank;
  }
  out += budget_value_row(r, "total_standard_uncertainty", "", r.standard_uncertainty, nullptr) + blank;
  out += budget_value_row(r, "expanded_uncertainty", csv_field(coverage_text(r.coverage)),
                          r.expanded_uncertainty, nullptr) +
         blank;
  if (known_bias.size()) out += budget_value_row(r, "known_error_bias", "", known_bias, nullptr) + blank;
  // |dK| below it is round-off of the derivatives (the tables show 0): kRoundOffFloor of each total.
  out += budget_value_row(r, "round_off_floor",
                          fmt::format("{:g} of total_standard_uncertainty", kRoundOffFloor),
                          Eigen::VectorXd(kRoundOffFloor * r.standard_uncertainty), nullptr) +
         blank;
  return out;
}

// The budget as one CSV table: a line per source by rank, then budget_closing_csv_lines.
std::string csv_of(const Config& cfg, const BudgetDetail& r, const Eigen::VectorXd& known_bias) {
  const std::size_t correlation_columns = r.input_correlation.size() > 0 ? r.sources.size() : 0;
  std::string out = budget_csv_header(r, correlation_columns);
  for (std::size_t s : by_rank(r)) out += budget_source_csv_line(cfg, r, s, correlation_columns);
  return out + budget_closing_csv_lines(r, known_bias, correlation_columns);
}

}  // namespace

std::string json(const verbs::BudgetResult& r) {
  if (r.instruments.empty()) return json_of(r.config, r.budget, r.observability, r.known_error_bias);
  // A test of several instruments: each one's JSON as budget() of it alone gives it, after its id; then the
  // covariance of all their coefficients.
  nlohmann::ordered_json j;
  j["ccal_version"] = version();
  j["config"] = r.config.source;
  j["instruments"] = nlohmann::ordered_json::array();
  for (const verbs::BudgetResult& one : r.instruments) {
    nlohmann::ordered_json x;
    x["id"] = one.config.instrument_id;
    x.update(nlohmann::ordered_json::parse(json(one)));
    j["instruments"].push_back(std::move(x));
  }
  if (r.covariance) j["covariance"] = covariance_json(*r.covariance);
  return j.dump(2) + "\n";
}

std::string csv(const verbs::BudgetResult& r) {
  if (r.instruments.empty()) return csv_of(r.config, r.budget, r.known_error_bias);
  // A test of several instruments: one table, each instrument's lines after its id in a leading column; the
  // instruments share the identification and the tolerances' ids, so their headers are one.
  std::string out, header;
  for (const verbs::BudgetResult& one : r.instruments) {
    const std::string table = csv(one);
    const std::size_t end = table.find('\n');
    if (header.empty()) {
      header = table.substr(0, end);
      out = "instrument," + header + "\n";
    } else if (table.compare(0, end, header) != 0) {
      throw OptionError("format", "csv",
                        fmt::format("is one table, and the instruments of {} have budgets of other columns (other "
                                    "sources or terms); accepted: {} text or json",
                                    r.config.source, OptionError::name("format")));
    }
    for (std::size_t at = end + 1; at < table.size();) {
      const std::size_t next = table.find('\n', at);
      out += csv_field(one.config.instrument_id) + "," + table.substr(at, next - at + 1);
      at = next + 1;
    }
  }
  return out;
}

}  // namespace ccal::render
