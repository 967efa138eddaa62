"""Logs as a data acquisition system writes them, from Python (docs/python.md, reduce): the sample folders of
examples/daq reduce through reduce(config, folder) with their manifest's [format] and [columns] keys, a dict
of logs takes the same layout through log_layout= (as `ccal reduce --log … --log-layout FILE`), and a bad key
is refused with its file, line and key."""

import datetime
import json
import os
import pathlib
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

    def test_arguments_of_another_kind_are_refused_naming_them(self):
        # Found by the careless round: os.fspath's words named no argument; a list of logs was "log_layout is for
        # a dict of logs; a folder's manifest has the layout"; an unknown run's key said "run: … or an index
        # 1..4" (the command line's 1-based index: Python's are 0-based).
        logs = {run: os.path.join(DAQ, "semicolon", f"{run}.csv") for run in RUNS}
        layout = os.path.join(DAQ, "semicolon_layout.toml")
        with self.assertRaisesRegex(TypeError, r"^reduce\(\): log_layout: expected the path \(str or os.PathLike\) "
                                               r"of a layout file.*, got int$"):
            ccal.reduce(self.config, logs, log_layout=5)
        with self.assertRaisesRegex(TypeError, r"^reduce\(\): logs: expected a dict of run .* or a folder with its "
                                               r"manifest.toml .*, got list$"):
            ccal.reduce(self.config, list(logs.values()), log_layout=layout)
        wrong = dict(logs)
        wrong["7g"] = wrong.pop("5g")
        with self.assertRaisesRegex(ccal.InputError, r"^logs: '7g' is no run; accepted: a run name \(5g, 10g, 20g, "
                                                     r"30g\) or a 0-based index 0 to 3$"):
            ccal.reduce(self.config, wrong, log_layout=layout)
        with self.assertRaisesRegex(ccal.InputError, r"^run: '7g' is no run; accepted: .* 0-based index 0 to 3$"):
            ccal.sensed_input(self.config, run="7g")
        # A log given as a path object is a path (it was "Unable to cast Python instance to C++ type"), a number is
        # refused naming its entry, and a mistyped keyword for the logs gets Python's words, not pybind11's
        # "incompatible function arguments" with the configuration's repr.
        by_path = ccal.reduce_logs(self.config, {run: pathlib.Path(path) for run, path in logs.items()},
                                   log_layout=pathlib.Path(layout))
        self.assertEqual(len(by_path.runs), 4)
        with self.assertRaisesRegex(TypeError, r"^reduce\(\): logs\['5g'\]: expected the path of a log file \(str or "
                                               r"os.PathLike\), got int$"):
            ccal.reduce(self.config, dict(logs, **{"5g": 5}), log_layout=layout)
        with self.assertRaisesRegex(TypeError, r"^reduce\(\): logs: a key 1.5 is no run"):
            ccal.reduce(self.config, {1.5: logs["5g"]}, log_layout=layout)
        with self.assertRaisesRegex(TypeError, r"^reduce\(\): missing a required argument: 'logs'; 'log' is no "
                                               r"keyword: did you mean 'logs'\?; accepted: config, logs, log_layout"):
            ccal.reduce(self.config, log=logs)
        with tempfile.TemporaryDirectory() as folder:
            not_toml = os.path.join(folder, "layout.yaml")
            with open(not_toml, "w") as f:
                f.write("delimiter: semicolon\n")
            with self.assertRaisesRegex(ccal.InputError, r"layout.yaml:1:10: TOML syntax error.*; accepted: a layout "
                                                         r"file in TOML"):
                ccal.reduce(self.config, logs, log_layout=not_toml)
            with self.assertRaisesRegex(ccal.InputError, r": it is a folder; accepted: a layout file in TOML"):
                ccal.reduce(self.config, logs, log_layout=folder)

    def test_reduce_logs_takes_the_layout_too(self):
        # reduce_logs read ccal's own layout only: a DAQ's logs were refused at their preamble, now named as one.
        logs = {run: os.path.join(DAQ, "semicolon", f"{run}.csv") for run in RUNS}
        layout = os.path.join(DAQ, "semicolon_layout.toml")
        by_reduce = ccal.reduce(self.config, logs, log_layout=layout)
        alone = ccal.reduce_logs(self.config, logs, log_layout=layout)
        self.assertEqual([r.log.mean_output for r in alone.runs], [r.log.mean_output for r in by_reduce.logs.runs])
        self.assertEqual([r.log.gaps for r in alone.runs], [0, 0, 1, 0])
        with self.assertRaisesRegex(ccal.InputError, r"\dg.csv:1: time: no such column: the header, line 1 .* a "
                                                     r"preamble above it\? accepted: header_line or skip_lines"):
            ccal.reduce_logs(self.config, logs)

    def test_timestamps_with_and_without_their_zone_are_refused(self):
        # The comma folder's times as ISO 8601 timestamps, the first five rows with 'Z' and the rest without: the
        # time between them is not known (an hour off in another zone); they were read as written.
        start = datetime.datetime(2026, 11, 30, 10, 15)
        with tempfile.TemporaryDirectory() as folder:
            for run in RUNS:
                with open(os.path.join(DAQ, "comma", f"{run}.csv")) as f:
                    lines = f.read().splitlines()
                rows = [lines[0]]
                for k, line in enumerate(lines[1:]):
                    t, rest = line.split(",", 1)
                    stamp = (start + datetime.timedelta(seconds=float(t))).isoformat(timespec="microseconds")
                    rows.append(f"{stamp}{'Z' if k < 5 else ''},{rest}")
                with open(os.path.join(folder, f"{run}.csv"), "w") as f:
                    f.write("\n".join(rows) + "\n")
            with open(os.path.join(DAQ, "comma", "manifest.toml")) as f:
                manifest = f.read().replace("time_unit = 's'", "time_unit = 'iso8601'")
            with open(os.path.join(folder, "manifest.toml"), "w") as f:
                f.write(manifest)
            with self.assertRaisesRegex(ccal.InputError, r"5g.csv:7:1: time: '2026-11-30T10:15:00.\d+' states no "
                                                         r"zone, the log's first timestamp \(line 2\) does"):
                ccal.reduce(self.config, folder)

if __name__ == "__main__":
    unittest.main()
