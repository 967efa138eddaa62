// ccal.report: `ccal report` from Python (docs/python.md): the same sections from the same options
// (verbs::ReportOptions, by its table), the same page.
#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "bindings.hpp"
#include "ccal/core/errors.hpp"
#include "ccal/io/config_file.hpp"
#include "ccal/io/observation_csv.hpp"
#include "ccal/render/pdf_print.hpp"
#include "ccal/render/report.hpp"
#include "ccal/verbs/report.hpp"
#include "interruptible.hpp"
#include "option_keywords.hpp"
#include "report_scripts.hpp"

namespace ccal::python {
namespace {

// report's run= as everywhere in Python: a run's name or a 0-based index (the command line's --run is 1-based),
// as the run's name; the other keywords into `rest`.
std::optional<std::string> run_keyword(const Config& cfg, const py::kwargs& keywords, py::kwargs& rest) {
  std::optional<std::string> run;
  for (const auto& [key, value] : keywords) {
    if (py::str(key).cast<std::string>() != "run") {
      rest[key] = value;
    } else if (py::isinstance<py::str>(value)) {
      run = cfg.plan.runs[run_index(cfg, value.cast<std::string>())].name;
    } else if (py::isinstance<py::int_>(value) && !py::isinstance<py::bool_>(value)) {
      run = cfg.plan.runs[run_index(cfg, value.cast<int>())].name;
    } else {
      keywords::wrong_type("run", "a run's name (str) or its 0-based index (int)", value);
    }
  }
  return run;
}

// A report and the options it was made with, which its page's provenance lists as command lines.
struct Report {
  verbs::ReportResult result;
  verbs::ReportOptions options;
};

// The text of a page's charting scripts: a Report pickled by value stores its page without it.
void bind_report_scripts(py::module_& m) {
  m.def(
      "_report_script_text", [] { return render::script_text(required_report_scripts()); },
      "The text of a report page's <script> element of vega, vega-lite and vega-embed: a Report pickled by value "
      "stores its page without it.");
}

}  // namespace

void bind_report(py::module_& m) {
  py::class_<Report>(m, "Report",
                     "`ccal report`: the sections' results (budget, monte_carlo, and allocation, design, observed "
                     "when asked for); to_html() is the page the CLI writes.",
                     py::dynamic_attr())  // the call that made it: python/ccal/_results.py
      .def_property_readonly(
          "config", [](const Report& r) { return r.result.config; }, "the configuration [Config]")
      .def_property_readonly(
          "budget", [](const Report& r) { return r.result.budget; }, "the budget section [Budget]")
      .def_property_readonly(
          "monte_carlo",
          [](const Report& r) -> std::optional<verbs::MonteCarloResult> {
            if (r.result.certificate) return std::nullopt;
            return r.result.monte_carlo;
          },
          "the Monte Carlo section, or None for a certificate, which shows none [MonteCarlo]")
      .def_property_readonly(
          "warnings", [](const Report& r) { return r.result.warnings; },
          "what the laboratory should know (e.g. inputs of a certificate's budget traceable to no stated "
          "standard) [list[str]]")
      .def_property_readonly(
          "certificate", [](const Report& r) { return r.result.certificate; },
          "whether the page is the calibration certificate (observations, a [certificate] table, not "
          "engineering=True): it shows the statement and its budget, not the tolerances' Monte Carlo [bool]")
      .def_property_readonly(
          "allocation", [](const Report& r) { return r.result.allocation; },
          "the allocation section, or None [Allocation]")
      .def_property_readonly(
          "design", [](const Report& r) { return r.result.design; }, "the design section, or None [Design]")
      .def_property_readonly(
          "observed", [](const Report& r) { return r.result.observed; },
          "the observations with their calibration statement, or None [Identification]")
      .def(
          "_html",
          [](const Report& r, std::optional<std::string> config_text, const std::string& command_line) {
            const std::string_view scripts = required_report_scripts();
            render::ReportProvenance p;
            if (config_text)
              p.config_text = *config_text;
            else if (r.result.config.source.rfind("bundled:", 0) == 0)
              p.config_text = std::string(bundled_example_text());
            else
              throw InputError("report: the configuration's text is not known (a Config of load_config, "
                               "parse_config or bundled_example has it)");
            p.command_line = command_line;
            p.date_utc = render::report_date_utc();
            render::report_commands(r.result, r.options, p);
            return render::html(r.result, p, scripts);
          },
          py::arg("config_text"), py::arg("command_line"),
          "The page for the configuration's text and the call that made the report (to_html() gives them).")
      .def_static(
          "_print_pdf",
          [](const std::string& html) {
            std::string pdf;
            {
              py::gil_scoped_release release;  // the browser takes seconds
              pdf = print_pdf(html);
            }
            return py::bytes(pdf);
          },
          py::arg("html"), "A page printed to PDF by headless Chromium (render/pdf_print.hpp), as bytes (to_pdf()).");

  bind_report_scripts(m);
  m.def(
      "report",
      [](const Config& cfg, const std::optional<TargetMap>& allocate_targets, bool design,
         const std::optional<TargetMap>& design_targets, const py::object& observations,
         const py::kwargs& keywords) {
        Report r;
        py::kwargs rest;
        const std::optional<std::string> run = run_keyword(cfg, keywords, rest);
        r.options = options_from_keywords<verbs::ReportOptions>(
            rest, "report", {}, {}, {"config", "allocate_targets", "design", "design_targets", "observations"});
        verbs::ReportOptions& o = r.options;
        if (run) o.run = *run;
        if (allocate_targets) o.allocate = verbs::report_allocation(target_texts(*allocate_targets), o);
        if (design || design_targets)
          o.design = verbs::report_design(
              design_targets ? target_texts(*design_targets) : std::vector<std::string>{}, o);
        if (!observations.is_none())
          o.observations = read_csv_file(path_argument(observations, "report", "observations",
                                                       "the path of an observations CSV file (str or os.PathLike)"));
        r.result = run_interruptible(py::none(), [&](ProgressCallback on_progress) {
          verbs::ReportOptions with_progress = o;
          with_progress.monte_carlo.on_progress = std::move(on_progress);
          return verbs::report(cfg, with_progress);
        });
        return r;
      },
      py::arg("config"), py::kw_only(), py::arg("allocate_targets") = py::none(), py::arg("design") = false,
      py::arg("design_targets") = py::none(), py::arg("observations") = py::none(),
      "`ccal report`: the budget, Monte Carlo, exact-vs-paper and sensed-input sections, and with "
      "allocate_targets (as allocate's targets) the allocation, with design or design_targets the design, with "
      "observations (an observations CSV path) the calibration statement; to_html() is the self-contained page. "
      "Ctrl-C stops the call and raises KeyboardInterrupt.");
  record_keywords<verbs::ReportOptions>(m, "report", {}, {{"run", "Union[int, str]"}});
}

}  // namespace ccal::python
