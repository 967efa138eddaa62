"""Round seven of wrong or careless calls from Python, each found wrong before: an argument of the wrong type
answered with pybind11's "incompatible function arguments" and the whole configuration's repr, a coverage
probability at the default's value taken beside a stated coverage factor, a calibration dated after today
recorded."""

import json
import pathlib
import tempfile
import unittest

import ccal

EXAMPLES = pathlib.Path(__file__).resolve().parent.parent.parent / "examples"


def seven_statement(certificate=None):
    st = {"coverage_probability": 0.95, "coefficients": {
        "K0": {"unit": "deg/s", "corrected_estimate": 1.5, "expanded_uncertainty": 0.2, "coverage_factor": 2}}}
    if certificate:
        st["certificate"] = certificate
    return json.dumps(st)


class SevenArgumentTypes(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lab = ccal.load_config(EXAMPLES / "lab.toml")

    def test_a_wrong_argument_is_named_with_what_is_accepted(self):
        cases = [
            (lambda: ccal.allocate(self.lab, targets=[("K3", 1e-4)]),
             r"^allocate\(\): targets: expected a dict of str → number or str, got list \(\[\('K3', 0\.0001\)\]\)$"),
            (lambda: self.lab.instrument(None), r"^Config\.instrument\(\): id: expected a str, got NoneType \(None\)$"),
            (lambda: ccal.allocate(self.lab, targets={"K3": [1e-4]}),
             r"^allocate\(\): targets\['K3'\]: expected a number or a str, got list \(\[0\.0001\]\); accepted: a "
             r"dict of str → number or str$"),
            (lambda: ccal.allocate(self.lab, {3: 1e-4}),
             r"^allocate\(\): targets: key 3: expected a str, got int \(3\)"),
            (lambda: ccal.design(self.lab, targets=5), r"^design\(\): targets: expected a dict of str"),
            (lambda: ccal.report(self.lab, allocate_targets=["K3=1e-4"]),
             r"^report\(\): allocate_targets: expected a dict of str → number or str or None, got list"),
            (lambda: ccal.budget(str(EXAMPLES / "lab.toml")),
             r"^budget\(\): config: expected a ccal\.Config, got str \(.*lab\.toml'\); a configuration file is "
             r"read by ccal\.load_config\(path\)$"),
        ]
        for call, message in cases:
            with self.subTest(message=message), self.assertRaisesRegex(TypeError, message) as caught:
                call()
            self.assertNotIn("incompatible function arguments", str(caught.exception))
            self.assertNotIn("6 runs", str(caught.exception))  # the configuration's repr


class SevenCoverages(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lab = ccal.load_config(EXAMPLES / "lab.toml")

    def test_two_coverages_are_refused_also_at_the_default_probability(self):
        message = (r"^coverage_factor: 2 and coverage_probability 0\.95 are two coverages; accepted: one of them "
                   r"\(a stated coverage factor, or a coverage probability\)$")
        for call in (lambda: ccal.budget(self.lab, coverage_probability=0.95, coverage_factor=2),
                     lambda: ccal.design(self.lab, coverage_probability=0.95, coverage_factor=2),
                     lambda: ccal.report(self.lab, coverage_probability=0.95, coverage_factor=2, trials=200)):
            with self.assertRaisesRegex(ccal.InputError, message):
                call()
        # Either alone, or None for the probability, is taken; unset means the default.
        self.assertEqual(ccal.budget(self.lab).coverage_probability, 0.95)
        self.assertEqual(ccal.budget(self.lab, coverage_probability=None, coverage_factor=2).coverage_factor, 2)
        self.assertEqual(ccal.budget(self.lab, coverage_probability=0.95).coverage_probability, 0.95)

    def test_two_coverages_of_a_statement_are_refused(self):
        with tempfile.TemporaryDirectory() as folder:
            logs = ccal.simulate(self.lab).write_logs(str(pathlib.Path(folder) / "logs"))
            with self.assertRaisesRegex(ccal.InputError, r"^coverage_factor: 2 and coverage_probability 0\.95 are "
                                                         r"two coverages"):
                ccal.reduce(self.lab, logs=logs, statement=True, statement_trials=0, coverage_probability=0.95,
                            coverage_factor=2)


class SevenHistory(unittest.TestCase):
    def test_a_calibration_dated_after_today_is_not_recorded(self):
        with tempfile.TemporaryDirectory() as folder:
            d = pathlib.Path(folder)
            (d / "st.json").write_text(seven_statement(), encoding="utf-8")
            with self.assertRaisesRegex(ccal.InputError, r"^date: 9999-12-31 is after today \(\d{4}-\d\d-\d\d, "
                                                         r"UTC\), and a calibration is recorded once it is done; "
                                                         r"accepted: its date, YYYY-MM-DD, up to "):
                ccal.history_add(d / "st.json", db=d / "h.sqlite", serial="S1", date="9999-12-31")
            self.assertFalse((d / "h.sqlite").exists())
            (d / "future.json").write_text(
                seven_statement({"serial_number": "S1", "date_of_calibration": "9999-12-31"}), encoding="utf-8")
            with self.assertRaisesRegex(ccal.InputError, r"date of calibration '9999-12-31' \(\[certificate\] "
                                                         r"date_of_calibration\) is after today"):
                ccal.history_add(d / "future.json", db=d / "h.sqlite")
            self.assertFalse((d / "h.sqlite").exists())
            self.assertEqual(ccal.history_add(d / "st.json", db=d / "h.sqlite", serial="S1", date="2020-02-29"), 1)


class SevenFreshRound(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lab = ccal.load_config(EXAMPLES / "lab.toml")

    def test_messages_name_the_argument_and_what_is_accepted(self):
        with tempfile.TemporaryDirectory() as folder:
            d = pathlib.Path(folder)
            (d / "a_file").write_text("x", encoding="utf-8")
            sim = ccal.simulate(self.lab)
            with self.assertRaisesRegex(ccal.InputError, r"^Simulation\.write_logs\(\): folder: '.*a_file' is a "
                                                         r"file, not a folder; accepted: a folder's path"):
                sim.write_logs(d / "a_file")
            with self.assertRaisesRegex(ccal.InputError, r"^Simulation\.write_logs\(\): folder: the path is "
                                                         r"empty; accepted: a folder's path"):
                sim.write_logs("")
        with self.assertRaisesRegex(TypeError, r"^progress: expected None or a callable progress\(done, total\), "
                                               r"got int \(5\)$"):
            ccal.monte_carlo(self.lab, trials=100, progress=5)
        with self.assertRaisesRegex(TypeError, r"^history_export\(\) got an unexpected keyword argument 'path'; "
                                               r"accepted: serial, db$"):
            ccal.history_export("S1", path="e.json")
        with self.assertRaisesRegex(TypeError, r"^bundled_example\(\): too many positional arguments; accepted: "
                                               r"no arguments$"):
            ccal.bundled_example("lab")
        with self.assertRaisesRegex(ccal.InputError, r"the bare number -1 has no unit; accepted: a string with the "
                                                     r"unit, such as \"1 deg\", or unit="):
            self.lab.with_tolerance("dthz5", -1)
        with self.assertRaisesRegex(ValueError, r"^fit: the design has 2 rows but y has 1 entries; accepted: one y "
                                                r"per row of the design$"):
            ccal.fit([[1.0, 2.0], [3.0, 4.0]], [1.0], ["a", "b"])
        with self.assertRaisesRegex(ValueError, r"^fit: non-finite value nan in y at row 2.*; accepted: finite "
                                                r"numbers$"):
            ccal.fit([[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]], [1.0, float("nan"), 2.0], ["a", "b"])
        with self.assertRaisesRegex(ValueError, r"^fit: 1 term names for a design with 2 columns; accepted: one name "
                                                r"per column of the design$"):
            ccal.fit([[1.0, 0.0], [0.0, 1.0]], [1.0, 2.0], ["a"])
        with self.assertRaisesRegex(ccal.InputError, r"^coverage_factor: 1e\+308 is out of range; accepted: 1 to 10"):
            ccal.budget(self.lab, coverage_factor=1e308)

    def test_a_bool_is_no_number_and_a_run_is_0_based_everywhere(self):
        # True was taken as a target of 1 (deg/s/g^3), allocated and verified with exit 0.
        with self.assertRaisesRegex(TypeError, r"^allocate\(\): targets\['K3'\]: expected a number or a str, got "
                                               r"bool \(True\)$"):
            ccal.allocate(self.lab, {"K3": True})
        with self.assertRaisesRegex(TypeError, r"^Config\.with_tolerance\(\): bound: expected a number or a str, "
                                               r"got bool \(False\)$"):
            self.lab.with_tolerance("dthz5", False)
        # report(run=...) named runs by the command line's 1-based index ("an index 1..6"), unlike every other
        # function: 0-based now, its message too.
        with self.assertRaisesRegex(ccal.InputError, r"^run: index 6 is out of range for 6 runs; accepted: 0 to 5"):
            ccal.report(self.lab, run=6, trials=200)
        with self.assertRaisesRegex(ccal.InputError, r"^run: '99g' is no run; accepted: a run name \(5g, 10g, "
                                                     r"15g, 20g, 25g, 30g\) or a 0-based index 0 to 5$"):
            ccal.report(self.lab, run="99g", trials=200)
        with self.assertRaisesRegex(ccal.InputError, r"^with_plan: g: no runs; accepted: at least one g-level"):
            self.lab.with_plan(g=[])
        with self.assertRaisesRegex(ccal.InputError, r"^with_plan: duration: -1 s is out of range; accepted: a run "
                                                     r"duration in \(0, 1e6\] s$"):
            self.lab.with_plan(g=[5, 10, 15], duration="-1 s")

    def test_identify_refuses_a_dropped_fixed_term(self):
        with tempfile.TemporaryDirectory() as folder:
            obs = pathlib.Path(folder) / "obs.csv"
            obs.write_text(ccal.simulate(self.lab).to_csv(), encoding="utf-8")
            with self.assertRaisesRegex(ccal.InputError, r"^fix: 'K9=1' replaces the fixed terms of .*obs\.csv, "
                                                         r"and its K1 = 505\.2097 deg/s/g would be left out"):
                ccal.identify_file(obs, fix=["K9=1"])
            with self.assertRaisesRegex(ccal.InputError, r"^output_column: a_i is also the input_column"):
                ccal.identify_file(obs, input_column="a_i", output_column="a_i")


if __name__ == "__main__":
    unittest.main()
