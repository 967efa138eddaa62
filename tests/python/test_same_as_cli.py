"""Every verb gives the same numbers in Python as on the command line: the result's to_json() equals the
program's JSON for the same configuration and the same options, left at their defaults on both sides (one set
of defaults, in the library). Only the timing and thread-count fields, which depend on the run, are left out.
Run by ctest with the module on PYTHONPATH and the program in CCAL_PROGRAM."""

import json
import math
import os
import re
import subprocess
import tempfile
import unittest

import ccal

SECOND = os.path.join(os.path.dirname(__file__), "..", "data", "golden", "second.toml")
VOLATILE = {"wall_time_s", "threads", "trials_per_s", "cache_seconds", "search_seconds", "candidates_from_cache"}


def normalised(value):
    """The JSON without the fields that depend on the machine and the run."""
    if isinstance(value, dict):
        return {k: normalised(v) for k, v in value.items() if k not in VOLATILE}
    if isinstance(value, list):
        return [normalised(v) for v in value]
    if isinstance(value, str):
        return re.sub(r", \d+ threads?, [0-9.]+ s", "", value)
    return value


def program_json(*args):
    out = subprocess.run([os.environ["CCAL_PROGRAM"], *args, "--format", "json"], check=True,
                         capture_output=True, text=True).stdout
    return normalised(json.loads(out))


class SameAsCli(unittest.TestCase):
    def check(self, result, *args):
        self.assertEqual(normalised(json.loads(result.to_json())), program_json(*args))

    def test_every_verb_on_two_configurations(self):
        for path in [None, SECOND]:
            cfg = ccal.load_config(path) if path else ccal.bundled_example()
            arg = [path] if path else []
            with self.subTest(config=path or "bundled"):
                self.check(ccal.budget(cfg), "budget", *arg)
                self.check(ccal.budget(cfg, derivatives="automatic"), "budget", *arg,
                           "--derivatives", "automatic")
                self.check(ccal.sensed_input(cfg), "force", *arg)
                self.check(ccal.sensed_input(cfg, run=2, time=123.4), "force", *arg, "--run", "3", "--time",
                           "123.4")
                self.check(ccal.simulate(cfg), "simulate", *arg)
                self.check(ccal.monte_carlo(cfg, trials=3000, seed=7), "montecarlo", *arg, "--trials",
                           "3000", "--seed", "7")
                self.check(ccal.monte_carlo(cfg), "montecarlo", *arg)  # the defaults are the same
                targets = {"K2": 2e-5, "K3": 2e-3} if path is None else {"K2": 1e-5, "K3": 1e-3}
                self.check(ccal.allocate(cfg, targets), "allocate", *arg,
                           *[f"--target={k}={v}" for k, v in targets.items()])

    def test_design(self):
        # The bundled example with the [design] defaults, and with targets and another seed.
        cfg = ccal.bundled_example()
        self.check(ccal.design(cfg), "design")
        self.check(ccal.design(cfg, targets={"K2": 2e-5, "K3": "1e-3 deg/s/g^3"}, seed=3, starts=2), "design",
                   "--target", "K2=2e-5", "--target", "K3=1e-3 deg/s/g^3", "--seed", "3", "--starts", "2")

    def test_identify(self):
        # The observations file simulate writes (its own terms, fixed K1 and known rate column), with the
        # calibration statement of a budget configuration, and a plain table with terms, a fixed term, a
        # weight column and no known column.
        with tempfile.TemporaryDirectory() as tmp:
            obs = os.path.join(tmp, "obs.csv")
            with open(obs, "w") as f:
                f.write(ccal.simulate(ccal.bundled_example()).to_csv())
            self.check(ccal.identify_file(obs), "identify", obs)
            # Observations of the bundled example stated with another configuration's budget: refused.
            with self.assertRaisesRegex(ccal.InputError, "was made with another configuration than"):
                ccal.identify_file(obs, statement=True, config=ccal.load_config(SECOND))
            with open(obs, "w") as f:
                f.write(ccal.simulate(ccal.load_config(SECOND)).to_csv())
            self.check(ccal.identify_file(obs, statement=True, config=ccal.load_config(SECOND), mode="paper",
                                          coverage_probability=0.9),
                       "identify", obs, "--statement", "--config", SECOND, "--mode", "paper",
                       "--coverage-probability", "0.9")
            table = os.path.join(tmp, "table.csv")
            with open(table, "w") as f:
                f.write("x,y,sigma\n" + "".join(f"{x},{1 + 0.5 * x + 0.01 * x * x + 1e-4 * (-1) ** x},0.001\n"
                                                  for x in range(1, 9)))
            self.check(ccal.identify_file(table, terms=["K0", "K2"], fix=["K1=0.5"], known=["none"],
                                          input_column="x", output_column="y", weight_column="sigma"),
                       "identify", table, "--terms", "K0,K2", "--fix", "K1=0.5", "--known", "none",
                       "--input-column", "x", "--output-column", "y", "--weight-column", "sigma")

    def test_reduce(self):
        # Synthetic logs of the first three runs (as in tests/system/golden_outputs_test.cpp): pulses of 1e-3 deg,
        # encoders at the planned rate of a 2.5 m arm, every 0.1 s.
        with tempfile.TemporaryDirectory() as tmp:
            logs = {}
            for r, (level, mean) in enumerate([(5, 2526.171), (10, 5052.236), (15, 7578.517)]):
                rate = math.sqrt(level * 9.8 / 2.5)
                rows = ["time,pulses,theta1,gamma"]
                for k in range(1201):
                    t = 120 * k / 1200
                    rows.append(f"{t:.6f},{math.floor(mean * t / 1e-3):.6f},"
                                f"{math.fmod(0.3 + rate * (1 + 1e-6) * t, 2 * math.pi):.6f},"
                                f"{math.fmod(8 * math.pi + 1.1 - rate * (1 - 2e-6) * t, 2 * math.pi):.6f}")
                path = os.path.join(tmp, f"run{r + 1}.csv")
                with open(path, "w") as f:
                    f.write("\n".join(rows) + "\n")
                logs[r] = path
            result = ccal.reduce(ccal.bundled_example(), logs, pulse_weight=1e-3)
            self.check(result, "reduce", *[f"--log={r + 1}={p}" for r, p in logs.items()], "--pulse-weight",
                       "1e-3")

    def test_bad_arguments_of_the_verb_functions(self):
        # Each refused with InputError naming the argument and what it accepts.
        cfg = ccal.bundled_example()
        cases = [
            (lambda: ccal.reduce(cfg, {0: "a.csv", 1: "b.csv", 2: "c.csv"}, angle_unit="grad"),
             "angle_unit: 'grad'"),
            (lambda: ccal.reduce(cfg, {0: "a.csv"}, mode="fast"), "mode: 'fast'"),
            (lambda: ccal.reduce(cfg, {0: "a.csv", 1: "b.csv", 2: "c.csv"}, pulse_weight=-1.0),
             "pulse_weight: -1 is not a positive weight"),
            (lambda: ccal.simulate(cfg, mode="fast"), "mode: 'fast'"),
            (lambda: ccal.monte_carlo(cfg, trials=1), "trials: 1 is out of range"),
            (lambda: ccal.budget(cfg, coverage_factor=-1.0), "coverage_factor: -1 is out of range"),
            (lambda: ccal.identify_file(os.path.join(os.path.dirname(__file__), "no such file.csv")),
             "no such file.csv: cannot read the file"),
            (lambda: ccal.identify_file(SECOND.replace(".toml", ".csv"), mode="fast"), "mode: 'fast'"),
        ]
        for call, message in cases:
            with self.subTest(message=message):
                with self.assertRaises(ccal.InputError) as e:
                    call()
                self.assertIn(message, str(e.exception))

    def test_text_report_is_the_cli_text(self):
        cfg = ccal.bundled_example()
        out = subprocess.run([os.environ["CCAL_PROGRAM"], "budget"], check=True, capture_output=True,
                             text=True).stdout
        self.assertEqual(str(ccal.budget(cfg)), out)


if __name__ == "__main__":
    unittest.main()
