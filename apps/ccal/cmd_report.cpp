// ccal report: the HTML report of a configuration (budget, Monte Carlo distribution, exact-vs-paper
// comparison, sensed input, provenance; optionally a tolerance allocation and a test-plan design, each before
// and after), one self-contained page with the charting library inlined.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>

#include "atomic_file.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/render/pdf_print.hpp"
#include "ccal/render/report.hpp"
#include "ccal/verbs/report.hpp"
#include "commands.hpp"
#include "option_flags.hpp"
#include "output.hpp"
#include "report_scripts.hpp"

namespace ccal::cli {
namespace {

struct ReportCli {
  ConfigChoice config;
  verbs::ReportOptions options;  // its table's flags, and the Monte Carlo's but for its mode, are bound to it
  std::vector<std::string> allocate_targets;  // non-empty: the allocation section
  bool design = false;                        // the design section
  std::vector<std::string> design_targets;    // the design's targets (imply the section)
  std::string observations;                   // non-empty: the calibration statement section
  std::string pdf;                            // non-empty: the page printed to this PDF file too
  OutputOptions output;
};

// Before the long computation: the PDF file is not the page's, and there is a browser to print it with.
void check_pdf(const std::string& pdf, const OutputOptions& output) {
  if (pdf.empty()) return;
  if (!output.path.empty() && same_file(pdf, output.path))
    throw InputError(fmt::format("--pdf: '{}' is also the -o file; accepted: two different files", pdf));
  try {
    require_pdf_browser();
  } catch (const InputError& e) {
    throw InputError(std::string("--pdf: ") + e.what());
  }
}

// Without -o, the page (some 1 MB of HTML with the charting library inlined) would scroll through a terminal:
// refused before the work, saying where to put it; to a file or a pipe it goes as asked, and `-o -` sends it
// to standard output whatever that is. With --pdf alone only the PDF is written.
void refuse_page_on_terminal(const OutputOptions& output, const std::string& pdf) {
  if (output.path.empty() && pdf.empty() && isatty(STDOUT_FILENO) != 0)
    throw InputError(
        "report: the HTML page (about 1 MB) would be written to the terminal; accepted: -o FILE.html (e.g. "
        "-o report.html), --pdf FILE.pdf, a redirection (> report.html) or a pipe, or -o - for standard "
        "output all the same");
}

// The page as a PDF (InputError naming --pdf).
std::string pdf_of(const std::string& page) {
  try {
    return print_pdf(page);
  } catch (const InputError& e) {
    throw InputError(std::string("--pdf: ") + e.what());
  }
}

// The observations file, or an error naming --observations.
CsvTable read_observations(const std::string& path) {
  note_input(path);
  try {
    return read_csv_file(path);
  } catch (const InputError& e) {
    throw InputError(std::string("--observations: ") + e.what());
  }
}

// Runs `ccal report`: the page (or the certificate) of the configuration, written as HTML, printed to PDF or
// both.
void run_report(ReportCli& o) {
  refuse_page_on_terminal(o.output, o.pdf);
  const std::string_view scripts = required_report_scripts();  // before the long computation
  check_pdf(o.pdf, o.output);
  verbs::ReportOptions ro = o.options;
  note_input(ro.history_db);       // the history store is read: never replaced by the page
  ro.monte_carlo.progress = true;  // drawn only when standard error is a terminal
  if (!o.allocate_targets.empty()) {
    ro.allocate = verbs::report_allocation(o.allocate_targets, ro);
    ro.allocate->progress = true;
  }
  if (o.design || !o.design_targets.empty()) ro.design = verbs::report_design(o.design_targets, ro);
  if (!o.observations.empty()) ro.observations = read_observations(o.observations);
  const Config config = load_config_or_example(o.config);
  const verbs::ReportResult r = verbs::report(config, ro);
  print_warnings(r.warnings);
  render::ReportProvenance p;
  p.config_text = config_file_text(o.config.path);
  p.command_line = command_line_text();
  p.date_utc = render::report_date_utc();
  render::report_commands(r, ro, p);
  const std::string page = render::html(r, p, scripts);
  if (o.pdf.empty()) return write_output(o.output, page);
  std::string bytes = pdf_of(page);
  if (o.output.path.empty())
    write_files({{"--pdf", o.pdf, std::move(bytes), {}}});
  else
    write_outputs(o.output, page, {{"--pdf", o.pdf, std::move(bytes)}});
}

}  // namespace

Command add_report(CLI::App& app) {
  auto o = std::make_shared<ReportCli>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "HTML report: budget, Monte Carlo distribution, exact vs paper, sensed input, provenance; optionally "
      "a tolerance allocation and a test-plan design, each against the configured one, and, with "
      "observations, the calibration statement and certificate (also printed to PDF)");
  add_config_argument(*cmd, o->config);
  add_option_flags(*cmd, o->options, option_table<verbs::ReportOptions>());
  // An empty --run (an unset shell variable) would be taken as none given: the run of highest g-level.
  cmd->get_option("--run")->each([](const std::string& run) {
    if (run.empty())
      throw CLI::ParseError("--run: '' names no run; accepted: a run name or a 1-based index, or --run left out "
                            "for the run of highest g-level",
                            CLI::ExitCodes::ValidationError);
  });
  cmd->add_option("--allocate-target", o->allocate_targets,
                  "COEFF=U: add the tolerance allocation (as `ccal allocate --target`, with this report's "
                  "--mode, --coverage-probability, --seed and --threads); repeat for each coefficient")
      ->allow_extra_args(false)
      ->type_name("COEFF=U");
  cmd->add_flag("--design", o->design,
                "Add the test-plan design (as `ccal design` with the configuration's [design] table)");
  cmd->add_option(
         "--design-target", o->design_targets,
         "COEFF=U: the design's target (as `ccal design --target`); implies --design; repeat for each "
         "coefficient")
      ->allow_extra_args(false)
      ->type_name("COEFF=U");
  cmd->add_option("--observations", o->observations,
                  "OBS.csv: add the calibration statement of these observations (as `ccal identify OBS.csv "
                  "--statement --config CONFIG` with this report's --mode and --coverage-probability)")
      ->type_name("OBS.csv");
  o->output.format = "html";
  refuse_empty_output(
      *cmd->add_option("-o,--output", o->output.path,
                       "Write the page to FILE ('-': standard output; without -o the page goes to standard "
                       "output only when that is not a terminal)")
           ->type_name("FILE.html"));
  refuse_empty_path(cmd->add_option("--pdf", o->pdf,
                                    "Print the page to FILE as PDF (A4), through headless Chromium (Debian's "
                                    "chromium, or the program named by CCAL_CHROMIUM); without -o only the PDF "
                                    "is written"),
                    "--pdf", "a file path, e.g. certificate.pdf")
      ->type_name("FILE.pdf");
  cmd->footer(
      "Examples:\n"
      "  ccal report -o report.html\n"
      "      the report of the bundled paper example (opens in any browser, with no network)\n"
      "  ccal report my.toml --trials 100000 --run 20g -o my-report.html\n"
      "  ccal report --allocate-target K2=2e-5 --allocate-target K3=2e-3 --design -o report.html\n"
      "      with the allocation for those targets and the designed plan, each against the configured one\n"
      "      (the same numbers as `ccal allocate --target K2=2e-5 --target K3=2e-3` and `ccal design`)\n"
      "  ccal simulate my.toml --observations-out obs.csv && ccal report my.toml --observations obs.csv\n"
      "      with the calibration statement of the observations (`ccal identify obs.csv --statement "
      "--config my.toml`)\n"
      "  ccal report lab.toml --observations obs.csv --pdf certificate.pdf\n"
      "      the calibration certificate (with lab.toml's [certificate] table) as a PDF to sign and file\n");
  return {cmd, [o] { run_report(*o); }};
}

}  // namespace ccal::cli
