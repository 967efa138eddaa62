#!/usr/bin/env python3
"""A report of a configuration with [[correlations]]: the bundled example with two pairs (the ripples that
cancel on K2, the two tilts of one level) written by `ccal report`, its numbers traced by
check_report_structure.py, and the inputs' correlation matrix shown: a table of the correlated sources whose
every r is the budget's, and the cross terms' line in each coefficient's budget.

    check_correlated_report.py CCAL EXAMPLE.toml FOLDER

Exit 1 with one line per problem."""
import os
import re
import subprocess
import sys

PAIRS = """
[[correlations]]
between = ["ripple1_c1", "ripple3_c1"]
r = -0.5

[[correlations]]
between = ["dthy4", "dthy5"]
r = 0.6
"""


def main(program, example_file, folder):
    os.makedirs(folder, exist_ok=True)
    with open(example_file, encoding="utf-8") as f:
        example = f.read()
    config = os.path.join(folder, "correlated.toml")
    with open(config, "w", encoding="utf-8") as f:
        f.write(example + PAIRS)
    page = os.path.join(folder, "correlated.html")
    subprocess.run([program, "report", config, "--trials", "2000", "-o", page], check=True)
    problems = []
    structure = subprocess.run([sys.executable, os.path.join(os.path.dirname(__file__), "check_report_structure.py"),
                                program, page, config], capture_output=True, text=True)
    if structure.returncode != 0:
        problems.append("check_report_structure.py: " + structure.stdout + structure.stderr)
    text = open(page, encoding="utf-8").read()
    table = re.search(r'<table class="input-correlation">.*?</table>', text, re.S)
    if not table:
        problems.append("no table of the inputs' correlation matrix")
    else:
        heads = re.findall(r"<th>([^<]+)</th>", table.group(0))
        # The four paired sources, a header row and a header column each.
        for source in ("ripple1_c1", "ripple3_c1", "dthy4", "dthy5"):
            if heads.count(source) != 2:
                problems.append(f"the matrix does not show {source} as a row and a column: {heads}")
        if len(heads) != 8:
            problems.append(f"the matrix shows sources that no correlation links: {heads}")
        cells = re.findall(r'data-src="budget:/input_correlation/matrix/\d+/\d+"', table.group(0))
        if len(cells) != 16:
            problems.append(f"{len(cells)} matrix cells traced to the budget, not 16")
    cross = re.findall(r'correlations between sources.*?data-src="budget:/input_correlation/share_of_variance/(\w+)"',
                       text, re.S)
    if sorted(set(cross)) != ["K0", "K2", "K3"]:
        problems.append(f"the cross terms' line is not in every coefficient's budget: {cross}")
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
