#include "ccal/render/identify.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <nlohmann/json.hpp>

#include "ccal/version.hpp"
#include "parts.hpp"
#include "statement_part.hpp"

namespace ccal::render {

std::string text(const verbs::IdentifyResult& r) {
  const TableFitSpec& spec = r.spec;
  const verbs::Identification& id = r.identification;
  std::string subtracted;
  for (const auto& k : spec.known) subtracted += " - " + k;
  std::string out = fmt::format("ccal identify: {}, {} rows; {}{} fitted on {}{}\n\n", r.source, r.rows,
                                spec.output, subtracted, fmt::join(id.fit.names, ", "),
                                spec.weight.empty() ? "" : fmt::format(" (weights 1/{}^2)", spec.weight));
  out += identification_text(id);
  if (r.statement) {
    out += '\n';
    out += statement_text(*r.statement);
  }
  return out;
}

std::string json(const verbs::IdentifyResult& r) {
  const TableFitSpec& spec = r.spec;
  const verbs::Identification& id = r.identification;
  nlohmann::ordered_json j;
  j["command"] = "identify";
  j["ccal_version"] = version();
  j["file"] = r.source;
  j["rows"] = r.rows;
  j["input"] = spec.input;
  j["output"] = spec.output;
  j["weight"] = spec.weight.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(spec.weight);
  const nlohmann::ordered_json fit = identification_json(id);
  for (const auto& [key, value] : fit.items()) j[key] = value;
  if (r.statement) j["statement"] = statement_json(*r.statement);
  return j.dump(2) + "\n";
}

}  // namespace ccal::render
