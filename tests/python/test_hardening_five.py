"""A fresh round of wrong or unusual calls from Python, each found wrong before: paths given as pathlib.Path
where every path is taken as Python takes one, an empty instrument id refused as the command line refuses it,
a reduction from a folder of logs that pickles, a reduction of several instruments given to history_add, a
wild cell of a log refused at its line, a serial number with a control character refused by the
configuration."""

import json
import os
import pathlib
import pickle
import tempfile
import unittest

import ccal

EXAMPLES = pathlib.Path(__file__).resolve().parent.parent.parent / "examples"


class PathsAsPathlib(unittest.TestCase):
    def test_every_path_argument_takes_a_pathlib_path(self):
        lab = ccal.load_config(EXAMPLES / "lab.toml")
        self.assertEqual(lab.source, str(EXAMPLES / "lab.toml"))
        with tempfile.TemporaryDirectory() as d:
            d = pathlib.Path(d)
            sim = ccal.simulate(lab)
            (d / "obs.csv").write_text(sim.to_csv(), encoding="utf-8")
            self.assertEqual(ccal.identify_file(d / "obs.csv").to_json(),
                             ccal.identify_file(str(d / "obs.csv")).to_json())
            report = ccal.report(lab, observations=d / "obs.csv", trials=200)
            self.assertTrue(report.certificate)
            red = ccal.reduce(lab, logs=sim.write_logs(str(d / "logs")), statement=True, statement_trials=0)
            (d / "st.json").write_text(json.dumps(red.to_dict()["statement"]), encoding="utf-8")
            self.assertEqual(ccal.history_add(d / "st.json", db=d / "h.sqlite"), 1)
            (d / "ex.json").write_text(ccal.history_export("SN 0815", db=d / "h.sqlite"), encoding="utf-8")
            self.assertEqual(ccal.history_import(d / "ex.json", db=d / "other.sqlite").added, 1)
        # Anything else is a TypeError naming the argument and what is accepted.
        with self.assertRaisesRegex(TypeError, r"load_config\(\): path: expected the path of a TOML file \(str or "
                                               r"os.PathLike\), got int"):
            ccal.load_config(5)
        with self.assertRaisesRegex(TypeError, r"history_add\(\): statement: expected .*got float"):
            ccal.history_add(1.5)


class InstrumentIds(unittest.TestCase):
    def test_an_empty_id_is_refused_as_the_command_line_refuses_it(self):
        two = ccal.load_config(EXAMPLES / "daq" / "two_short.toml")
        with self.assertRaisesRegex(ccal.InputError, r"^instrument: the id is empty; accepted: an instrument's id "
                                                     r"of the configuration's \[\[instruments\]\], e.g. A$"):
            two.instrument("")


class PythonWords(unittest.TestCase):
    def test_the_tradeoff_of_several_instruments_names_the_keyword(self):
        two = ccal.load_config(EXAMPLES / "daq" / "two_short.toml")
        with self.assertRaisesRegex(ccal.InputError, r"^tradeoff: 0.5 is not taken for a test of 2 instruments "
                                                     r".*; accepted: tradeoff with a configuration of one"):
            ccal.design(two, tradeoff=[0.5, 1], verify_trials=0)


class UnitsAsText(unittest.TestCase):
    def test_the_time_of_sensed_input_takes_its_unit_as_force_does(self):
        cfg = ccal.bundled_example()
        self.assertEqual(ccal.sensed_input(cfg, run="5g", time="0.5 min").to_json(),
                         ccal.sensed_input(cfg, run="5g", time=30).to_json())
        self.assertEqual(ccal.sensed_input(cfg, run="5g", time="30").to_json(),
                         ccal.sensed_input(cfg, run="5g", time=30.0).to_json())
        with self.assertRaisesRegex(ccal.InputError, r"time: '10 m': unit 'm' is a length, expected a time"):
            ccal.sensed_input(cfg, run="5g", time="10 m")
        with self.assertRaisesRegex(ccal.InputError, r"time: .* is outside run '5g'"):
            ccal.sensed_input(cfg, run="5g", time="1 h")


class ReductionFromAFolder(unittest.TestCase):
    def test_a_reduction_of_a_folder_pickles_and_names_the_folder(self):
        two = ccal.load_config(EXAMPLES / "daq" / "two_short.toml")
        folder = EXAMPLES / "daq" / "two_instruments"
        for logs in (str(folder), folder):
            red = ccal.reduce(two, logs=logs)
            again = pickle.loads(pickle.dumps(red))
            self.assertEqual(again.to_json(), red.to_json())
            self.assertEqual(str(again), str(red))
            self.assertIn(str(folder / "5g.csv"), again.to_json())

    def test_the_statements_of_several_instruments_are_not_one_statement(self):
        two = ccal.load_config(EXAMPLES / "daq" / "two_short.toml")
        red = ccal.reduce(two, logs=EXAMPLES / "daq" / "two_instruments", statement=True, statement_trials=0)
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "two.json")
            with open(path, "w", encoding="utf-8") as f:
                f.write(red.to_json())
            with self.assertRaisesRegex(ccal.InputError, r"two.json: holds the statements of 2 instruments \(A, B\) "
                                                         r"of a test of several; accepted: one instrument's "
                                                         r"statement alone"):
                ccal.history_add(path, db=os.path.join(d, "h.sqlite"))
            self.assertFalse(os.path.exists(os.path.join(d, "h.sqlite")))


class WildCells(unittest.TestCase):
    def test_a_count_glitch_in_the_first_cell_is_refused_at_its_line(self):
        lab = ccal.load_config(EXAMPLES / "lab.toml")
        with tempfile.TemporaryDirectory() as d:
            logs = ccal.simulate(lab).write_logs(os.path.join(d, "logs"))
            path = pathlib.Path(logs["5g"])
            lines = path.read_text(encoding="utf-8").splitlines()
            cells = lines[1].split(",")
            cells[1] = "-300000"
            lines[1] = ",".join(cells)
            path.write_text("\n".join(lines) + "\n", encoding="utf-8")
            with self.assertRaisesRegex(ccal.InputError, r"5g.csv:3:2: pulses: the count's step to this line.*a "
                                                         r"wild count in this line or the one before"):
                ccal.reduce(lab, logs=os.path.join(d, "logs"))


class TablesThatAreToml(unittest.TestCase):
    def test_a_configuration_given_for_observations_is_said_to_be_toml(self):
        with self.assertRaisesRegex(ccal.InputError, r"lab.toml:\d+:1: the header, '\[site\]', is a line of TOML"):
            ccal.identify_file(EXAMPLES / "lab.toml")


class SerialNumbers(unittest.TestCase):
    def test_a_control_character_in_a_serial_number_is_refused_at_its_line(self):
        text = (EXAMPLES / "lab.toml").read_text(encoding="utf-8")
        bad = text.replace('serial_number = "SN 0815"', 'serial_number = "SN\\u00000815"')
        with self.assertRaisesRegex(ccal.InputError, r"lab.toml:\d+:17: certificate.serial_number: 'SN\\x000815' "
                                                     r"holds a control character"):
            ccal.parse_config(bad, "lab.toml")


if __name__ == "__main__":
    unittest.main()
