#!/usr/bin/env python3
"""The report of an instrument's third calibration with its history (`ccal report --history-db`): the lab example
simulated three years running with K2 drifting by 2e-4 deg/s/g^2 a year, each year reduced with the statement and
recorded in a history store; the third year's certificate then shows the history section (a chart and a table per
coefficient, three calibrations each, the drift), every number traced by check_report_structure.py to `ccal history
show`'s JSON.

    check_history_report.py CCAL LAB.toml LAB_TRUTH.toml FOLDER

Exit 1 with one line per problem."""
import os
import re
import subprocess
import sys

RUNS = ["5g", "10g", "15g", "20g", "25g", "30g"]


def run(*args):
    subprocess.run(args, check=True, capture_output=True, text=True)


def main(program, lab, truth, folder):
    os.makedirs(folder, exist_ok=True)
    os.chdir(folder)
    text = open(lab, encoding="utf-8").read()
    db = os.path.abspath("history.sqlite")
    if os.path.exists(db):
        os.remove(db)
    for year in range(3):
        config = f"lab{year}.toml"
        with open(config, "w", encoding="utf-8") as f:
            f.write(text.replace('K2 = "0.02 deg/s/g^2"', f'K2 = "{0.02 + 2e-4 * year:.4f} deg/s/g^2"')
                        .replace("date_of_receipt = 2026-11-23", f"date_of_receipt = {2024 + year}-11-23")
                        .replace("date_of_calibration = 2026-11-30", f"date_of_calibration = {2024 + year}-11-30")
                        .replace("date_of_issue = 2026-12-03", f"date_of_issue = {2024 + year}-12-03"))
        run(program, "simulate", config, "--truth", truth, "--logs-out", f"logs{year}", "-o", os.devnull)
        logs = [a for r in RUNS for a in ("--log", f"{r}=logs{year}/{r}.csv")]
        run(program, "reduce", config, *logs, "--statement", "--statement-trials", "0", "--statement-out",
            f"statement{year}.json", "--observations-out", f"obs{year}.csv", "-o", os.devnull)
        run(program, "history", "add", f"statement{year}.json", "--db", db)
    run(program, "report", "lab2.toml", "--observations", "obs2.csv", "--history-db", db, "--trials", "2000",
        "--statement-trials", "0", "--engineering", "-o", "certificate.html")  # the history is the engineers'
    problems = []
    structure = subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                             "check_report_structure.py"),
                                program, "certificate.html", "lab2.toml"], capture_output=True, text=True)
    if structure.returncode != 0:
        problems.append("check_report_structure.py: " + structure.stdout + structure.stderr)
    page = open("certificate.html", encoding="utf-8").read()
    section = re.search(r'<section id="history">.*?</section>', page, re.S)
    if not section:
        problems.append("no history section in the third calibration's certificate")
    else:
        s = section.group(0)
        for k in ("K0", "K2", "K3"):
            if f'id="history-{k}"' not in s and f"history-{k}" not in s:
                problems.append(f"no history chart of {k}")
        rows = re.findall(r"<tr><th>20\d\d-11-30</th>", s)
        if len(rows) != 9:
            problems.append(f"{len(rows)} calibration rows, not 3 for each of K0, K2, K3")
        if s.count("Drift: ") != 3 or "per year" not in s:
            problems.append("no drift line stated for each coefficient")
        if s.count("history:/coefficients/K2/normalised_errors/") != 2:
            problems.append("E_n of K2 is not traced to `ccal history show` twice")
        # Each year's configuration differs only in the instrument's K2 and the dates: one machine set-up, whose
        # shared Type B the section says it takes out, with no change between the years; the table names each
        # calibration's set-up.
        if not re.search(r"Set-ups: S1 \(<code>[0-9a-f]{12}</code>: #1, #2, #3\)\.", s) or "another set-up" in s:
            problems.append("the one set-up of the three calibrations is not stated, or a change is")
        if s.count("<th>set-up</th>") != 3:
            problems.append("no set-up column in each coefficient's table")
    # The store is named by its file name: no folder of the machine anywhere in the page.
    if os.path.dirname(db) in page:
        problems.append(f"the page names the folder {os.path.dirname(db)}")
    # The charts' date axis shows the year on every tick.
    if page.count('"format":"%Y-%m-%d"') + page.count('"format": "%Y-%m-%d"') < 3:
        problems.append("the history charts' date axis has no year in its format")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
