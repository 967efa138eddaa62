#pragma once
// What the text, JSON and CSV of `ccal budget` share (private to the library): each source in the unit the
// configuration wrote it in, its name and sensitivity per that unit, and the contributions that make up a
// coefficient's variance.
#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "ccal/verbs/budget.hpp"

namespace ccal::render::budget_parts {

// A source as the configuration states it.
struct SourceView {
  std::string unit;    // as written in [tolerances] ("um", "arcsec"), else a readable SI unit
  double unit_si = 1;  // SI size of one such unit
  double bound = 0;    // in `unit`
  double u = 0;        // standard uncertainty u(x_i), in `unit`
  std::string name;    // the catalogue's words
};
SourceView source_view(const Config& cfg, const SourceBudget& s);

// c_i of coefficient k (display unit of the coefficient per `view.unit`): u_i(y) = c_i u(x_i).
double sensitivity_per_unit(const ccal::BudgetResult& r, const SourceBudget& s, const SourceView& view,
                            std::size_t k);

// One addend of a coefficient's variance: a correlation group (its members' effects added with their signs;
// an independent source is a group of one) or a drive's rate noise. Shares of one coefficient sum to 1.
struct Contribution {
  std::string label;  // the source id, or "<group> (id, id…)"
  double share = 0;   // of u_k²
};
std::vector<Contribution> contributions(const ccal::BudgetResult& r, std::size_t k);

// "id (group)", or the id alone.
std::string source_label(const std::string& id, const std::string& group);

// A CSV field, quoted when it holds a comma, a quote or a line break.
std::string csv_field(std::string_view text);

}  // namespace ccal::render::budget_parts
