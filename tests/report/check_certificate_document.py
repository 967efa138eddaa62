#!/usr/bin/env python3
"""The calibration certificate as a document of its own, and the engineering report beside it, made as a lab makes
them: the bundled lab example (with a revision, the certificate it replaces, the date of receipt) simulated as run
logs, reduced to observations, and `ccal report` given absolute paths, once for the certificate (HTML and PDF) and
once with --engineering. Checked:

- no folder of the machine in either document: the pages (HTML, pdftotext), the PDF's bytes and its metadata;
- the PDF's metadata: title "Certificate <number>", author the laboratory, subject the item and its serial number,
  creation date the page's (SOURCE_DATE_EPOCH);
- no command, option, configuration key or table, or documentation path in the certificate's text;
- page 1's method per coefficient is the annex's, and the statement's (Monte Carlo where its interval is the
  Monte Carlo's);
- ν_eff an integer or ∞, k with two decimals, units typeset (°/s/g², no deg/s/g^2), no number in e-notation;
- the engineering report states the same rounded result as the certificate;
- the certificate's layout in print: no page ends with a heading, no page but the last is more than half blank,
  no text beyond the page's width (pdftotext -bbox-layout, lines below the foot's band left out).

    check_certificate_document.py CCAL WORK_FOLDER

Exit 77 (skipped) without Chromium or poppler-utils; 1 with one line per problem."""
import html.parser
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

HERE = os.path.dirname(os.path.abspath(__file__))
LAB = os.path.join(HERE, "..", "..", "examples", "lab.toml")
LAB_TRUTH = os.path.join(HERE, "..", "..", "examples", "lab_truth.toml")
EPOCH = "1796947200"  # 2026-12-11T00:00:00Z: the page's date, so that the PDF's can be compared


class Page(html.parser.HTMLParser):
    """The visible text of a page (no <head>, <style> or <script>), its h2 headings, and its data-method and data-text
    elements in order."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.text, self.headings, self.methods, self.texts = [], [], [], []
        self._hidden = 0
        self._open = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag in ("head", "style", "script"):
            self._hidden += 1
        if tag == "h2":
            self._open = ("h2", None, [])
        elif "data-method" in a:
            self._open = ("method", a["data-method"], [])
        elif "data-text" in a:
            self._open = ("text", a["data-text"], [])

    def handle_endtag(self, tag):
        if tag in ("head", "style", "script"):
            self._hidden -= 1
        if self._open and tag in ("h2", "td", "span"):
            kind, key, parts = self._open
            value = "".join(parts).strip()
            if kind == "h2":
                self.headings.append(value)
            elif kind == "method":
                self.methods.append((key, value))
            else:
                self.texts.append((key, value))
            self._open = None

    def handle_data(self, data):
        if not self._hidden:
            self.text.append(data)
        if self._open:
            self._open[2].append(data)


def run(*args, env=None):
    r = subprocess.run(list(args), capture_output=True, text=True, env=env)
    if r.returncode != 0:
        sys.exit(f"{' '.join(args)}: exit {r.returncode}\n{r.stderr}")
    return r.stdout


def page_of(path):
    page = Page()
    with open(path, encoding="utf-8") as f:
        page.feed(f.read())
    return page


def layout_problems(pdf, headings, name):
    """Per page the lines of text above the foot's band: the last must not be a heading, and must reach below the
    page's middle on every page but the last; no word beyond the page's right edge."""
    problems = []
    xml = run("pdftotext", "-bbox-layout", pdf, "-")
    xml = re.sub(r"<!DOCTYPE[^>]*>", "", xml).replace('xmlns="http://www.w3.org/1999/xhtml"', "")
    pages = ET.fromstring(xml).findall(".//page")
    for number, page in enumerate(pages, 1):
        width, height = float(page.get("width")), float(page.get("height"))
        lines = []
        for line in page.iter("line"):
            words = [w.text or "" for w in line.iter("word")]
            y = float(line.get("yMax"))
            if y > height - 18 / 25.4 * 72:  # the foot's band (the bottom margin, 18 mm): number and page count
                continue
            lines.append((y, " ".join(words)))
            if float(line.get("xMax")) > width + 0.5:
                problems.append(f"{name} page {number}: '{' '.join(words)[:40]}' runs beyond the page's width")
        if not lines:
            problems.append(f"{name} page {number} is blank")
            continue
        lines.sort()
        last_y, last = lines[-1]
        if last.strip() in headings:
            problems.append(f"{name} page {number} ends with the heading '{last}'")
        # A heading needs some of its section below it: at least 3 lines where the page goes on after it.
        texts = [t.strip() for _, t in lines]
        under = [len(texts) - 1 - k for k, t in enumerate(texts) if t in headings]
        if number < len(pages) and under and 0 < under[-1] < 3:
            problems.append(f"{name} page {number} ends {under[-1]} line(s) after a heading")
        if number < len(pages) and last_y < height / 2:
            problems.append(f"{name} page {number} is more than half blank (its text ends at "
                            f"{100 * last_y / height:.0f} % of its height)")
    return problems


def main(ccal, work):
    for tool in ("pdftotext", "pdfinfo"):
        if not shutil.which(tool):
            print(f"skipped: no {tool} (Debian package poppler-utils)")
            return 77
    if not (shutil.which("chromium") or os.environ.get("CCAL_CHROMIUM")):
        print("skipped: no Chromium to print the PDF with (Debian package chromium)")
        return 77
    # A folder whose name no document may show.
    folder = os.path.join(os.path.abspath(work), "machine-folder-q7x")
    os.makedirs(folder, exist_ok=True)
    os.chdir(folder)
    with open(LAB, encoding="utf-8") as f:
        text = f.read()
    text = text.replace('number = "CAL-2026-0142"\n', 'number = "CAL-2026-0142A"\nrevision = 1\n'
                        'replaces = "CAL-2026-0142"\n').replace("date_of_receipt = 2026-11-23",
                                                                 "date_of_receipt = 2026-11-25")
    config = os.path.join(folder, "lab.toml")
    with open(config, "w", encoding="utf-8") as f:
        f.write(text)
    run(ccal, "simulate", config, "--truth", LAB_TRUTH, "--logs-out", os.path.join(folder, "logs"), "-o", os.devnull)
    observations = os.path.join(folder, "obs.csv")
    run(ccal, "reduce", config, "--logs", os.path.join(folder, "logs"), "--observations-out", observations, "-o",
        os.devnull)
    env = dict(os.environ, SOURCE_DATE_EPOCH=EPOCH, TZ="UTC")
    made = {}
    for name, extra in (("certificate", []), ("engineering", ["--engineering"]),
                        ("certificate-k2", ["--coverage-factor", "2"])):
        html_file, pdf_file = os.path.join(folder, name + ".html"), os.path.join(folder, name + ".pdf")
        run(ccal, "report", config, "--observations", observations, "--trials", "20000", *extra, "-o", html_file,
            "--pdf", pdf_file, env=env)
        made[name] = (html_file, pdf_file)

    problems = []
    for name, (html_file, pdf_file) in made.items():
        with open(html_file, encoding="utf-8") as f:
            page_text = f.read()
        with open(pdf_file, "rb") as f:
            pdf_bytes = f.read()
        pdf_text = run("pdftotext", "-layout", pdf_file, "-")
        info = run("pdfinfo", "-isodates", pdf_file, env=env)
        for where, content in (("HTML", page_text), ("PDF text", pdf_text), ("PDF metadata", info),
                               ("PDF bytes", pdf_bytes.decode("latin-1"))):
            if folder in content or "machine-folder-q7x" in content:
                problems.append(f"the {name}'s {where} shows the machine's folder {folder}")

    cert_html, cert_pdf = made["certificate"]
    info = dict(re.findall(r"^(\w+):\s*(.*)$", run("pdfinfo", "-isodates", cert_pdf, env=env), re.M))
    expected = {"Title": "Certificate CAL-2026-0142A", "Author": "Inertial Test Laboratory, 12 Centrifuge Road, Harbin",
                "Subject": "Calibration certificate of PIGA, pendulous integrating gyro accelerometer, serial number "
                           "SN 0815",
                "CreationDate": "2026-12-11T00:00:00Z"}
    for key, value in expected.items():
        if info.get(key) != value:
            problems.append(f"the certificate PDF's {key} is {info.get(key)!r}, expected {value!r}")

    page = page_of(cert_html)
    visible = "".join(page.text)
    pdf_text = run("pdftotext", "-layout", cert_pdf, "-")
    # Software words: a command, an option, a table or key of the configuration, a documentation path.
    software = [r"\bccal\b", r"(^|\s)--[a-z]", r"\[(tolerances|errors|certificate|site|instrument|identification|"
                r"plan|design)\b", r"\b(date_of_\w+|serial_number|radius_standard|rate_standard|fixed_terms_source|"
                r"g_unit|statement_trials)\b", r"docs/", r"\.md\b", r"\bLPU\b", r"validated"]
    for where, content in (("page", visible), ("PDF", pdf_text)):
        for pattern in software:
            found = re.search(pattern, content, re.M)
            if found:
                problems.append(f"the certificate's {where} has software words: {found.group(0)!r} in "
                                f"'{content[max(0, found.start() - 40):found.end() + 40]}'")
    for needed in ("Calibration certificate", "No. CAL-2026-0142A, revision 1; replaces certificate CAL-2026-0142",
                   "Date of receipt", "2026-11-25", "Model and units", "Traceability",
                   "absolute gravimeter survey", "local acceleration due to gravity", "g = 9.8 m/s²",
                   "dividing-head calibration, certificate CAL-2026-0098", "Annex A: Uncertainty budget",
                   "Annex B: The runs", "End of certificate", "°/s/g²"):
        if needed not in visible:
            problems.append(f"the certificate has no {needed!r}")
    for needed in ("Calibration certificate", "End of certificate", "°/s/g²", "Page 1 of", "CAL-2026-0142A"):
        if needed not in pdf_text:
            problems.append(f"the certificate's PDF has no {needed!r}")

    # The method per coefficient: page 1 = annex = the statement's.
    statement = None
    import json
    statement = json.loads(run(ccal, "identify", observations, "--statement", "--config", config, "--format",
                               "json"))["statement"]
    methods = {}
    for coefficient, text in page.methods:
        methods.setdefault(coefficient, []).append(text)
    for coefficient, c in statement["coefficients"].items():
        shown = methods.get(coefficient, [])
        if len(shown) != 2 or shown[0] != shown[1]:
            problems.append(f"{coefficient}: the result and the annex state the methods {shown}, expected one twice")
            continue
        monte_carlo = c["interval_method"] == "monte_carlo"
        if monte_carlo != shown[0].startswith("Monte Carlo"):
            problems.append(f"{coefficient}: the certificate states '{shown[0]}', the statement's method is "
                            f"{c['interval_method']}")
        if not monte_carlo and c["effective_dof"] is None and shown[0] != "normal (νeff = ∞)":
            problems.append(f"{coefficient}: ν_eff is ∞ but the method reads '{shown[0]}'")

    # Figures and units as a customer reads them.
    for pattern, what in ((r"\b\d+(\.\d+)?[eE][+-]?\d+\b", "a number in e-notation"), (r"deg/|/g\^|\bum\b|\^", "an untypeset unit"),
                          (r"νeff = \d+\.\d", "a fractional ν_eff")):
        found = re.search(pattern, pdf_text)
        if found:
            problems.append(f"the certificate's PDF shows {what}: '{pdf_text[max(0, found.start() - 30):found.end() + 30]}'")
    k_cells = re.findall(r'<tr data-coefficient="[^"]+">(?:<td[^>]*>.*?</td>){4}<td class="num">([^<]*)</td>',
                         open(cert_html, encoding="utf-8").read())
    if not k_cells or any(k != "–" and not re.fullmatch(r"\d+\.\d\d", k) for k in k_cells):
        problems.append(f"the result's k column reads {k_cells}, expected two decimals (or – for Monte Carlo)")

    # The same rounded result in the engineering report.
    engineering = dict(page_of(made["engineering"][0]).texts)
    for key, value in page.texts:
        if engineering.get(key) != value:
            problems.append(f"{key}: the certificate shows {value!r}, the engineering report {engineering.get(key)!r}")
    if not page.texts:
        problems.append("the certificate shows no rounded figure of the statement")

    problems += layout_problems(cert_pdf, set(page.headings), "the certificate")

    # A stated k = 2: every interval not from the Monte Carlo has k = 2.00, its method names the stated k in the
    # result and in the annex alike, and the coverage is worded as EA-4/02 words it, approximately 95 %.
    stated = page_of(made["certificate-k2"][0])
    stated_html = open(made["certificate-k2"][0], encoding="utf-8").read()
    k_cells = re.findall(r'<tr data-coefficient="[^"]+">(?:<td[^>]*>.*?</td>){4}<td class="num">([^<]*)</td>',
                         stated_html)
    if not k_cells or any(k not in ("2.00", "–") for k in k_cells):
        problems.append(f"with a stated k = 2 the result's k column reads {k_cells}, expected 2.00")
    stated_methods = {}
    for coefficient, text in stated.methods:
        stated_methods.setdefault(coefficient, []).append(text)
    for coefficient, shown in stated_methods.items():
        if len(shown) != 2 or shown[0] != shown[1] or not (shown[0].startswith("stated k, ")
                                                            or shown[0].startswith("Monte Carlo")):
            problems.append(f"{coefficient}: with a stated k the result and the annex read {shown}")
    if "coverage probability of approximately 95 %" not in "".join(stated.text):
        problems.append("with a stated k = 2 the certificate does not say 'approximately 95 %'")

    for p in problems:
        print(p, file=sys.stderr)
    print(f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: check_certificate_document.py CCAL WORK_FOLDER")
    sys.exit(main(os.path.abspath(sys.argv[1]), sys.argv[2]))
