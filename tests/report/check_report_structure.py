#!/usr/bin/env python3
"""The structure of a report of `ccal report`: every number in its tables is the number of the verb output it
names (data-src="budget:/coefficients/2/standard_uncertainty"), formatted with the digits it states, where the
output is the JSON that the program itself prints for the verb's command line listed in the page; sums,
root-sum-squares and ratios of such numbers are redone; a budget contribution shows 0 where the cell's flag
(data-round-off) says it is below the round-off floor, and each flag is redone from the floor; no table cell
shows a number without a source; the charts' data are the same outputs' numbers; the configuration is shown
byte for byte with its SHA-256.

Each output the page names (its "ccal-sources" script) is {"command": [verb, options...]}, run as
`ccal VERB CONFIG OPTIONS --format json`, optionally with "writes": {option: file} (the command also writes
that file, e.g. `ccal design --plan-out designed.toml`) and "config": file (a file written by an earlier
command replaces CONFIG, e.g. `ccal budget designed.toml`), "no_config": true (the command takes none, e.g.
`ccal history show SERIAL --db FILE`) or "config_option": option (CONFIG is given
as that option's value instead of as the first argument, e.g. `ccal identify OBS.csv --statement --config CONFIG`); the
files go to a temporary directory.

    check_report_structure.py CCAL REPORT.html [CONFIG]

Exit 1 with one line per problem."""
import hashlib
import html.parser
import json
import math
import os
import subprocess
import sys
import tempfile
import tomllib


class Page(html.parser.HTMLParser):
    """The numeric cells, the other table cells, the JSON scripts and the configuration text of a page."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.cells, self.plain_cells, self.specs, self.scripts = [], [], [], {}
        self.config_text = None
        self._open = None  # (kind, attributes, text parts) of the element whose text is collected
        self._table_class = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "table":
            self._table_class.append(a.get("class", ""))
        if tag in ("td", "span") and "num" in a.get("class", "").split():
            self._open = ("num", a, [])
        elif tag == "td" and self._table_class:
            self._open = ("plain", dict(a, table=self._table_class[-1]), [])
        elif tag == "script" and a.get("type") == "application/json":
            self._open = ("script", a, [])
        elif tag == "pre" and a.get("id") == "config-text":
            self._open = ("config", a, [])

    def handle_endtag(self, tag):
        if tag == "table" and self._table_class:
            self._table_class.pop()
        if self._open is None or tag not in ("td", "span", "script", "pre"):
            return
        kind, a, parts = self._open
        text = "".join(parts)
        if kind == "num":
            self.cells.append((a, text.strip()))
        elif kind == "plain":
            self.plain_cells.append((a, text.strip()))
        elif kind == "script":
            if a.get("id"):
                self.scripts[a["id"]] = json.loads(text)
            else:
                self.specs.append((a.get("data-target"), json.loads(text)))
        elif kind == "config":
            self.config_text = text
        self._open = None

    def handle_data(self, data):
        if self._open is not None:
            self._open[2].append(data)


def pointer(doc, path):
    value = doc
    for part in path.split("/")[1:]:
        part = part.replace("~1", "/").replace("~0", "~")
        value = value[int(part)] if isinstance(value, list) else value[part]
    return value


def formatted(value, digits):
    """As the page writes it: C's %.<digits>g, which Python's format shares."""
    return f"{value:.{digits}g}"


def is_number(text):
    try:
        float(text)
        return True
    except ValueError:
        return False


def round_off_flags(budget):
    """Each line's below_round_off_floor flags are |u_i(y)| < round_off_floor_relative u_c (the library decides in
    SI; a ratio within 1e-9 of the floor is left alone: the display units' rounding may tip it)."""
    problems = []
    relative = budget["round_off_floor_relative"]
    u = {c["id"]: c["standard_uncertainty"] for c in budget["coefficients"]}
    for c in budget["coefficients"]:
        if c["round_off_floor"] != relative * c["standard_uncertainty"] and not math.isclose(
                c["round_off_floor"], relative * c["standard_uncertainty"], rel_tol=1e-15):
            problems.append(f"budget:{c['id']}: round_off_floor {c['round_off_floor']} is not {relative} u")
    lines = [(s, s["effect"]) for s in budget["sources"]] + [(n, n["u"]) for n in budget.get("rate_noise", [])]
    for line, effect in lines:
        for k, flag in line["below_round_off_floor"].items():
            ratio = abs(effect[k]) / u[k] / relative if u[k] > 0 else 0.0
            if abs(ratio - 1) > 1e-9 and flag != (ratio < 1):
                problems.append(f"budget:{line['id']}: below_round_off_floor/{k} is {flag}, but |u_i(y)| is "
                                f"{ratio:.3g} times the floor")
    return problems


def main(program, report, config=None):
    problems = []
    with open(report, encoding="utf-8") as f:
        page = Page()
        page.feed(f.read())
    sources = page.scripts["ccal-sources"]
    docs = {}
    with tempfile.TemporaryDirectory() as written:
        for name, how in sources.items():
            if "command" in how:
                verb, *options = how["command"]
                where = [os.path.join(written, how["config"])] if "config" in how else [config] if config else []
                if how.get("no_config"):  # e.g. `ccal history show SERIAL --db FILE`
                    where = []
                if "config_option" in how:
                    if not config:
                        sys.exit(f"the output {name} needs the configuration's file: give CONFIG")
                    options += [how["config_option"], config]
                    where = []
                for option, file in how.get("writes", {}).items():
                    options += [option, os.path.join(written, file)]
                args = [program, verb, *where, *options, "--format", "json"]
                docs[name] = json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)

    # x_i: the configured [errors] values (SI in the budget's estimate_si); every one the configuration does not
    # set is 0.
    text = open(config, "rb").read() if config else None
    configured = tomllib.loads(text.decode()).get("errors", {}) if text else {}
    for source in docs["budget"]["sources"]:
        if source["id"] not in configured and source["estimate_si"] != 0:
            problems.append(f"budget:{source['id']}: x_i = {source['estimate_si']}, but the configuration does not "
                            "set it (0)")
    problems += round_off_flags(docs["budget"])

    checked = 0
    for a, shown in page.cells:
        if "data-text" in a:  # a text of the output, e.g. a rounded figure: character for character
            name, path = a["data-text"].split(":", 1)
            if shown != pointer(docs[name], path):
                problems.append(f"{a['data-text']}: the page shows {shown}, the output gives "
                                f"{pointer(docs[name], path)!r}")
            checked += 1
            continue
        digits = int(a["data-digits"])
        scale = float(a.get("data-scale", "1"))
        if "data-round-off" in a:  # a contribution below the round-off floor is shown as 0
            name, path = a["data-round-off"].split(":", 1)
            if pointer(docs[name], path) is True:
                if shown != "0":
                    problems.append(f"{a['data-src']}: below the round-off floor ({a['data-round-off']}), but the "
                                    f"page shows {shown}, not 0")
                checked += 1
                continue
        if "data-src" in a:
            name, path = a["data-src"].split(":", 1)
            expected = pointer(docs[name], path) * scale
        else:
            kind = next(k for k in ("sum", "rss", "ratio") if "data-" + k in a)
            name, paths = a["data-" + kind].split(":", 1)
            values = [pointer(docs[name], p) for p in paths.split()]
            if kind == "ratio":
                expected = values[0] / values[1] * scale
            else:
                expected = (sum(values) if kind == "sum" else math.sqrt(sum(v * v for v in values))) * scale
        if shown != formatted(expected, digits):
            where = a.get("data-src") or a.get("data-sum") or a.get("data-rss") or a.get("data-ratio")
            problems.append(f"{where}: the page shows "
                            f"{shown}, the output gives {formatted(expected, digits)} ({expected!r})")
        checked += 1
    # No number in a result table without its source (the set-up tables show the configuration as written).
    for a, shown in page.plain_cells:
        if a["table"] != "setup" and is_number(shown):
            problems.append(f"a {a['table']} table shows the number {shown} without a source")

    # The charts draw the same numbers: the Monte Carlo histograms and interval ends, the Pareto shares.
    mc = docs["montecarlo"]["coefficients"]
    for target, spec in page.specs:
        if target.startswith("mc-"):
            c = mc[target[3:]]
            counts = [b["trials"] for b in spec["layer"][0]["data"]["values"]]
            if counts != c["histogram"]["counts"]:
                problems.append(f"{target}: the bars are not the histogram of `ccal montecarlo`")
            ends = [r["x"] for r in spec["layer"][2]["data"]["values"]][:2]
            if ends != c["symmetric_interval"]:
                problems.append(f"{target}: the interval rules {ends} are not {c['symmetric_interval']}")
        if target.startswith("pareto-"):
            coefficient = target[7:]
            shares = {s["id"]: s["share"][coefficient] for s in docs["budget"]["sources"]}
            shares.update({s["id"]: s["share"][coefficient] for s in docs["budget"].get("rate_noise", [])})
            for bar in spec["data"]["values"]:
                if bar["source"] in shares and bar["share"] != 100 * shares[bar["source"]]:
                    problems.append(f"{target}: {bar['source']} drawn at {bar['share']} %")
        if target == "allocate-scale":
            drawn = {b["source"]: b["scale"] for b in spec["layer"][0]["data"]["values"]}
            given = {s["id"]: s["scale"] for s in docs["allocate"]["sources"]}
            if drawn != given:
                problems.append(f"{target}: the bars are not the factors λ of `ccal allocate`")
        if target == "statement-split":
            # Per coefficient the Type A and Type B shares of u_c² = u_A² + u_B², in %.
            statement = docs["identify"]["statement"]["coefficients"]
            for bar in spec["data"]["values"]:
                c = statement[bar["coefficient"]]
                a, b = c["type_a"]["u"] ** 2, c["type_b"]["u"] ** 2
                part = a if bar["part"].startswith("Type A") else b
                if not math.isclose(bar["share"], 100 * part / (a + b), rel_tol=1e-12, abs_tol=1e-300):
                    problems.append(f"{target}: {bar['coefficient']} {bar['part']} drawn at {bar['share']} %")
        if target == "design-ratio":
            for bar in spec["layer"][0]["data"]["values"]:
                c = docs["design"]["coefficients"][bar["coefficient"]]
                key = "expanded" if bar["budget"] == "full budget" else "tolerance_expanded"
                if bar["ratio"] != c["designed_" + key] / c["configured_" + key]:
                    problems.append(f"{target}: {bar['coefficient']} ({bar['budget']}) drawn at {bar['ratio']}")
    # The sections the sources announce are on the page, with their charts and a cell from each output.
    targets = {t for t, _ in page.specs}
    # A Pareto chart and a histogram per coefficient, the sensed input, exact vs paper (exact mode only).
    budget = docs["budget"]
    expected_charts = 2 * len(budget["coefficients"]) + 1 + ("paper_effect" in (budget["sources"] or [{}])[0])
    for doc, chart in (("allocate", "allocate-scale"), ("design", "design-ratio"), ("identify", "statement-split")):
        if doc in docs:
            expected_charts += 1
            if chart not in targets:
                problems.append(f"the {doc} section has no chart {chart}")
    named = {a.get("data-src", a.get("data-ratio", ":")).split(":", 1)[0] for a, _ in page.cells}
    for name in docs:
        if name not in named:
            problems.append(f"no number of the page is taken from the output {name}")
    if len(page.specs) < expected_charts:
        problems.append(f"{len(page.specs)} charts, expected at least {expected_charts}")

    expected_text = (text or b"").decode() if config else None
    if expected_text is not None and page.config_text != expected_text:
        problems.append("the configuration text in the page is not the file's")
    sha = hashlib.sha256((page.config_text or "").encode()).hexdigest()
    if f'<code id="config-sha256">{sha}</code>' not in open(report, encoding="utf-8").read():
        problems.append(f"the page's SHA-256 is not that of its configuration text ({sha})")

    for p in problems:
        print(p)
    print(f"{checked} numbers checked against {len(docs)} outputs, {len(page.specs)} charts, "
          f"{len(problems)} problem(s)")
    return 1 if problems or checked < 100 else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
