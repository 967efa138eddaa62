"""to_frame() with pandas (Debian's python3-pandas, which scripts/setup.sh installs for the tests; ccal does not
require it): every result that has to_frame() (the module's classes are enumerated: a new one without a case
here fails) gives a frame whose numeric columns are numbers (float64 or int64, not text), whose text columns
(units, names, a statement's rounded figures) are text with their trailing zeros, equal to display()'s rows,
and which round-trips through DataFrame.to_csv and pandas.read_csv exactly (the text columns read as text).
Run by ctest with Debian's python3 and the module on PYTHONPATH."""

import io
import json
import math
import os
import shutil
import tempfile
import unittest

try:
    import pandas
except ImportError as e:  # the full set-up installs it: a missing pandas is a set-up to complete, not a skip
    raise ImportError("tests/python/test_frames.py needs pandas: apt-get install python3-pandas (bash "
                      "scripts/setup.sh installs it)") from e

import ccal

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
LAB = os.path.join(ROOT, "examples", "lab.toml")


def frame_history(folder):
    db = os.path.join(folder, "h.sqlite")
    for i, (k2, date) in enumerate([(5.0, "2020-06-01"), (5.25, "2021-06-01"), (5.75, "2023-06-01")]):
        path = os.path.join(folder, f"s{i}.json")
        with open(path, "w", encoding="utf-8") as f:
            json.dump({"coverage_probability": 0.95, "coefficients": {"K2": {
                "unit": "deg/s/g^2", "corrected_estimate": k2, "expanded_uncertainty": 0.2,
                "coverage_factor": 2.0, "effective_dof": None}}}, f)
        ccal.history_add(path, db=db, serial="SN 1", date=date)
    return ccal.history("SN 1", db=db, at="2024-06-01")


class Frames(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp()
        cfg = ccal.load_config(LAB)
        sim = ccal.simulate(cfg)
        logs = sim.write_logs(os.path.join(cls.folder, "logs"))
        observations = os.path.join(cls.folder, "observations.csv")
        with open(observations, "w", encoding="utf-8") as f:
            f.write(sim.to_csv())
        reduction = ccal.reduce(cfg, logs, statement=True, statement_trials=2000)
        budget = ccal.budget(cfg)
        cls.frames = {  # label → (the result's class, its table, its frame)
            "Config": cfg, "Budget": budget, "SensedInput": ccal.sensed_input(cfg, run="20g", time=10.0),
            "History": frame_history(cls.folder), "Simulation": sim, "Fit": ccal.identify(sim.observations, cfg),
            "Statement": reduction.statement, "Reduction": reduction,
            "MonteCarlo": ccal.monte_carlo(cfg, trials=2000),
            "Allocation": ccal.allocate(cfg, {"K2": "5e-4 deg/s/g^2"}, verify_trials=200),
            "Identification": ccal.identify_file(observations, statement=True, config=cfg, statement_trials=2000),
            "Reduction of two instruments": ccal.reduce(ccal.load_config(os.path.join(ROOT, "examples", "daq",
                                                                                       "two_short.toml")),
                                                        os.path.join(ROOT, "examples", "daq", "two_instruments")),
        }
        cls.tables = {label: (type(r).__name__, r.display(), r.to_frame()) for label, r in cls.frames.items()}
        # A statement's frame is not its display() (the certificate's rounded figures): its own test below.
        cls.tables["Statement"] = ("Statement", None, cls.tables["Statement"][2])
        cls.tables["Budget.sources_frame"] = ("Budget", budget.sources_table(), budget.sources_frame())

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)

    def test_every_class_with_to_frame_has_a_case_here(self):
        classes = {name for name, v in vars(ccal).items() if isinstance(v, type) and hasattr(v, "to_frame")}
        classes.discard("Table")  # display()'s, through which each case here goes
        self.assertGreaterEqual(len(classes), 11)
        self.assertEqual(sorted(classes - {kind for kind, _, _ in self.tables.values()}), [])

    def test_numbers_are_numbers_and_text_is_text(self):
        for label, (_, table, frame) in self.tables.items():
            with self.subTest(frame=label):
                if table is None:
                    text = [c for c in frame.columns if frame[c].dtype == object]
                    self.assertEqual(text, ["coefficient", "unit", "interval_method", "value_rounded", "U_rounded",
                                            "low_rounded", "high_rounded"])
                    continue
                self.assertEqual(list(frame.columns), table.columns)
                self.assertEqual(len(frame), len(table.rows))
                numeric = 0
                for column in table.columns:
                    cells = [row[column] for row in table.rows]
                    dtype = str(frame[column].dtype)
                    if all(isinstance(c, bool) for c in cells):
                        self.assertEqual(dtype, "bool", column)
                    elif all(c is None or (isinstance(c, (int, float)) and not isinstance(c, bool)) for c in cells):
                        if all(c is None for c in cells):
                            continue
                        self.assertIn(dtype, ("float64", "int64"), column)
                        numeric += 1
                        for k, c in enumerate(cells):  # the same number, to the last bit
                            value = frame[column].iloc[k]
                            self.assertTrue(math.isnan(value) if c is None or c != c else value == c, column)
                    else:
                        self.assertEqual(dtype, "object", column)
                        self.assertEqual(list(frame[column]), cells, column)
                self.assertGreater(numeric, 0, "a frame without a numeric column")

    def test_a_statements_rounded_figures_are_text_columns_of_their_own(self):
        _, _, frame = self.tables["Statement"]
        statement = self.frames["Statement"].to_dict()["coefficients"]
        for column in ("value", "U", "low", "high"):
            self.assertEqual(str(frame[column].dtype), "float64", column)
            self.assertEqual(str(frame[f"{column}_rounded"].dtype), "object", column)
        for name, c in statement.items():
            self.assertEqual(frame.loc[name, "U_rounded"], c["rounded"]["expanded_uncertainty"])
            self.assertEqual(frame.loc[name, "U"], c["expanded_uncertainty"])
        # The lab's K2 is 0.02 to the figures its uncertainty gives: its trailing zeros are kept as written.
        self.assertEqual(frame.loc["K2", "value_rounded"], "0.020000")

    def test_each_frame_round_trips_through_csv(self):
        for label, (_, _, frame) in self.tables.items():
            with self.subTest(frame=label):
                text = {c: str for c in frame.columns if frame[c].dtype == object}
                # A missing number as "nan", so that an empty text ("" verdict) reads back as itself.
                back = pandas.read_csv(io.StringIO(frame.to_csv(na_rep="nan")), index_col=0, dtype=text,
                                       float_precision="round_trip", keep_default_na=False, na_values=["nan"])
                back.index = back.index.astype(frame.index.dtype)
                back.index.name = frame.index.name
                pandas.testing.assert_frame_equal(back, frame, check_exact=True)

    def test_the_observations_and_statement_files_read_by_pandas_as_docs_cli_md_says(self):
        # An observations file (Simulation.to_csv(), as --observations-out writes it): its '#' lines comments,
        # each number the same double as Python reads from the text.
        text = self.frames["Simulation"].to_csv()
        table = pandas.read_csv(io.StringIO(text), comment="#", float_precision="round_trip")
        lines = [line.split(",") for line in text.splitlines() if not line.startswith("#")]
        self.assertEqual(list(table.columns), lines[0])
        self.assertEqual(list(table["run"]), [row[0] for row in lines[1:]])
        for k, row in enumerate(lines[1:]):
            self.assertEqual([table[c].iloc[k] for c in lines[0][1:]], [float(v) for v in row[1:]])
        # statement.csv (Statement.to_csv()): the rounded figures, quoted, read as text with their zeros.
        rounded = ("rounded_estimate", "rounded_expanded_uncertainty", "rounded_low", "rounded_high")
        statement = pandas.read_csv(io.StringIO(self.frames["Statement"].to_csv()), dtype={c: str for c in rounded})
        figures = self.frames["Statement"].to_dict()["coefficients"]
        for k, name in enumerate(statement["coefficient"]):
            r = figures[name]["rounded"]
            self.assertEqual([statement[c].iloc[k] for c in rounded],
                             [r["estimate"], r["expanded_uncertainty"], *r["interval"]])
        self.assertEqual(str(statement["expanded_uncertainty"].dtype), "float64")


if __name__ == "__main__":
    unittest.main()
