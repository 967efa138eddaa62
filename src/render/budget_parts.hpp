#pragma once
// What the text, JSON and CSV of `ccal budget` share (private to the library): the lines of a GUM budget
// table (JCGM 100 §5, the columns of EA-4/02) in the units the configuration wrote, the round-off floor, and
// the contributions that make up a coefficient's variance. The report's tables read the same fields from the
// JSON.
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/verbs/budget.hpp"

namespace ccal::render::budget_parts {

// An input quantity X_i as the configuration states it: a tolerance (Type B) or a drive's rate noise (Type
// A).
struct SourceView {
  std::string unit;        // as written in [tolerances] ("um", "arcsec"), else a readable SI unit
  double unit_si = 1;      // SI size of one such unit
  double estimate = 0;     // x_i: the configured [errors] value (0 where none), in `unit`
  double estimate_si = 0;  // the same in SI
  double bound = 0;        // in `unit`
  double divisor = 1;      // of the distribution: u = bound / divisor (setup/tolerance.hpp)
  double u = 0;            // standard uncertainty u(x_i), in `unit`
  char type = 'B';         // the evaluation (JCGM 100 §4.2, §4.3): 'A' for a drive's rate noise
  // ν_i: ∞ for both. A tolerance's bound is taken as exact (JCGM 100 G.4.2); a rate noise's σ follows from
  // the configured density, a stated value rather than one estimated from this budget's observations.
  double dof = std::numeric_limits<double>::infinity();
  std::string name;  // the catalogue's words
};
SourceView source_view(const Config& cfg, const SourceBudget& s);
// A drive's rate noise: its density N in ppm/rtHz as x_i's u, x_i = 0 (a zero-mean noise), normal, Type A.
SourceView rate_noise_view(const RateNoiseBudget& n);

// c_i of coefficient k (display unit of the coefficient per `view.unit`): u_i(y) = c_i u(x_i).
double sensitivity_per_unit(const ccal::BudgetDetail& r, const SourceBudget& s, const SourceView& view,
                            std::size_t k);
double sensitivity_per_unit(const ccal::BudgetDetail& r, const RateNoiseBudget& n, const SourceView& view,
                            std::size_t k);
// The unit of c_i: "deg/s/g^3 per arcsec".
std::string sensitivity_unit(const ccal::BudgetDetail& r, std::size_t k, const SourceView& view);

// The divisor as a table prints it: "1", "√2", "√3", "√6" (its square is whole for every distribution).
std::string divisor_text(double divisor);

// The round-off floor of coefficient k in its display unit (kRoundOffFloor u_c, uncertainty/budget.hpp), and
// whether a contribution (SI, signed) is below it: a table shows such a contribution, its c_i and share as 0.
double round_off_floor(const ccal::BudgetDetail& r, std::size_t k);
bool below_round_off_floor(const ccal::BudgetDetail& r, double contribution_si, std::size_t k);

// One line of coefficient k's budget table: a source of the budget, or a drive's rate noise (no sign).
struct BudgetLine {
  const SourceBudget* tolerance = nullptr;  // the source; null for a rate noise
  std::string source;                       // "id (group)", or the id
  SourceView x;
  std::string distribution;
  double sensitivity = 0;   // c_i, in the coefficient's display unit per x.unit
  double contribution = 0;  // u_i(y) = c_i u(x_i) in the display unit: signed; ≥ 0 for a rate noise
  double share = 0;         // of u_c²
  bool round_off = false;   // |u_i(y)| below the floor
};
// Every source and rate noise, by share of coefficient k's variance, largest first.
std::vector<BudgetLine> budget_lines(const Config& cfg, const ccal::BudgetDetail& r, std::size_t k);

// The label of the cross terms' line (Σ_{s≠t} of correlated sources' effects) in a table of shares of u²: the
// budget's answer and the allocation's table of tolerances.
inline constexpr std::string_view kCrossTermsLabel = "correlations between sources";

// One addend of a coefficient's variance: a correlation group (its members' effects added with their signs;
// an independent source is a group of one) or a drive's rate noise. Shares of one coefficient sum to 1.
struct Contribution {
  std::string label;  // the source id, or "<group> (id, id…)"
  double share = 0;   // of u_k²
};
std::vector<Contribution> contributions(const ccal::BudgetDetail& r, std::size_t k);
// "The answer": the largest contributions that make 90 % of u_k², the cross terms of partly correlated
// sources that cancel (a negative share) counted first and listed last when they reach 1 % of u_k².
std::vector<Contribution> answer_contributions(const ccal::BudgetDetail& r, std::size_t k);

// "id (group)", or the id alone.
std::string source_label(const std::string& id, const std::string& group);

// A CSV field, quoted when it holds a comma, a quote or a line break.
std::string csv_field(std::string_view text);

// A CSV column's name with its unit, as one plain word that any reader takes as it is (no space, bracket or
// slash): the unit's '/' and spaces as '_', '^' left out, µ as u, ° as deg, % as pct, any other sign as '_'
// (dK0 and "deg/s" give dK0_deg_s, "deg/s/g^2" deg_s_g2). docs/cli.md lists the columns.
std::string csv_column(std::string_view name, std::string_view unit);

// The inputs' correlation matrix ([[correlations]] and the groups' r = 1, sources in tolerance order) and the
// share of each coefficient's u² its cross terms make, as the budget's and the Monte Carlo's JSON carry it;
// null when the budget has none (no [[correlations]]).
nlohmann::ordered_json input_correlation_json(const ccal::BudgetDetail& r);

}  // namespace ccal::render::budget_parts
