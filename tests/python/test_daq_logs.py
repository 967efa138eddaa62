"""Logs as a data acquisition system writes them, from Python (docs/python.md, reduce): the sample folders of
examples/daq reduce through reduce(config, folder) with their manifest's [format] and [columns] keys, a dict
of logs takes the same layout through log_layout= (as `ccal reduce --log … --log-layout FILE`), and a bad key
is refused with its file, line and key."""

import json
import os
import shutil
import tempfile
import unittest

import ccal

DAQ = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "daq")
RUNS = ("5g", "10g", "20g", "30g")


class DaqLogs(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.config = ccal.load_config(os.path.join(DAQ, "lab_short.toml"))
        cls.comma = ccal.reduce(cls.config, os.path.join(DAQ, "comma"))

    def test_the_semicolon_folder_reduces_to_the_comma_folders_coefficients(self):
        # Decimal commas, a preamble, a units row, ms, counts of 2^24 latched down and a 5 s dropout in the
        # 20 g run: the same coefficients to 1e-3 of their standard errors (the counts' quantisation, 3.7e-7
        # rad, in line fits of 416 samples a run, moves them by some 1e-4 of a standard error: 1.2e-4 for K2;
        # tests/verbs/reduce_layouts_test.cpp has 450 s runs and the tighter 1e-4).
        semicolon = ccal.reduce(self.config, os.path.join(DAQ, "semicolon"))
        self.assertEqual(list(semicolon.names), list(self.comma.names))
        a = json.loads(self.comma.to_json())["identification"]["coefficients"]
        b = json.loads(semicolon.to_json())["identification"]["coefficients"]
        for term in a:
            self.assertLess(abs(a[term]["value"] - b[term]["value"]), 1e-3 * a[term]["std_error"], term)
        runs = semicolon.logs.runs
        self.assertEqual([r.log.gaps for r in runs], [0, 0, 1, 0])
        self.assertAlmostEqual(runs[2].log.missing, 5.0, delta=0.08)  # to a step of the 20 g run's sampling

    def test_a_dict_of_logs_takes_the_layout_as_the_command_line_does(self):
        logs = {run: os.path.join(DAQ, "semicolon", f"{run}.csv") for run in RUNS}
        layout = os.path.join(DAQ, "semicolon_layout.toml")
        by_dict = ccal.reduce(self.config, logs, log_layout=layout)
        by_folder = ccal.reduce(self.config, os.path.join(DAQ, "semicolon"))
        self.assertEqual(list(by_dict.coefficients), list(by_folder.coefficients))
        # A semicolon file read as ccal's own: the header is one name that holds ';', and the message names the
        # key to set.
        with tempfile.TemporaryDirectory() as folder:
            with open(os.path.join(DAQ, "comma", "20g.csv")) as f:
                text = f.read().replace(",", ";")
            with open(os.path.join(folder, "20g.csv"), "w") as f:
                f.write(text)
            mixed = {r: os.path.join(DAQ, "comma", f"{r}.csv") for r in RUNS}
            mixed["20g"] = os.path.join(folder, "20g.csv")
            with self.assertRaisesRegex(ccal.InputError, r"20g.csv:1:1: the header is one name.*the delimiter is "
                                                         r"probably ';'.*delimiter = \"semicolon\""):
                ccal.reduce(self.config, mixed)
        with self.assertRaisesRegex(ccal.InputError, "log_layout is for a dict of logs"):
            ccal.reduce(self.config, os.path.join(DAQ, "comma"), log_layout=layout)

    def test_a_bad_format_key_is_refused_at_its_line(self):
        with tempfile.TemporaryDirectory() as folder:
            for run in RUNS:
                shutil.copy(os.path.join(DAQ, "semicolon", f"{run}.csv"), folder)
            with open(os.path.join(DAQ, "semicolon", "manifest.toml")) as f:
                text = f.read().replace("max_gap = '10 s'", "max_gap = '2 s'")
            with open(os.path.join(folder, "manifest.toml"), "w") as f:
                f.write(text)
            with self.assertRaisesRegex(ccal.InputError, r"20g.csv:144:1: t_ms: a gap of 5.06024 s .* at most max_gap "
                                                         r"= 2 s"):
                ccal.reduce(self.config, folder)
            with open(os.path.join(folder, "manifest.toml"), "w") as f:
                f.write(text.replace("decimal = 'comma'", "decimal = 'dot'"))
            with self.assertRaisesRegex(ccal.InputError, r"manifest.toml:4:11: format.decimal: unknown value 'dot'; "
                                                         r"accepted: point, comma"):
                ccal.reduce(self.config, folder)


if __name__ == "__main__":
    unittest.main()
