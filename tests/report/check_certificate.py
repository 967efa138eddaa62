#!/usr/bin/env python3
"""A lab's calibration end to end, on the bundled lab example (examples/lab.toml, with its [certificate] table):
its test simulated as run logs, the logs reduced with the calibration statement, the certificate written as
HTML and PDF, and what a laboratory files checked:

- the page is a certificate: its fields as the configuration writes them, then the result, the model, the method,
  the traceability, the signature lines, then the annexes (the budget and the runs); the engineering report
  (--engineering) of the same observations has the statement first, then the budget and the provenance;
- the statement's rounded figures on the page are those of `ccal reduce --format json` and of the text's
  "K = (value ± U) unit" lines (or "K = value unit, p = 95 %: [low, high]" where the Monte Carlo's interval is
  stated), character for character;
- the same U of each coefficient by the same method (the LPU's normal k at p = 95 %) in `ccal budget`,
  `ccal allocate` (its configured U), the report's summary and, where the module is importable, Python's budget;
- the statement's covariance is symmetric, positive semi-definite, with u_c² on its diagonal;
- observations reduced with another configuration are refused with exit code 2 naming both SHA-256;
- the PDF (with --pdf; exit 77, skipped, without a Chromium): A4 pages, the certificate's number and the
  rounded K2 interval in its text (pdftotext, where poppler-utils is installed).

    check_certificate.py CCAL WORK_FOLDER [--pdf]

Exit 1 with one line per problem."""
import hashlib
import html.parser
import json
import math
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
LAB = os.path.join(HERE, "..", "..", "examples", "lab.toml")
LAB_TRUTH = os.path.join(HERE, "..", "..", "examples", "lab_truth.toml")
RUNS = ["5g", "10g", "15g", "20g", "25g", "30g"]


class Outline(html.parser.HTMLParser):
    """The ids of the page's top-level header and sections in order, the data-field cells and the data-text
    spans or cells (a rounded figure and the output place it names)."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.blocks, self.fields, self.texts = [], {}, []
        self._open = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag in ("header", "section") and "id" in a:
            self.blocks.append(a["id"])
        if "data-field" in a:
            self._open = ("field", a["data-field"], [])
        elif "data-text" in a:
            self._open = ("text", a["data-text"], [])

    def handle_endtag(self, tag):
        if self._open and tag in ("td", "span"):
            kind, key, parts = self._open
            (self.fields.__setitem__(key, "".join(parts)) if kind == "field"
             else self.texts.append((key, "".join(parts))))
            self._open = None

    def handle_data(self, data):
        if self._open:
            self._open[2].append(data)


def run(ccal, *args, expect=0):
    r = subprocess.run([ccal, *args], capture_output=True, text=True)
    if r.returncode != expect:
        sys.exit(f"ccal {' '.join(args)}: exit {r.returncode}, expected {expect}\n{r.stderr}")
    return r


def main(ccal, work, pdf):
    problems = []
    if pdf and not (shutil.which("chromium") or os.environ.get("CCAL_CHROMIUM")):
        print("skipped: no Chromium to print the PDF with (Debian package chromium)")
        return 77
    os.makedirs(work, exist_ok=True)
    os.chdir(work)
    run(ccal, "simulate", LAB, "--truth", LAB_TRUTH, "--logs-out", "logs", "-o", "simulate.txt")
    logs = [a for r in RUNS for a in ("--log", f"{r}=logs/{r}.csv")]
    reduced = json.loads(run(ccal, "reduce", LAB, *logs, "--statement", "--observations-out", "obs.csv",
                             "--statement-out", "statement.json", "--format", "json").stdout)
    text = run(ccal, "reduce", LAB, *logs, "--statement").stdout
    statement = reduced["statement"]
    with open("statement.json", encoding="utf-8") as f:
        if json.load(f) != statement:
            problems.append("--statement-out statement.json is not the statement of reduce's JSON")

    pages = ["-o", "certificate.html"] + (["--pdf", "certificate.pdf"] if pdf else [])
    run(ccal, "report", LAB, "--observations", "obs.csv", "--trials", "20000", *pages)
    run(ccal, "report", LAB, "--observations", "obs.csv", "--trials", "20000", "--engineering", "-o",
        "engineering.html")
    with open("certificate.html", encoding="utf-8") as f:
        page = f.read()
    outline = Outline()
    outline.feed(page)
    with open("engineering.html", encoding="utf-8") as f:
        engineering = f.read()
    engineering_outline = Outline()
    engineering_outline.feed(engineering)

    # The certificate: its fields, the result, the model, the method, the traceability, the signatures, the
    # annexes; the engineering report: the statement first.
    if "<h1>Calibration certificate</h1>" not in page:
        problems.append("the page is not titled as a calibration certificate")
    expected_blocks = ["certificate", "result", "model", "method", "traceability", "signatures", "annex-budget",
                       "annex-runs"]
    if outline.blocks != expected_blocks:
        problems.append(f"the certificate's parts are {outline.blocks}, expected {expected_blocks}")
    if engineering_outline.blocks[:1] != ["statement"] or "provenance" not in engineering_outline.blocks:
        problems.append(f"the engineering report's sections are {engineering_outline.blocks}, expected the "
                        "statement first and the provenance")
    if dict(engineering_outline.texts) != dict(outline.texts) | dict(engineering_outline.texts):
        problems.append("the engineering report states another rounded result than the certificate")
    for key, value in {"number": "CAL-2026-0142", "serial_number": "SN 0815", "date_of_issue": "2026-12-03",
                       "conditions": "(20 ± 1) °C, instrument at its operating temperature (71 ± 0.05) °C"}.items():
        if outline.fields.get(key) != value:
            problems.append(f"certificate field {key}: the page shows {outline.fields.get(key)!r}, the "
                            f"configuration writes {value!r}")
    for who in ("Calibrated by: A. Engineer", "Approved by: B. Head of Laboratory"):
        if who not in page:
            problems.append(f"no signature line '{who}'")

    # The rounded figures: page = JSON = text.
    shown = dict(outline.texts)
    for name, c in statement["coefficients"].items():
        r = c["rounded"]
        base = f"identify:/statement/coefficients/{name}/rounded"
        # The Monte Carlo's interval (where its check refused the Student-t one) is stated by its ends alone.
        monte_carlo = c["interval_method"] == "monte_carlo"
        figures = [("estimate", r["estimate"]), ("interval/0", r["interval"][0]), ("interval/1", r["interval"][1])]
        if not monte_carlo:
            figures.append(("expanded_uncertainty", r["expanded_uncertainty"]))
        for key, value in figures:
            if shown.get(f"{base}/{key}") != value:
                problems.append(f"{name} {key}: the page shows {shown.get(f'{base}/{key}')!r}, reduce's JSON "
                                f"gives {value!r}")
        if monte_carlo:
            line = (f"  {name} = {r['estimate']} {c['unit']}, p = 95 %: [{r['interval'][0]}, {r['interval'][1]}] "
                    "(the Monte Carlo's interval, JCGM 101)")
        else:
            line = (f"  {name} = ({r['estimate']} ± {r['expanded_uncertainty']}) {c['unit']}, "
                    f"k = {c['coverage_factor']:.3f}, p = 95 %: [{r['interval'][0]}, {r['interval'][1]}]")
        if line not in text:
            problems.append(f"the text has no line {line!r}")

    # Every log by run, file, SHA-256 and logged span: in the observations file's header and in the page's
    # provenance.
    with open("obs.csv", encoding="utf-8") as f:
        observations = f.read()
    for r in RUNS:
        with open(f"logs/{r}.csv", "rb") as f:
            digest = hashlib.sha256(f.read()).hexdigest()
        line = f"# ccal log v1; run={r}; sha256={digest}; duration=450; file=logs/{r}.csv"
        if line not in observations:
            problems.append(f"obs.csv has no line {line!r}")
        if f'data-run="{r}">{r}: <code>logs/{r}.csv</code>, SHA-256 <code>{digest}</code>' not in engineering:
            problems.append(f"the provenance does not name log {r} with its SHA-256 {digest}")
    if f'<code id="observations-sha256">{hashlib.sha256(observations.encode()).hexdigest()}</code>' not in engineering:
        problems.append("the provenance does not name the observations' SHA-256")

    # What the logs measured is in the observations file and credited on the page: the table of inputs names the
    # six the encoders measured (the drives' rates, the mismatch, both ripples' first harmonics).
    for i in ("domega", "dOmega", "ripple1_c1", "ripple1_s1", "ripple3_c1", "ripple3_s1"):
        if f"# ccal measured v1; id={i};" not in observations:
            problems.append(f"obs.csv does not record that the logs measured {i}")
    if "6 measured in this test" not in engineering or 'class="statement-inputs"' not in engineering:
        problems.append("the page's table of Type B inputs does not say that 6 were measured in this test")

    # One U per method: budget, allocate's configured U, the report's summary, Python.
    budget = json.loads(run(ccal, "budget", LAB, "--format", "json").stdout)
    allocate = json.loads(run(ccal, "allocate", LAB, "--target", "K3=0.04 deg/s/g^3", "--verify-trials", "0",
                              "--format", "json").stdout)
    budget_u = {c["id"]: c["expanded_uncertainty"] for c in budget["coefficients"]}
    for name, c in allocate["coefficients"].items():
        if not math.isclose(c["configured_expanded"], budget_u[name], rel_tol=1e-12):
            problems.append(f"{name}: allocate's configured U {c['configured_expanded']} is not budget's "
                            f"{budget_u[name]}")
    for k, (name, u) in enumerate(budget_u.items()):
        cell = re.search(rf'data-src="budget:/coefficients/{k}/expanded_uncertainty"[^>]*>([^<]*)<', engineering)
        if not cell or not math.isclose(float(cell.group(1)), u, rel_tol=5e-4):
            problems.append(f"{name}: the report's summary U {cell and cell.group(1)} is not budget's {u:.4g}")
    # Python: Debian's interpreter, which has numpy (the module's PYTHONPATH from ctest).
    python = "/usr/bin/python3" if os.path.exists("/usr/bin/python3") else sys.executable
    got = subprocess.run([python, "-c", "import ccal, sys; "
                          "sys.stdout.write(ccal.budget(ccal.load_config(sys.argv[1])).to_json())", LAB],
                         capture_output=True, text=True)
    if got.returncode != 0:
        problems.append(f"Python's budget failed: {got.stderr.strip()[-400:]}")
    else:
        for c in json.loads(got.stdout)["coefficients"]:
            if not math.isclose(c["expanded_uncertainty"], budget_u[c["id"]], rel_tol=1e-12):
                problems.append(f"{c['id']}: Python's U {c['expanded_uncertainty']} is not budget's "
                                f"{budget_u[c['id']]}")

    # The covariance: symmetric, PSD, u_c² on the diagonal (1e-12 relative: the same parts, summed two ways).
    cov = statement["covariance"]["combined"]
    names = statement["covariance"]["order"]
    n = len(names)
    for i in range(n):
        u = statement["coefficients"][names[i]]["combined_standard_uncertainty"]
        if not math.isclose(cov[i][i], u * u, rel_tol=1e-12):
            problems.append(f"covariance[{i}][{i}] = {cov[i][i]} is not u_c² = {u * u}")
        for j in range(n):
            if cov[i][j] != cov[j][i]:
                problems.append(f"covariance[{i}][{j}] ≠ covariance[{j}][{i}]")
    # Positive semi-definite: a Cholesky factorisation of C + ε·diag(C) succeeds (ε = 1e-12 absorbs round-off).
    a = [[cov[i][j] + (1e-12 * cov[i][i] if i == j else 0) for j in range(n)] for i in range(n)]
    for j in range(n):
        d = a[j][j] - sum(a[j][k] ** 2 for k in range(j))
        if d <= 0:
            problems.append(f"the covariance is not positive semi-definite (pivot {j}: {d})")
            break
        a[j][j] = math.sqrt(d)
        for i in range(j + 1, n):
            a[i][j] = (a[i][j] - sum(a[i][k] * a[j][k] for k in range(j))) / a[j][j]

    # Another configuration's observations are refused, naming both fingerprints.
    with open(LAB, encoding="utf-8") as f:
        other = f.read().replace('dR_s = "25 um"', 'dR_s = "30 um"')
    with open("other.toml", "w", encoding="utf-8") as f:
        f.write(other)
    refused = run(ccal, "report", "other.toml", "--observations", "obs.csv", "--trials", "20000", "-o",
                  "other.html", expect=2)
    hashes = re.findall(r"[0-9a-f]{64}", refused.stderr)
    if len(set(hashes)) < 2 or os.path.exists("other.html"):
        problems.append(f"a report of other observations: {refused.stderr.strip()!r}, expected both SHA-256 "
                        "named and no page")

    if pdf:
        with open("certificate.pdf", "rb") as f:
            if not f.read(5) == b"%PDF-":
                problems.append("certificate.pdf is no PDF")
        if shutil.which("pdfinfo"):
            info = subprocess.run(["pdfinfo", "certificate.pdf"], capture_output=True, text=True).stdout
            if "(A4)" not in info:
                problems.append(f"certificate.pdf's pages are not A4: {info}")
        if shutil.which("pdftotext"):
            pdf_text = subprocess.run(["pdftotext", "-layout", "certificate.pdf", "-"], capture_output=True,
                                      text=True).stdout
            k2 = statement["coefficients"]["K2"]["rounded"]
            for expected in ("Calibration certificate", "CAL-2026-0142", "Page 1 of", k2["interval"][0],
                             k2["interval"][1], "Approved by: B. Head of Laboratory"):
                if expected not in pdf_text:
                    problems.append(f"certificate.pdf's text has no {expected!r}")

    for p in problems:
        print(p, file=sys.stderr)
    print(f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit("usage: check_certificate.py CCAL WORK_FOLDER [--pdf]")
    sys.exit(main(os.path.abspath(sys.argv[1]), sys.argv[2], "--pdf" in sys.argv[3:]))
