"""Round eight of wrong or careless calls from Python, each found wrong before: a NumPy array given for a number
("'<NULL>' is not a finite number"), hints that suggested values the option refuses, options passed over in
silence, a complex array fitted without its imaginary parts, a PDF written under an HTML name."""

import datetime
import json
import os
import pathlib
import tempfile
import unittest
import warnings

import numpy as np

import ccal

EXAMPLES = pathlib.Path(__file__).resolve().parent.parent.parent / "examples"


def eight_statement():
    return json.dumps({"coverage_probability": 0.95, "coefficients": {
        "K0": {"unit": "deg/s", "corrected_estimate": 1.5, "expanded_uncertainty": 0.2, "coverage_factor": 2}}})


class EightNumbers(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lab = ccal.load_config(EXAMPLES / "lab.toml")

    def test_an_array_is_no_number(self):
        with self.assertRaisesRegex(TypeError, r"^coverage_probability: expected a number, got ndarray"):
            ccal.budget(self.lab, coverage_probability=np.array([0.9]))
        with self.assertRaisesRegex(TypeError, r"^tradeoff: expected a number, got ndarray"):
            ccal.design(self.lab, tradeoff=np.array([[0.5, 1.0]]))
        with self.assertRaisesRegex(TypeError, r"^Config\.with_plan\(\): g\[0\]: expected a number or a str, got "
                                               r"ndarray"):
            self.lab.with_plan(g=np.array([[5.0, 10.0, 15.0]]))
        # A NumPy scalar is a number, as before.
        self.assertEqual(ccal.budget(self.lab, coverage_probability=np.float64(0.9)).budget.coverage_probability,
                         0.9)

    def test_a_number_that_is_not_one_says_the_range(self):
        with self.assertRaisesRegex(ccal.InputError, r"^coverage_probability: 'nan' is not a finite number; "
                                                     r"accepted: a number in \[0\.5, 1\), e\.g\. 0\.95$"):
            ccal.budget(self.lab, coverage_probability=float("nan"))

    def test_max_trials_and_statement_options_are_not_passed_over(self):
        with self.assertRaisesRegex(ccal.InputError, r"^max_trials: 50 bounds the adaptive procedure, which "
                                                     r"digits 0 does not run"):
            ccal.monte_carlo(self.lab, trials=100, max_trials=50)
        with tempfile.TemporaryDirectory() as folder:
            logs = ccal.simulate(self.lab).write_logs(pathlib.Path(folder) / "logs")
            with self.assertRaisesRegex(ccal.InputError, r"^statement_trials: 100 is an option of the calibration "
                                                         r"statement, which is not asked for; accepted: "
                                                         r"statement_trials with statement, or statement_trials "
                                                         r"left out$"):
                ccal.reduce(self.lab, logs, statement_trials=100)

    def test_fit_refuses_complex_numbers(self):
        with warnings.catch_warnings():
            warnings.simplefilter("error")  # numpy's ComplexWarning was the only word said
            with self.assertRaisesRegex(TypeError, r"^fit\(\): H: expected an array of real numbers, got complex "
                                                   r"numbers; accepted: real numbers"):
                ccal.fit(np.array([[1, 0], [0, 1], [1, 1]], dtype=complex), [1.0, 2.0, 3.0], ["a", "b"])
            with self.assertRaisesRegex(TypeError, r"^fit\(\): y: expected an array of real numbers"):
                ccal.fit([[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]], [1 + 1j, 2.0, 3.0], ["a", "b"])
        self.assertEqual(len(ccal.fit([[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]], [1.0, 2.0, 3.0], ["a", "b"]).value), 2)


class EightFiles(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lab = ccal.load_config(EXAMPLES / "lab.toml")

    def test_a_json_file_given_for_a_configuration_is_said_to_be_one(self):
        with tempfile.TemporaryDirectory() as folder:
            path = pathlib.Path(folder) / "st.json"
            path.write_text(eight_statement(), encoding="utf-8")
            with self.assertRaisesRegex(ccal.InputError, r"st\.json:1:1: TOML syntax error: .* \(the file opens a "
                                                         r"JSON document, a statement or a result of ccal\?, not "
                                                         r"TOML\); accepted: a configuration file"):
                ccal.load_config(path)

    def test_an_empty_input_column_is_named(self):
        with tempfile.TemporaryDirectory() as folder:
            path = pathlib.Path(folder) / "t.csv"
            path.write_text("a_i,output\n1,2\n2,4.1\n3,5.9\n", encoding="utf-8")
            with self.assertRaisesRegex(ccal.InputError, r"^input_column: '' is empty; accepted: the name of a "
                                                         r"column of the file$"):
                ccal.identify_file(path, terms=["K0", "K1"], input_column="")

    def test_a_history_date_is_also_a_datetime_date(self):
        with tempfile.TemporaryDirectory() as folder:
            d = pathlib.Path(folder)
            (d / "st.json").write_text(eight_statement(), encoding="utf-8")
            record = ccal.history_add(d / "st.json", db=d / "h.sqlite", serial="S1", date=datetime.date(2026, 1, 2))
            self.assertEqual(ccal.history("S1", db=d / "h.sqlite").records[0].date, "2026-01-02")
            self.assertEqual(record, 1)
            shown = ccal.history("S1", db=d / "h.sqlite", at=datetime.date(2027, 1, 1))
            self.assertEqual(shown.serial, "S1")
            with self.assertRaisesRegex(TypeError, r"^date: expected a str, got datetime"):
                ccal.history_add(d / "st.json", db=d / "h.sqlite", serial="S1",
                                 date=datetime.datetime(2026, 1, 2, 10, 0))


class EightReportFiles(unittest.TestCase):
    def test_to_pdf_refuses_another_formats_name(self):
        report = ccal.report(ccal.load_config(EXAMPLES / "lab.toml"), trials=200)
        with tempfile.TemporaryDirectory() as folder:
            for name, what in (("page.html", "an HTML"), ("page.JSON", "a JSON")):
                with self.assertRaisesRegex(ccal.InputError, rf"^Report\.to_pdf\(\): path: '.*{name}' names {what} "
                                                             rf"file, and to_pdf writes PDF; accepted: FILE\.pdf$"):
                    report.to_pdf(os.path.join(folder, name))
                self.assertFalse(os.path.exists(os.path.join(folder, name)))
            with self.assertRaisesRegex(ccal.InputError, r"^Report\.to_pdf\(\): path: the path is empty"):
                report.to_pdf("")
            with self.assertRaisesRegex(ccal.InputError, r"is a folder; accepted: a file path"):
                report.to_pdf(folder)


class EightMessages(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lab = ccal.load_config(EXAMPLES / "lab.toml")

    def test_a_repeated_g_level_and_a_step_say_what_is_wrong(self):
        # "run names must be non-empty and unique; '5g' is not": names the user never gave.
        with self.assertRaisesRegex(ccal.InputError, r"^with_plan: g: the g-level of run '5g' is given twice, and "
                                                     r"runs are named by it \(names unique in the plan\); "
                                                     r"accepted: each g-level once$"):
            self.lab.with_plan(g=[5, 5, 10])
        # "a step of 0 s is more than a quarter revolution": 0 and nan are no steps at all.
        sim = ccal.simulate(self.lab)
        for step in (0.0, float("nan"), -1.0):
            with self.subTest(step=step), self.assertRaisesRegex(
                    ccal.InputError, r"^run logs: step: .* s is not a positive time; accepted: a positive step of "
                                     r"at most a quarter revolution of every run, e\.g\. 0\.05 s$"):
                sim.run_logs(step=step)
        with self.assertRaisesRegex(ccal.InputError, r"^run logs: step: 1000 s is more than a quarter revolution of "
                                                     r"run '5g'; accepted: a step of at most 0\.355 s for this run$"):
            sim.run_logs(step=1000.0)

    def test_fit_messages_say_what_is_accepted(self):
        design = [[1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]
        with self.assertRaisesRegex(ValueError, r"^fit: weight 0 at row 2 is not positive and finite; accepted: "
                                                r"weights 1/σ² > 0"):
            ccal.fit(design, [1.0, 2.0, 3.0], ["a", "b"], weights=[1, 0, 1])
        with self.assertRaisesRegex(ValueError, r'^fit: duplicate term name "a"; accepted: a name of its own for '
                                                r'each column$'):
            ccal.fit(design, [1.0, 2.0, 3.0], ["a", "a"])

    def test_files_are_said_for_what_they_are(self):
        with tempfile.TemporaryDirectory() as folder:
            d = pathlib.Path(folder)
            ccal.simulate(self.lab).write_logs(d / "logs")
            with self.assertRaisesRegex(ccal.InputError, r"manifest\.toml: a file, not the folder of the logs; "
                                                         r"accepted: the folder that holds manifest\.toml and the "
                                                         r"logs"):
                ccal.reduce(self.lab, d / "logs" / "manifest.toml")
            with self.assertRaisesRegex(ccal.InputError, r"nope\.json: no such file; accepted: an exported history "
                                                         r"file"):
                ccal.history_import(d / "nope.json", db=d / "h.sqlite")
            self.assertFalse((d / "h.sqlite").exists())

    def test_to_pdf_writes_a_file_of_the_umasks_mode(self):
        # mkstemp's 0600 was left on the PDF, which `ccal report --pdf` writes 0644 under the usual umask.
        report = ccal.report(self.lab, trials=200)
        try:
            report._print_pdf("<html></html>")
        except ccal.InputError:
            self.skipTest("no Chromium to print with")
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "page.pdf")
            umask = os.umask(0o022)
            try:
                report.to_pdf(path)
            finally:
                os.umask(umask)
            self.assertEqual(os.stat(path).st_mode & 0o777, 0o644)


class EightConfirmingRound(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.lab = ccal.load_config(EXAMPLES / "lab.toml")

    def test_hints_flags_arrays_and_folders(self):
        # The example was "300 deg" for a duration, and with_plan has no unit= keyword.
        with self.assertRaisesRegex(ccal.InputError, r'^with_plan: duration: the bare number 300 has no unit; '
                                                     r'accepted: a string with the unit, such as "300 s"$'):
            self.lab.with_plan(g=[5, 10, 15], duration=np.float64(300))
        # 1 was taken for True, though every option's flag takes True or False only.
        with self.assertRaisesRegex(TypeError, r"^monte_carlo\(\): keep_samples: expected True or False, got int "
                                               r"\(1\)$"):
            ccal.monte_carlo(self.lab, trials=100, keep_samples=1)
        # A 3-D array for the design was pybind11's "incompatible function arguments" with the array's repr.
        with self.assertRaisesRegex(TypeError, r"^fit\(\): H: expected a 2-D array of numbers, got ndarray "
                                               r"\(array\(\[\[\[0\., 0\.\], \[0\., 0\.\]\], "):
            ccal.fit(np.zeros((2, 2, 2)), [1.0, 2.0], ["a", "b"])
        # A folder that does not exist was a FileNotFoundError naming a temporary file.
        report = ccal.report(self.lab, trials=200)
        with self.assertRaisesRegex(ccal.InputError, r"^Report\.to_pdf\(\): path: cannot write 'nodir/x\.pdf': its "
                                                     r"folder 'nodir' does not exist; accepted: a file in an existing "
                                                     r"folder$"):
            report.to_pdf("nodir/x.pdf")


class EightSecondConfirmingRound(unittest.TestCase):
    def test_ragged_text_and_unordered_arguments_are_named(self):
        # A ragged list was numpy's "inhomogeneous shape" from inside the complex check; text and a set were
        # pybind11's "incompatible function arguments".
        with self.assertRaisesRegex(TypeError, r"^fit\(\): H: expected a 2-D array of numbers, got list "
                                               r"\(\[\[1\.0, 0\.0\], \[0\.0\], \[1\.0, 1\.0\]\]\)$"):
            ccal.fit([[1.0, 0.0], [0.0], [1.0, 1.0]], [1, 2, 3], ["a", "b"])
        with self.assertRaisesRegex(TypeError, r"^fit\(\): H: expected a 2-D array of numbers, got list"):
            ccal.fit([["a", "b"], ["c", "d"]], [1, 2], ["a", "b"])
        with self.assertRaisesRegex(TypeError, r"^Config\.with_plan\(\): g: expected a list of number or str or "
                                               r"None, got set"):
            ccal.load_config(EXAMPLES / "lab.toml").with_plan(g={5, 10, 15})
        # A boolean array is numbers (0 and 1), as before.
        self.assertEqual(list(ccal.fit(np.array([[True, False], [False, True], [True, True]]), [1, 2, 3],
                                       ["a", "b"]).value), [1.0, 2.0])


class EightThirdConfirmingRound(unittest.TestCase):
    def test_design_names_its_verifications_trials(self):
        # "trials = 5": design has no such keyword; its verification's is verify_trials.
        lab = ccal.load_config(EXAMPLES / "lab.toml")
        with self.assertRaisesRegex(ccal.InputError, r"^coverage_probability: 0\.95 with verify_trials = 5: .*"
                                                     r"accepted: verify_trials at least 11 for this p"):
            ccal.design(lab, verify_trials=5, starts=0)


class EightLastRound(unittest.TestCase):
    def test_a_serial_with_blanks_around_it_is_refused(self):
        # " SN 0815 " was recorded as another instrument's history than SN 0815's.
        with tempfile.TemporaryDirectory() as folder:
            d = pathlib.Path(folder)
            (d / "st.json").write_text(eight_statement(), encoding="utf-8")
            with self.assertRaisesRegex(ccal.InputError, r"^serial: ' SN 0815 ' begins or ends with a blank"):
                ccal.history_add(d / "st.json", db=d / "h.sqlite", serial=" SN 0815 ", date="2026-01-01")
            self.assertFalse((d / "h.sqlite").exists())


if __name__ == "__main__":
    unittest.main()
