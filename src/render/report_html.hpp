#pragma once
// Pieces of the HTML report (private to the library): escaping, numbers read from a verb's JSON output into
// table cells that name their source, Vega-Lite charts, and the report's sections.
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "ccal/render/report.hpp"

namespace ccal::render::report_html {

using Json = nlohmann::ordered_json;

// Text as HTML: & < > " ' replaced by entities (safe in element content and in quoted attributes).
std::string escape(std::string_view text);

// A JSON value for a <script> element: every '<' written as \u003c, so that no "</script>" or "<!--" can
// end or change the element.
std::string script_json(const Json& value);

// One verb's JSON output, by the name the cells use ("budget", "montecarlo", "force0", …).
struct Doc {
  std::string name;
  const Json& json;
};

// A number of a verb's output: the value at `pointer` (RFC 6901) in doc, times scale (100 for a share in %),
// with `digits` significant digits, as a table cell that names its source.
std::string num_cell(const Doc& doc, const std::string& pointer, int digits = 4, double scale = 1.0);
// The same number as plain text (no cell), e.g. for a sentence; also names its source.
std::string num_span(const Doc& doc, const std::string& pointer, int digits = 4, double scale = 1.0);
// The same cell, showing 0 where the flag at `zero_if` is true (a budget's contribution below its round-off
// floor, render/budget_parts.hpp): it names the number and the flag (data-round-off="budget:/…") either way,
// so that the check can redo both.
std::string num_cell_or_zero(const Doc& doc, const std::string& pointer, const std::string& zero_if,
                             int digits = 4, double scale = 1.0);
// The ratio of two numbers of the output, numerator / denominator, as a cell that names both
// (data-ratio="design:/a /b"), so that the check can redo the division.
std::string ratio_cell(const Doc& doc, const std::string& numerator, const std::string& denominator,
                       int digits = 3);
// A text of a verb's output (a string at `pointer`, e.g. a rounded figure) as a numeric cell or span that names its
// source (data-text="identify:/statement/…/rounded/estimate"): the check compares it character for character.
std::string text_num_cell(const Doc& doc, const std::string& pointer);
std::string text_num_span(const Doc& doc, const std::string& pointer);
// A text cell (escaped).
std::string text_cell(std::string_view text);

// A chart: a container and its Vega-Lite specification (drawn by the page's script).
std::string chart(const std::string& id, const Json& spec);

// The sections.
std::string setup_section(const Config& config, std::string_view config_text);
std::string budget_section(const Doc& budget, std::size_t top);
std::string paper_section(const Doc& budget, std::size_t top);
std::string montecarlo_section(const Doc& montecarlo, const std::vector<std::string>& advice);
std::string sensed_input_section(const verbs::SensedInputSeries& series, const std::vector<Json>& instants);
// The allocation (`ccal allocate`, doc "allocate"), configured against allocated.
std::string allocation_section(const Doc& allocate, const verbs::AllocateResult& result);
// The design (`ccal design`, doc "design"), configured against designed: the budgets of both plans (docs
// "design-before", "design-after": `ccal budget` of each) and the configured runs (`ccal force --run k`).
struct DesignDocs {
  const Doc& design;
  const Doc& before;
  const Doc& after;
  const std::vector<Doc>& configured_runs;
};
std::string design_section(const DesignDocs& docs);
// Text as a CSS string literal ("…", with " \ < > & and line breaks escaped), e.g. for @page content.
std::string css_string(std::string_view text);
// The calibration statement of the observations (`ccal identify OBS.csv --statement --config CONFIG`, doc "identify").
std::string statement_section(const Doc& identify);
// The calibration history of the certificate's serial number (`ccal history show`, doc "history").
std::string history_section(const Doc& history);

}  // namespace ccal::render::report_html
