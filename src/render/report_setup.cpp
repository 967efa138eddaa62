// The report's set-up section: every table of the configuration with its values as written, so in the
// configuration's own units ("1e-5 rad", "10 um", "450 s"); the tolerances as one table.
#include <fmt/format.h>
#include <toml++/toml.h>

#include <set>
#include <sstream>

#include "certificate_parts.hpp"
#include "report_html.hpp"

namespace ccal::render::report_html {
namespace {

std::string written(const toml::node& node) {
  if (const auto* s = node.as_string()) return s->get();
  if (const auto* a = node.as_array()) {
    std::string out;
    for (const auto& e : *a) out += (out.empty() ? "" : ", ") + written(e);
    return out;
  }
  if (const auto* t = node.as_table()) {
    std::string out;
    for (const auto& [k, v] : *t)
      out += (out.empty() ? "" : ", ") + std::string(k.str()) + " = " + written(v);
    return out;
  }
  std::ostringstream os;
  node.visit([&os](const auto& v) { os << v; });
  return os.str();
}

// key → value rows of one table (sub-tables and arrays of tables are shown on their own).
std::string key_value_table(const std::string& caption, const toml::table& table) {
  std::string rows;
  for (const auto& [k, v] : table) {
    if (v.is_table() && !v.as_table()->is_inline()) continue;
    if (v.is_array_of_tables()) continue;
    rows += "<tr>" + text_cell(k.str()) + text_cell(written(v)) + "</tr>\n";
  }
  if (rows.empty()) return {};
  return "<table class=\"setup\"><caption>" + escape(caption) + "</caption>\n" + rows + "</table>\n";
}

// An array of tables ([[plan.runs]]) as one table, a column per key.
std::string rows_table(const std::string& caption, const toml::array& rows) {
  std::vector<std::string> keys;
  std::set<std::string> seen;
  for (const auto& r : rows)
    if (const auto* t = r.as_table())
      for (const auto& [k, v] : *t)
        if (seen.insert(std::string(k.str())).second) keys.emplace_back(k.str());
  std::string out = "<table class=\"setup\"><caption>" + escape(caption) + "</caption>\n<tr>";
  for (const auto& k : keys) out += "<th>" + escape(k) + "</th>";
  out += "</tr>\n";
  for (const auto& r : rows) {
    const auto* t = r.as_table();
    if (!t) continue;
    out += "<tr>";
    for (const auto& k : keys) out += text_cell(t->contains(k) ? written(*t->get(k)) : std::string());
    out += "</tr>\n";
  }
  return out + "</table>\n";
}

// In the configuration's order of sources (the catalogue's, as the budget reads them).
std::string tolerance_table(const toml::table& tolerances, const Config& config) {
  std::string out =
      "<table class=\"setup\"><caption>tolerances (as "
      "configured)</caption>\n<tr><th>source</th><th>bound</th>"
      "<th>distribution</th><th>group</th><th>cost</th></tr>\n";
  for (const Tolerance& tolerance : config.tolerances) {
    const toml::node* node = tolerances.get(tolerance.id);
    if (!node) continue;
    const std::string& k = tolerance.id;
    const toml::node& v = *node;
    std::string bound = written(v), distribution = "normal", group, cost = "1";
    if (const auto* t = v.as_table()) {
      bound = t->contains("bound") ? written(*t->get("bound")) : std::string();
      if (t->contains("distribution")) distribution = written(*t->get("distribution"));
      if (t->contains("group")) group = written(*t->get("group"));
      if (t->contains("cost")) cost = written(*t->get("cost"));
    }
    out += "<tr>" + text_cell(k) + text_cell(bound) + text_cell(distribution) + text_cell(group) +
           text_cell(cost) + "</tr>\n";
  }
  return out + "</table>\n";
}

void add_tables(const std::string& name, const toml::table& table, const Config& config, std::string& out) {
  if (name == "tolerances") {
    out += tolerance_table(table, config);
    return;
  }
  out += key_value_table(name, table);
  for (const auto& [k, v] : table) {
    const std::string sub = name + "." + std::string(k.str());
    if (v.is_table() && !v.as_table()->is_inline()) add_tables(sub, *v.as_table(), config, out);
    if (v.is_array_of_tables()) out += rows_table(sub, *v.as_array());
  }
}

}  // namespace

std::string setup_section(const Config& config, std::string_view config_text) {
  std::string out = fmt::format(
      "<section id=\"setup\"><h2>Set-up</h2>\n<p>Configuration <code>{}</code>, every value as written in "
      "it (its units); the whole file is under <a href=\"#provenance\">Provenance</a>.</p>\n<div "
      "class=\"setup-grid\">\n",
      escape(certificate_parts::base_name(config.source)));
  try {
    const toml::table root = toml::parse(config_text, config.source);
    for (const auto& [k, v] : root)
      if (v.is_table()) add_tables(std::string(k.str()), *v.as_table(), config, out);
  } catch (const toml::parse_error& e) {
    out += "<p>The configuration text could not be read again: " + escape(e.description()) + "</p>\n";
  }
  return out + "</div>\n</section>\n";
}

}  // namespace ccal::render::report_html
