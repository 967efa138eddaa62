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


if __name__ == "__main__":
    unittest.main()
