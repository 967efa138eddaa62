#!/usr/bin/env python3
"""Does a calibration statement cover the truth as often as it says? (docs/model.md §10.6)

Simulates N calibrations of one configuration, each machine drawn from the configuration's own stated
knowledge (`ccal simulate --draw-truth`: every [tolerances] input from its distribution, groups and
[[correlations]] included, around the [errors] values; the instrument's noise), runs each as run logs and reduces
them with the calibration statement (`ccal reduce --statement`), exactly as a lab would. Per coefficient it
prints how often the stated interval covered the true coefficient ([instrument.terms]) against the coverage
probability p the statement claims, and the median stated U against the half-width that covers a fraction p
of the actual errors.

The statement holds when, for every coefficient,
  * the coverage is within three binomial standard errors of p: |c − p| ≤ 3 √(p(1 − p)/N), and
  * the median U is at most `--width-limit` (1.5) times the half-width that covers p of the errors.
Exit status 0 when it holds, 1 when it does not, 2 for a wrong argument or a failed calibration.

  python3 scripts/coverage_study.py examples/lab.toml --calibrations 300
  python3 scripts/coverage_study.py examples/lab.toml --ccal build/ccal --json > coverage.json
"""

import argparse
import concurrent.futures
import json
import math
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import tomllib


def true_terms(config_path):
    """The instrument's terms as the configuration writes them: {id: (value, unit text)}."""
    with open(config_path, "rb") as f:
        config = tomllib.load(f)
    terms = {}
    for term, text in config.get("instrument", {}).get("terms", {}).items():
        value, _, unit = str(text).strip().partition(" ")
        terms[term] = (float(value), unit.strip())
    return terms


def calibrate(ccal, config, seed, statement_trials, work):
    """One calibration of a drawn machine: its statement's coefficients (the reduce JSON's)."""
    folder = pathlib.Path(work) / f"calibration-{seed}"
    logs = folder / "logs"
    folder.mkdir(parents=True)
    run = lambda *args: subprocess.run([ccal, *args], capture_output=True, text=True)
    sim = run("simulate", config, "--draw-truth", "--seed", str(seed), "--logs-out", str(logs), "-o",
              str(folder / "simulate.txt"))
    if sim.returncode != 0:
        raise RuntimeError(f"simulate (seed {seed}) failed: {sim.stderr.strip()}")
    red = run("reduce", config, "--logs", str(logs), "--statement", "--statement-trials", str(statement_trials),
              "--seed", str(seed), "--format", "json")
    if red.returncode != 0:
        raise RuntimeError(f"reduce (seed {seed}) failed: {red.stderr.strip()}")
    return json.loads(red.stdout)["statement"]


def study(ccal, config, calibrations, first_seed, statement_trials, jobs):
    terms = true_terms(config)
    with tempfile.TemporaryDirectory(prefix="ccal-coverage-") as work:
        with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
            seeds = range(first_seed, first_seed + calibrations)
            statements = list(pool.map(lambda s: calibrate(ccal, config, s, statement_trials, work), seeds))
    p = statements[0]["coverage_probability"]
    rows = {}
    for name, first in statements[0]["coefficients"].items():
        if name not in terms:
            raise RuntimeError(f"{config}: [instrument.terms] has no {name}, so its true value is unknown")
        truth, unit = terms[name]
        if unit != first["unit"]:
            raise RuntimeError(f"{name}: the configuration writes it in '{unit}', the statement in "
                               f"'{first['unit']}'; accepted: a configuration whose terms are in the fit's units")
        covered, errors, expanded, methods = 0, [], [], {}
        for st in statements:
            c = st["coefficients"][name]
            low, high = c["interval"]
            covered += low <= truth <= high
            errors.append(abs(c["corrected_estimate"] - truth))
            expanded.append(c["expanded_uncertainty"])
            methods[c["interval_method"]] = methods.get(c["interval_method"], 0) + 1
        errors.sort()
        # The half-width that covers a fraction p of the actual errors: their p-quantile (the smallest error
        # at or beyond which ⌈pN⌉ errors lie).
        needed = errors[min(len(errors) - 1, math.ceil(p * len(errors)) - 1)]
        rows[name] = {"unit": unit, "truth": truth, "coverage": covered / len(statements),
                      "median_U": statistics.median(expanded), "half_width_needed": needed,
                      "width_ratio": statistics.median(expanded) / needed if needed > 0 else math.inf,
                      "interval_methods": methods}
    excess = sum(bool(st.get("type_a", {}).get("residual_check", {}).get("excess")) for st in statements)
    return {"config": config, "calibrations": len(statements), "coverage_probability": p,
            "residual_excess_charged": excess,
            "binomial_tolerance": 3 * math.sqrt(p * (1 - p) / len(statements)), "coefficients": rows}


def verdict(result, width_limit):
    p, tol = result["coverage_probability"], result["binomial_tolerance"]
    failures = []
    for name, r in result["coefficients"].items():
        if abs(r["coverage"] - p) > tol:
            failures.append(f"{name}: coverage {r['coverage']:.3f} is not within {tol:.3f} of {p:g}")
        if r["width_ratio"] > width_limit:
            failures.append(f"{name}: median U is {r['width_ratio']:.2f} times the half-width needed "
                            f"(at most {width_limit:g})")
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("config", help="the configuration (TOML) whose statement is studied")
    parser.add_argument("--calibrations", type=int, default=300, help="N, the calibrations simulated (300)")
    parser.add_argument("--seed", type=int, default=1, help="seed of the first calibration (1); then 2, 3, …")
    parser.add_argument("--statement-trials", type=int, default=100000,
                        help="M of each statement's Monte Carlo check (100000, as `ccal reduce`)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="calibrations at once (cores)")
    parser.add_argument("--width-limit", type=float, default=1.5,
                        help="largest accepted ratio of the median U to the half-width needed (1.5)")
    parser.add_argument("--ccal", default=str(pathlib.Path(__file__).resolve().parent.parent / "build" / "ccal"),
                        help="the ccal program (build/ccal)")
    parser.add_argument("--json", action="store_true", help="print the figures as JSON")
    a = parser.parse_args()
    if a.calibrations < 20:
        parser.error(f"--calibrations {a.calibrations}: accepted: at least 20, so that a coverage can be judged")
    if a.jobs < 1:
        parser.error(f"--jobs {a.jobs}: accepted: at least 1")
    try:
        result = study(a.ccal, a.config, a.calibrations, a.seed, a.statement_trials, a.jobs)
    except (RuntimeError, OSError, tomllib.TOMLDecodeError, ValueError) as e:
        print(f"coverage_study: {e}", file=sys.stderr)
        return 2
    failures = verdict(result, a.width_limit)
    result["holds"] = not failures
    result["failures"] = failures
    if a.json:
        print(json.dumps(result, indent=2))
    else:
        p = result["coverage_probability"]
        print(f"{result['calibrations']} calibrations of {a.config}, each machine drawn from its stated knowledge; "
              f"claimed coverage p = {p:g} (± {result['binomial_tolerance']:.3f}, three binomial standard errors)")
        print(f"{'coefficient':<12}{'coverage':>10}{'median U':>14}{'needed':>14}{'ratio':>8}  unit")
        for name, r in result["coefficients"].items():
            print(f"{name:<12}{r['coverage']:>10.3f}{r['median_U']:>14.4g}{r['half_width_needed']:>14.4g}"
                  f"{r['width_ratio']:>8.2f}  {r['unit']}")
        print(f"the residuals' check charged an excess in {result['residual_excess_charged']} of them "
              f"(1 % expected where the stated noise and inputs are the truth's)")
        print("holds" if not failures else "does not hold:\n  " + "\n  ".join(failures))
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
