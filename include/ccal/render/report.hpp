#pragma once
// The HTML report of `ccal report` (docs/cli.md): one self-contained page that a lab can attach to a
// calibration record. Every number in it is taken from the JSON output of the verb that computes it
// (`ccal budget`, `ccal montecarlo`, `ccal force`), and each number's cell names its place in that output
// (data-src="budget:/coefficients/2/standard_uncertainty"); the page lists the command line of each verb, so
// that any number can be checked by running it. Charts are Vega-Lite specifications drawn by vega-embed,
// whose scripts the caller passes in (the program embeds them), so the page needs no network.
#include <string>
#include <string_view>
#include <vector>

#include "ccal/verbs/report.hpp"

namespace ccal::render {

// A further section (e.g. an allocation or a design, before and after), placed after the budget: its title
// and its HTML body, which the caller has escaped.
struct ReportSection {
  std::string id;     // the anchor, [a-z0-9-]
  std::string title;  // plain text
  std::string html;
};

struct ReportProvenance {
  std::string config_text;   // the configuration's bytes, as read (hashed and shown in full)
  std::string command_line;  // as typed
  std::string date_utc;      // ISO 8601, e.g. 2026-12-01T07:00:00Z
  // The verbs' own command lines that give the same numbers (without the configuration and --format json),
  // e.g. {"montecarlo", "--trials", "1000000"}; filled by report_commands when empty.
  std::vector<std::string> budget_command, montecarlo_command;
  // With an allocation or a design section: `ccal allocate …` and `ccal design …` likewise (the design's is
  // run with --plan-out designed.toml, whose budget the section shows beside the configuration's).
  std::vector<std::string> allocate_command, design_command;
  // With the statement section: `ccal identify OBS.csv …`, run with `--config CONFIG` (the report's).
  std::vector<std::string> identify_command;
  std::string observations_sha256;  // of the observations file (its CsvTable's), filled by report_commands
  // The run logs the observations were reduced from, as their header records them (`ccal reduce`), filled by
  // report_commands: each log's run, file and SHA-256 in the provenance.
  std::vector<ObservationsHeader::Log> observation_logs;
};

// The provenance's date: now, or SOURCE_DATE_EPOCH (seconds since 1970, the reproducible-builds convention)
// when it is set, as ISO 8601 UTC.
std::string report_date_utc();

// The options of `ccal budget`, `ccal montecarlo`, `ccal allocate`, `ccal design` and `ccal identify` that
// reproduce a report's numbers.
void report_commands(const verbs::ReportResult& result, const verbs::ReportOptions& options,
                     ReportProvenance& provenance);

// The scripts as the text of the page's <script> element (a pickled Report stores its page without them).
std::string script_text(std::string_view scripts);

// The page, with the allocation, the design and the statement sections when the result has them. scripts:
// vega, vega-lite and vega-embed (their UMD builds, concatenated). When the result is a certificate's
// (verbs::gives_certificate), the page is the calibration certificate instead
// (render/certificate_page.cpp): the result in the customer's words, its budget and runs as the annex.
std::string html(const verbs::ReportResult& result, const ReportProvenance& provenance,
                 std::string_view scripts, const std::vector<ReportSection>& extra_sections = {});

}  // namespace ccal::render
