// [[correlations]]: pairs of tolerances whose errors are partly correlated (docs/config.md), each checked on
// its own (known ids, r in [−1, 1], no pair twice, not within one group) and then the matrix as a whole (a
// correlation matrix is positive semi-definite).
#include <fmt/format.h>

#include <map>
#include <utility>

#include "ccal/setup/input_correlation.hpp"
#include "config_reader.hpp"

namespace ccal::config_reading {

namespace {

// A source id of a pair: one with a tolerance, else refused with the nearest such id.
std::string source_id(const Reader& r, const toml::node& n, const std::string& p,
                      const std::vector<Tolerance>& tolerances) {
  const auto id = n.value<std::string>();
  if (!id) r.fail(n, p, fmt::format("expected a parameter id such as \"dthy4\", got {}", type_name(n)));
  std::vector<std::string> ids;
  for (const Tolerance& t : tolerances) {
    if (t.id == *id) return *id;
    ids.push_back(t.id);
  }
  const auto best = closest(*id, ids);
  r.fail(n, p,
         fmt::format("'{}' has no tolerance; accepted: a source of [tolerances]{}", *id,
                     best ? fmt::format(" (did you mean '{}'?)", *best) : std::string()));
}

const Tolerance& tolerance_of(const std::vector<Tolerance>& tolerances, const std::string& id) {
  for (const Tolerance& t : tolerances)
    if (t.id == id) return t;
  return tolerances.front();  // not reached: source_id checked it
}

// [[correlations]] entry k: two different sources with a tolerance, not of one group, r in [-1, 1], and a
// pair (a grouped source standing for its group) not given before (`seen`: each pair, sorted, with its line).
Correlation read_correlation(const Reader& r, const toml::node& entry, std::size_t k,
                             const std::vector<Tolerance>& tolerances,
                             std::map<std::pair<std::string, std::string>, int>& seen) {
  const std::string p = fmt::format("correlations[{}]", k + 1);
  const toml::table* t = entry.as_table();
  if (!t) r.fail(entry, p, fmt::format("expected a table ([[correlations]]), got {}", type_name(entry)));
  r.check_keys(*t, p, kCorrelationKeys);
  const toml::node* between = t->get("between");
  const toml::array* ids = between ? between->as_array() : nullptr;
  if (!ids || ids->size() != 2)
    r.fail(between ? *between : entry, p + ".between",
           "expected two parameter ids with a tolerance, e.g. between = [\"dthy4\", \"dthy5\"]");
  Correlation c;
  c.first = source_id(r, *ids->get(0), p + ".between", tolerances);
  c.second = source_id(r, *ids->get(1), p + ".between", tolerances);
  if (c.first == c.second)
    r.fail(
        *between, p + ".between",
        fmt::format("'{}' twice; a source is fully correlated with itself; accepted: two different sources",
                    c.first));
  const std::optional<double> value = r.number(*t, p, "r");
  if (!value) r.fail(entry, p + ".r", "missing; give the correlation coefficient, e.g. r = 0.6");
  if (!(*value >= -1 && *value <= 1))
    r.fail(*t->get("r"), p + ".r",
           fmt::format("{} is not a correlation coefficient; accepted: a number from -1 to 1",
                       number_text(*value)));
  c.r = *value;
  const std::string& group = tolerance_of(tolerances, c.first).group;
  if (!group.empty() && group == tolerance_of(tolerances, c.second).group)
    r.fail(*between, p + ".between",
           fmt::format("{} and {} are both in group \"{}\", which makes them fully correlated (r = 1); "
                       "accepted: the pair here or in one group, not both",
                       c.first, c.second, group));
  // A grouped source stands for its group (the pair applies to every member): a pair is its two groups.
  auto unit = [&](const std::string& id) {
    const std::string& g = tolerance_of(tolerances, id).group;
    return g.empty() ? id : "group \"" + g + "\"";
  };
  const std::string ua = unit(c.first), ub = unit(c.second);
  const std::pair<std::string, std::string> key = ua < ub ? std::pair{ua, ub} : std::pair{ub, ua};
  const int line = where(entry.source()).line;
  if (const auto it = seen.find(key); it != seen.end())
    r.fail(*between, p + ".between",
           fmt::format("the pair {}, {} is given twice (first at line {}{}); accepted: each pair once",
                       c.first, c.second, it->second,
                       ua == c.first && ub == c.second ? "" : ", a group standing for all its members"));
  seen.emplace(key, line);
  return c;
}

}  // namespace

std::vector<Correlation> read_correlations(const Reader& r, const toml::table& root,
                                           const std::vector<Tolerance>& tolerances) {
  std::vector<Correlation> out;
  const toml::node* node = root.get("correlations");
  if (!node) return out;
  const toml::array* entries = node->as_array();
  if (!entries)
    r.fail(
        *node, "correlations",
        fmt::format("expected an array of tables ([[correlations]] with between = [\"dthy4\", \"dthy5\"] and "
                    "r = 0.6), got {}",
                    type_name(*node)));
  std::map<std::pair<std::string, std::string>, int> seen;  // pair (sorted) → line
  for (std::size_t k = 0; k < entries->size(); ++k)
    out.push_back(read_correlation(r, *entries->get(k), k, tolerances, seen));
  const InputCorrelation ic = input_correlation(tolerances, out);
  if (ic.smallest_eigenvalue < kCorrelationEigenvalueFloor)
    r.fail(*node, "correlations",
           fmt::format("these correlations (with the groups' r = 1) are not those of any joint distribution: "
                       "the matrix is not positive semi-definite (smallest eigenvalue {:.3g}, along {}); "
                       "accepted: a matrix whose eigenvalues are all >= 0, e.g. smaller |r| among {}",
                       ic.smallest_eigenvalue, fmt::join(ic.along, ", "), fmt::join(ic.along, ", ")));
  return out;
}

}  // namespace ccal::config_reading
