#!/usr/bin/env python3
"""The test layout of docs/testing.md: every library source src/<layer>/<unit>.cpp has its test file
tests/<layer>/<unit>_test.cpp, or is listed below with the test files that exercise it instead; every test file
of a layer's folder is named after a unit of that layer (<unit>_test.cpp, or <unit>_<aspect>_test.cpp for a
further aspect of a large unit), so that the tests of unit X are found by its name; and every path under
tests/ that the documents describing the tests name exists. Exit 1 with one line per violation."""
import pathlib
import re
import sys

# The documents that describe where the tests are (docs/testing.md's layout, the README's Layout table).
DOCUMENTS = ["docs/testing.md", "docs/architecture.md", "README.md"]
# A path under tests/ as the documents write it; one with a placeholder (<unit>) or a pattern (*) is skipped.
DOC_PATH = re.compile(r"(?<![\w/.])tests/[A-Za-z0-9_./<>*-]*[A-Za-z0-9_/]")

LAYERS = ["core", "model", "setup", "reduction", "io", "intake", "uncertainty", "history", "verbs", "render"]

# Sources tested through other test files, with where. A source gets its own test file when it gains tests.
_OUTPUT = "the program's output: tests/cli/<verb>_test.cpp and tests/system/golden_outputs_test.cpp"
_REPORT = "a section of the HTML report: tests/render/report_test.cpp and the report.* tests (tests/report/)"
TESTED_ELSEWHERE = {
    "core/format.cpp": "number formatting: tests/render/budget_test.cpp and the pinned outputs",
    "io/config_sections_design.cpp": "the [design] table: tests/verbs/design_test.cpp (DesignConfig)",
    "io/config_sections_plan.cpp": "the [plan] and [identification] keys: tests/io/config_file*_test.cpp",
    "history/history_entry.cpp": "history_entry: tests/history/history_store_test.cpp, history_store_schema_test.cpp",
    "io/csv_stream.cpp": "the CSV reader: tests/io/observation_csv*_test.cpp, tests/intake/run_log_reducer_test.cpp",
    "io/observations_header.cpp": "the header and log lines: tests/io/observation_csv_test.cpp",
    "intake/run_log_writer.cpp": "logs from the model: tests/verbs/reduce_test.cpp",
    "uncertainty/linear_propagation.cpp": "propagate_linear: tests/uncertainty/montecarlo_test.cpp, "
    "montecarlo_correlations_test.cpp",
    "model/centrifuge.cpp": "the error lookup: tests/model/kinematics*_test.cpp",
    "model/instrument.cpp": "the terms: tests/io/config_file_test.cpp, tests/io/observation_csv_test.cpp",
    "model/sensed_input.cpp": "evaluate_force: tests/model/plan_test.cpp, tests/verbs/force_test.cpp",
    "reduction/run_means_nodes.cpp": "the kernel's nodes: tests/reduction/run_means_test.cpp",
    "render/budget_text.cpp": "the budget's text: tests/render/budget_test.cpp",
    "verbs/history.cpp": "history add and show: tests/cli/history_test.cpp",
    "render/design_plan.cpp": "the designed [plan]: tests/verbs/design_test.cpp (DesignPlanText)",
    "render/report_allocate.cpp": _REPORT,
    "render/report_budget.cpp": _REPORT,
    "render/certificate_result.cpp": "the certificate: tests/render/certificate_page_test.cpp, tests/report/check_certificate_document.py (report.certificate_document)",
    "render/report_design.cpp": _REPORT,
    "render/report_html.cpp": _REPORT,
    "render/report_montecarlo.cpp": _REPORT,
    "render/report_setup.cpp": _REPORT,
    "render/report_statement.cpp": _REPORT,
    "render/table.cpp": "the text tables: tests/render/budget_test.cpp (Table)",
    "setup/certificate.cpp": "the dates and the traceability: tests/io/config_sections_certificate_test.cpp (CertificateDates, CertificateTraceability)",
    "setup/config.cpp": "Config::experiment: tests/io/config_file_test.cpp",
    "setup/input_description.cpp": "each input's units: tests/io/config_sections_inputs_test.cpp",
    "io/config_sections_tolerances.cpp": "[tolerances]: tests/io/config_file_test.cpp, "
    "tests/io/config_sections_inputs_test.cpp",
    "setup/tolerance.cpp": "σ and divisor of each distribution: tests/io/config_file_test.cpp, "
    "tests/uncertainty/budget_groups_test.cpp, montecarlo_test.cpp",
    "uncertainty/allocate_tolerances.cpp": "a part of the allocation: tests/uncertainty/allocate_test.cpp",
    "uncertainty/allocate_barrier.cpp": "a part of the allocation's solver: tests/uncertainty/allocate_test.cpp "
    "(BadlyScaledProblemsAreSolvedToo)",
    "uncertainty/allocate_bounds.cpp": "a part of the allocation's solver: "
    "tests/uncertainty/allocate_guards_test.cpp",
    "uncertainty/allocation_verdict.cpp": "a part of the allocation: tests/uncertainty/allocate_test.cpp",
    "setup/coefficient_target.cpp": "the targets: tests/uncertainty/allocate_test.cpp (AllocationTargets), "
    "tests/verbs/allocate_test.cpp",
    "uncertainty/calibration_model.cpp": "the trial model: tests/uncertainty/montecarlo_test.cpp",
    "uncertainty/design_candidates.cpp": "the candidate runs: tests/verbs/design_test.cpp; the rounding to the machine's settings: tests/uncertainty/design_candidates_rounding_test.cpp",
    "uncertainty/design_exchange.cpp": "the exchange step: tests/uncertainty/design_search_test.cpp",
    "uncertainty/montecarlo_checks.cpp": "the run's checks: tests/cli/hardening_test.cpp, tests/cli/bad_inputs_test.cpp",
    "uncertainty/montecarlo_validation.cpp": "tests/uncertainty/montecarlo_distribution_test.cpp",
    "verbs/budget.cpp": "verbs::budget: tests/render/budget_test.cpp, tests/verbs/allocate_test.cpp",
    "verbs/identification.cpp": "tests/verbs/identify_test.cpp, tests/reduction/fit_ill_posed_test.cpp",
    "verbs/observability_report.cpp": "tests/cli/observability_test.cpp, tests/verbs/simulate_test.cpp",
    "verbs/report.cpp": "verbs::report: tests/render/report_test.cpp (ReportSections)",
    "verbs/result_checks.cpp": "the checks of every verb's result: tests/verbs/*_test.cpp",
}


def units_of(root, layer):
    """Names of the layer's units: its sources and headers (public and private), without the suffix."""
    names = {p.stem for p in (root / "src" / layer).glob("*.[ch]pp")}
    return names | {p.stem for p in (root / "include" / "ccal" / layer).glob("*.hpp")}


def main(root):
    root = pathlib.Path(root).resolve()
    problems = []
    sources = sorted(p.relative_to(root / "src").as_posix() for layer in LAYERS
                     for p in (root / "src" / layer).glob("*.cpp"))
    for source in sources:
        layer, unit = source[:-len(".cpp")].split("/")
        test = root / "tests" / layer / f"{unit}_test.cpp"
        if source in TESTED_ELSEWHERE:
            if test.exists():
                problems.append(f"src/{source}: has tests/{layer}/{unit}_test.cpp; take it off TESTED_ELSEWHERE")
        elif not test.exists():
            problems.append(f"src/{source}: no test file tests/{layer}/{unit}_test.cpp (add it, or list the "
                            f"source in {pathlib.Path(__file__).name}'s TESTED_ELSEWHERE with where it is tested)")
    for listed in sorted(set(TESTED_ELSEWHERE) - set(sources)):
        problems.append(f"{pathlib.Path(__file__).name}: TESTED_ELSEWHERE names src/{listed}, which does not exist")
    for layer in LAYERS:
        units = units_of(root, layer)
        for test in sorted((root / "tests" / layer).glob("*.cpp")):
            stem = test.stem
            named = stem.endswith("_test") and any(stem[:-len("_test")] == u or
                                                   stem.startswith(u + "_") for u in units)
            if not named:
                problems.append(f"{test.relative_to(root)}: not named <unit>_test.cpp or <unit>_<aspect>_test.cpp "
                                f"after a unit of src/{layer}/ or include/ccal/{layer}/")
    for doc in DOCUMENTS:
        text = (root / doc).read_text(encoding="utf-8")
        for m in DOC_PATH.finditer(text):
            path = m.group(0)
            if "<" not in path and "*" not in path and not (root / path).exists():
                line = text.count("\n", 0, m.start()) + 1
                problems.append(f"{doc}:{line}: {path} does not exist")
    for p in problems:
        print(p)
    print(f"{len(sources)} library sources checked, {len(sources) - len(TESTED_ELSEWHERE)} with their own test "
          f"file, {len(problems)} violation(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parents[1]))
