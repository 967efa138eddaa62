"""Round nine of wrong or careless calls from Python, each found wrong before: options given at their default
value without the option they serve, weight_column="" taken for no weights, a one-element array taken for a
number in some arguments and refused in others, a log step with its unit refused, and an exported history's text
echoed whole as a file name."""

import pathlib
import tempfile
import unittest

import numpy as np

import ccal

EXAMPLES = pathlib.Path(__file__).resolve().parent.parent.parent / "examples"


class NineLeftovers(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lab = ccal.load_config(EXAMPLES / "lab.toml")

    def test_an_option_at_its_default_without_the_option_it_serves_is_refused(self):
        with self.assertRaisesRegex(ccal.InputError, r"^max_trials: 1000000 bounds the adaptive procedure, which "
                                                     r"digits 0 does not run"):
            ccal.monte_carlo(self.lab, trials=100, max_trials=1000000)
        with self.assertRaisesRegex(ccal.InputError, r"^statement_trials: 100000 checks the statement of "
                                                     r"observations, and none are given"):
            ccal.report(self.lab, trials=200, statement_trials=100000)
        with tempfile.TemporaryDirectory() as folder:
            logs = ccal.simulate(self.lab).write_logs(pathlib.Path(folder) / "logs")
            for keyword, value in (("statement_trials", 100000), ("seed", 1), ("threads", 0)):
                with self.subTest(keyword=keyword), self.assertRaisesRegex(
                        ccal.InputError, rf"^{keyword}: {value} is an option of the calibration statement, which is "
                                         rf"not asked for; accepted: {keyword} with statement, or {keyword} left out$"):
                    ccal.reduce(self.lab, logs, **{keyword: value})
            # None is left out, as the signature's default says.
            self.assertIsNone(ccal.reduce(self.lab, logs, seed=None).statement)

    def test_an_empty_weight_column_is_refused(self):
        with tempfile.TemporaryDirectory() as folder:
            path = pathlib.Path(folder) / "t.csv"
            path.write_text("a_i,output,s\n1,2,0.1\n2,4.1,0.1\n3,5.9,0.1\n", encoding="utf-8")
            with self.assertRaisesRegex(ccal.InputError, r"^weight_column: '' names no column; accepted: the column "
                                                         r"of the standard deviations of y, or weight_column left "
                                                         r"out for an unweighted fit$"):
                ccal.identify_file(path, terms=["K0", "K1"], weight_column="")
            self.assertEqual(len(ccal.identify_file(path, terms=["K0", "K1"], weight_column="s").fit.value), 2)

    def test_a_one_element_array_is_no_number_anywhere(self):
        sim = ccal.simulate(self.lab)
        calls = {
            r"allocate\(\): targets\['K3'\]: expected a number or a str, got ndarray \(array\(\[0\.001\]\)\)":
                lambda: ccal.allocate(self.lab, {"K3": np.array([1e-3])}, verify_trials=0),
            r"sensed_input\(\): run: expected an integer or a str, got ndarray \(array\(\[0\]\)\)":
                lambda: ccal.sensed_input(self.lab, np.array([0])),
            r"Simulation\.run_logs\(\): step: expected a number or a str or None, got ndarray":
                lambda: sim.run_logs(step=np.array([0.05])),
            r"Config\.with_error\(\): value: expected a number or a str, got ndarray":
                lambda: self.lab.with_error(self.lab.error_ids[0], np.array([1e-4]), unit="deg"),
            r"Config\.with_tolerance\(\): cost: expected a number or None, got ndarray":
                lambda: self.lab.with_tolerance(self.lab.tolerances[0].id, "1 arcsec", cost=np.array([2.0])),
            r"^coverage_probability: expected a number, got ndarray": lambda: ccal.budget(
                self.lab, coverage_probability=np.array([0.9])),
        }
        for message, call in calls.items():
            with self.subTest(message=message), self.assertRaisesRegex(TypeError, message):
                call()
        # A NumPy scalar (also of 0 dimensions) is a number, as before.
        self.assertIn("'10g'", str(ccal.sensed_input(self.lab, np.int64(1))))
        self.assertEqual(len(sim.run_logs(step=np.float64(0.05))), len(self.lab.runs))

    def test_a_log_step_takes_its_unit(self):
        sim = ccal.simulate(self.lab)
        self.assertEqual(sim.run_logs(step="50 ms"), sim.run_logs(step=0.05))
        with tempfile.TemporaryDirectory() as folder:
            paths = sim.write_logs(pathlib.Path(folder) / "logs", step="0.05 s")
            self.assertEqual(pathlib.Path(paths["5g"]).read_text(encoding="utf-8"), sim.run_logs(step=0.05)[0][1])
        with self.assertRaisesRegex(ccal.InputError, r"^run logs: step: '5 deg': unit 'deg' is an angle, expected a "
                                                     r"time \(accepted: s, ms"):
            sim.run_logs(step="5 deg")
        with self.assertRaisesRegex(ccal.InputError, r"^run logs: step: 0 s is not a positive time"):
            sim.run_logs(step="0 s")


class NineConfirmingRound(unittest.TestCase):
    def test_a_column_of_g_levels_is_no_list_of_numbers(self):
        # np.array([[5.0], [10.0]]) planned two runs: each row, an array of one element, was taken for a number.
        lab = ccal.load_config(EXAMPLES / "lab.toml")
        with self.assertRaisesRegex(TypeError, r"^Config\.with_plan\(\): g\[0\]: expected a number or a str, got "
                                               r"ndarray \(array\(\[5\.\]\)\)"):
            lab.with_plan(g=np.array([[5.0], [10.0]]))
        self.assertEqual(len(lab.with_plan(g=np.array([5.0, 10.0])).runs), 2)


class NineRound(unittest.TestCase):
    def test_an_exported_historys_text_given_for_its_file_is_said_to_be_one(self):
        with tempfile.TemporaryDirectory() as folder:
            d = pathlib.Path(folder)
            (d / "st.json").write_text('{"coverage_probability": 0.95, "coefficients": {"K0": {"unit": "deg/s", '
                                       '"corrected_estimate": 1.5, "expanded_uncertainty": 0.2, '
                                       '"coverage_factor": 2}}}', encoding="utf-8")
            ccal.history_add(d / "st.json", db=d / "h.sqlite", serial="S1", date="2026-01-01")
            text = ccal.history_export("S1", db=d / "h.sqlite")
            with self.assertRaisesRegex(ccal.InputError, r"^'\{…' \(\d+ characters\): the text of a JSON document, not "
                                                         r"a file's path; accepted: the path of an exported history "
                                                         r"file \(`ccal history export`\) \(the text written to a "
                                                         r"file first\)$") as caught:
                ccal.history_import(text, db=d / "other.sqlite")
            self.assertLess(len(str(caught.exception)), 300)
            self.assertFalse((d / "other.sqlite").exists())


if __name__ == "__main__":
    unittest.main()
