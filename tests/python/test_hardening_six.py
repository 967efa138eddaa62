"""Round six of wrong or careless calls from Python, each found wrong before: a negative pulse weight echoed
without its unit, a record superseded twice without what is accepted, an empty path taken as no path (the
default history store, no history, no truth), True taken as record 1, a measured error far beyond any
centrifuge's simulated, a mistyped input column passed over, a folder given for a file."""

import json
import os
import pathlib
import tempfile
import unittest

import ccal

EXAMPLES = pathlib.Path(__file__).resolve().parent.parent.parent / "examples"


def lab_with(old, new):
    text = (EXAMPLES / "lab.toml").read_text(encoding="utf-8")
    assert old in text
    return text.replace(old, new, 1)


class SixLogsAndHistory(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.TemporaryDirectory()
        cls.d = pathlib.Path(cls.dir.name)
        cls.lab = ccal.load_config(EXAMPLES / "lab.toml")
        cls.logs = ccal.simulate(cls.lab).write_logs(str(cls.d / "logs"))
        red = ccal.reduce(cls.lab, logs=cls.logs, statement=True, statement_trials=0)
        (cls.d / "st.json").write_text(json.dumps(red.to_dict()["statement"]), encoding="utf-8")

    @classmethod
    def tearDownClass(cls):
        cls.dir.cleanup()

    def test_a_negative_pulse_weight_is_echoed_as_typed(self):
        with self.assertRaisesRegex(ccal.InputError, r"^pulse_weight: -2.5e-5 deg is not a positive weight; "
                                                     r"accepted: the integrated output per pulse, a positive "
                                                     r"number in deg/s·s or with a unit of that kind"):
            ccal.reduce(self.lab, logs=self.logs, pulse_weight="-2.5e-5 deg")

    def test_a_record_superseded_twice_says_what_is_accepted(self):
        db = self.d / "twice.sqlite"
        ccal.history_add(self.d / "st.json", db=db)
        ccal.history_supersede(1, db=db, reason="wrong mount")
        with self.assertRaisesRegex(ccal.InputError, r"calibration 1 is already superseded \(wrong mount\), and a "
                                                     r"record is superseded once; accepted: a calibration of "
                                                     r"SN 0815 that is not superseded"):
            ccal.history_supersede(1, db=db, reason="again")

    def test_true_is_no_record_id(self):
        db = self.d / "flag.sqlite"
        ccal.history_add(self.d / "st.json", db=db)
        with self.assertRaisesRegex(TypeError, r"^id: expected an integer, got bool \(True\)$"):
            ccal.history_supersede(True, db=db, reason="a flag for an id")
        self.assertEqual(ccal.history_list(db=db)[0].superseded, 0)

    def test_an_empty_path_is_refused(self):
        with self.assertRaisesRegex(ccal.InputError, r"^db: the path is empty; accepted: a path, or the keyword "
                                                     r"left out$"):
            ccal.history("SN 0815", db="")
        with self.assertRaisesRegex(ccal.InputError, r"^history_add\(\): statement: the path is empty"):
            ccal.history_add("", db=self.d / "never.sqlite")
        self.assertFalse((self.d / "never.sqlite").exists())
        with self.assertRaisesRegex(ccal.InputError, r"^history_db: the path is empty"):
            ccal.report(self.lab, history_db="", trials=200)
        with self.assertRaisesRegex(ccal.InputError, r"^simulate\(\): truth: the path is empty"):
            ccal.simulate(self.lab, truth="")
        with self.assertRaisesRegex(ccal.InputError, r"^load_config\(\): path: the path is empty"):
            ccal.load_config("")


class SixConfigurations(unittest.TestCase):
    def test_an_implausible_measured_error_is_refused_at_its_line(self):
        text = lab_with('dthz5 = "1.5 arcsec"', 'dthz5 = "1e300 arcsec"')
        with self.assertRaisesRegex(ccal.InputError, r"^lab.toml:\d+:9: errors.dthz5: 1e300 arcsec is implausible "
                                                     r"for a measured error of the machine; accepted: up to "
                                                     r"180 deg in size"):
            ccal.parse_config(text, "lab.toml")

    def test_a_refused_value_is_echoed_with_its_unit(self):
        with self.assertRaisesRegex(ccal.InputError, r"plan.runs\[1\].g_level: must be positive, got -5 g;"):
            ccal.parse_config(lab_with('g_level = "5 g"', 'g_level = "-5 g"'), "lab.toml")

    def test_a_folder_given_for_a_file_is_said_to_be_one(self):
        with tempfile.TemporaryDirectory() as d:
            with self.assertRaisesRegex(ccal.FileNotFound, r"cannot read the file: it is a folder; accepted: the "
                                                           r"path of a file$"):
                ccal.load_config(d)

    def test_an_input_column_that_is_not_there_is_refused(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "obs.csv")
            with open(path, "w", encoding="utf-8") as f:
                f.write(ccal.simulate(ccal.load_config(EXAMPLES / "lab.toml")).to_csv())
            with self.assertRaisesRegex(ccal.InputError, r"obs.csv:2: nope: no such column \(needed by the input "
                                                         r"column named\)"):
                ccal.identify_file(path, input_column="nope")


if __name__ == "__main__":
    unittest.main()
