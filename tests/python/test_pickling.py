"""Every result pickles by value (docs/python.md, "Pickling"): small, and unpickled without computing anything
into an object of the same name, taken by isinstance() for its class, whose every attribute (its parts', to
the last one) is the original's to the last bit, whose to_json(), str(), to_csv() and (a Report's) to_html() are
the original's, and whose log files need not exist any more. Every class of the module is reached by a round
trip here (a new class without one fails). An unpickled Simulation's run_logs() simulate again, to the same
bytes. Run by ctest with Debian's python3 and the module on PYTHONPATH."""

import json
import math
import os
import pickle
import shutil
import struct
import tempfile
import time
import unittest

import numpy as np

import ccal

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
LAB = os.path.join(ROOT, "examples", "lab.toml")
DAQ = os.path.join(ROOT, "examples", "daq")
SMALL_SPACE = '\n[design]\ng_step = "5 g"\nturn_fractions = 4\nphase_step = "90 deg"\nazimuth_step = "180 deg"\nstarts = 2\n'

# The largest pickle of each result (bytes): about 1.5 times what each pickles to today, so that a result that
# grows by half fails here. The reduction of the lab's logs with its statement was 2.5 MB pickled as its call
# (its logs with it); by value it is about 33 kB. A Design holds two full budgets (51 kB; 109 kB for two
# instruments); a Report its sections and its page without the 839 kB of charting scripts (119 kB with a design;
# its page with the scripts would add some 280 kB compressed).
SIZE_LIMIT = {"Budget": 45_000, "MonteCarlo": 25_000, "Allocation": 20_000, "Simulation": 14_000,
              "Reduction": 50_000, "Statement": 21_000, "SensedInput": 10_000, "Identification": 35_000,
              "Fit": 2_000, "Observations": 3_000, "Observability": 4_000, "LogReduction": 12_000,
              "History": 12_000, "HistoryImport": 1_000, "HistorySerial": 1_000, "Tolerance": 1_000,
              "Design": 77_000, "Report": 180_000, "Budget of two instruments": 112_000,
              "Reduction of two instruments": 130_000, "Design of two instruments": 163_000}


def bound(value):
    return isinstance(type(value), type(ccal.Config)) or isinstance(value, ccal.StoredResult)


def fields(cls):
    return [n for n, v in vars(cls).items() if isinstance(v, property) and not n.startswith("_")]


class ByValue(unittest.TestCase):
    seen = set()  # the classes of the module whose objects assert_same compared

    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.mkdtemp()
        cfg = ccal.load_config(LAB)
        sim = ccal.simulate(cfg)
        logs = sim.write_logs(os.path.join(cls.folder, "logs"))
        observations = os.path.join(cls.folder, "observations.csv")
        with open(observations, "w", encoding="utf-8") as f:
            f.write(sim.to_csv())
        cls.reduction = ccal.reduce(cfg, logs, statement=True, statement_trials=2000)
        cls.results = {
            "Budget": ccal.budget(cfg),
            "MonteCarlo": ccal.monte_carlo(cfg, trials=2000),
            "Allocation": ccal.allocate(cfg, {"K2": "5e-4 deg/s/g^2"}, verify_trials=200),
            "Simulation": sim,
            "Reduction": cls.reduction,
            "Statement": cls.reduction.statement,
            "SensedInput": ccal.sensed_input(cfg, run="20g", time=10.0),
            "Identification": ccal.identify_file(observations, statement=True, config=cfg, statement_trials=2000),
            "Fit": ccal.identify(sim.observations, cfg),
            "Observations": ccal.observe(cfg),
            "Observability": ccal.observability(sim.observations, cfg),
            "LogReduction": ccal.reduce_logs(cfg, logs),
            "Tolerance": cfg.tolerances[0],
        }
        cls.results.update(cls.history_results())
        cls.results.update(cls.design_results())

    @classmethod
    def design_results(cls):
        os.environ["SOURCE_DATE_EPOCH"] = "1700000000"  # the page's date: the same on every call
        small = ccal.parse_config(ccal.bundled_example_text() + SMALL_SPACE, "small.toml")
        two = ccal.load_config(os.path.join(DAQ, "two_short.toml"))
        with open(os.path.join(DAQ, "two_short.toml"), encoding="utf-8") as f:
            two_small = ccal.parse_config(f.read() + SMALL_SPACE, os.path.join(DAQ, "two_short_design.toml"))
        return {"Design": ccal.design(small, threads=1),
                "Report": ccal.report(small, trials=1000, design=True, threads=1),
                "Budget of two instruments": ccal.budget(two),
                "Reduction of two instruments": ccal.reduce(two, os.path.join(DAQ, "two_instruments"),
                                                            statement=True, statement_trials=500),
                "Design of two instruments": ccal.design(two_small, threads=1)}

    @classmethod
    def history_results(cls):
        db = os.path.join(cls.folder, "h.sqlite")
        for i, (k2, date) in enumerate([(5.0, "2020-06-01"), (5.25, "2021-06-01"), (5.75, "2023-06-01")]):
            path = os.path.join(cls.folder, f"s{i}.json")
            with open(path, "w", encoding="utf-8") as f:
                json.dump({"coverage_probability": 0.95, "coefficients": {"K2": {
                    "unit": "deg/s/g^2", "corrected_estimate": k2, "expanded_uncertainty": 0.2,
                    "coverage_factor": 2.0, "effective_dof": None}}}, f)
            ccal.history_add(path, db=db, serial="SN 1", date=date)
        export = os.path.join(cls.folder, "export.json")
        with open(export, "w", encoding="utf-8") as f:
            f.write(ccal.history_export("SN 1", db=db))
        return {"History": ccal.history("SN 1", db=db, at="2024-06-01"),
                "HistorySerial": ccal.history_list(db=db)[0],
                "HistoryImport": ccal.history_import(export, db=os.path.join(cls.folder, "h2.sqlite"))}

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.folder)
        del os.environ["SOURCE_DATE_EPOCH"]

    def assert_same(self, a, b, where):
        """b is a, to the last bit, through every attribute of every part."""
        if isinstance(a, np.ndarray):
            self.assertIsInstance(b, np.ndarray, where)
            self.assertEqual((a.dtype, a.shape, a.tobytes()), (b.dtype, b.shape, b.tobytes()), where)
        elif isinstance(a, float):
            self.assertIsInstance(b, float, where)
            self.assertEqual(struct.pack("<d", a), struct.pack("<d", b), where)  # NaN and -0.0 included
        elif bound(a):
            self.seen.add(type(a).__name__)
            self.assertEqual(type(b).__name__, type(a).__name__, where)
            self.assertIsInstance(b, type(a) if not isinstance(a, ccal.StoredResult) else a._ccal_original, where)
            for name in fields(type(a)):
                try:
                    value = getattr(a, name)
                except Exception as e:  # raised again the same way (MonteCarlo.samples without keep_samples)
                    with self.assertRaises(type(e), msg=f"{where}.{name}") as raised:
                        getattr(b, name)
                    self.assertEqual(str(raised.exception), str(e))
                    continue
                self.assert_same(value, getattr(b, name), f"{where}.{name}")
        elif isinstance(a, (list, tuple)):
            self.assertIs(type(b), type(a), where)
            self.assertEqual(len(a), len(b), where)
            for k, (x, y) in enumerate(zip(a, b)):
                self.assert_same(x, y, f"{where}[{k}]")
        elif isinstance(a, dict):
            self.assertEqual(list(a), list(b), where)
            for k in a:
                self.assert_same(a[k], b[k], f"{where}[{k!r}]")
        else:
            self.assertIs(type(b), type(a), where)
            self.assertEqual(a, b, where)

    def round_trip(self, label, result):
        data = pickle.dumps(result)
        self.assertLess(len(data), SIZE_LIMIT[label])
        back = pickle.loads(data)
        self.assertIsInstance(back, type(result))
        self.assertEqual(type(back).__name__, type(result).__name__)
        self.assert_same(result, back, label)
        for text in ("to_json", "to_csv", "to_html"):
            if hasattr(result, text):
                self.assertEqual(getattr(back, text)(), getattr(result, text)(), text)
        self.assertEqual(str(back), str(result))
        self.assertEqual(repr(back), repr(result))
        self.assert_same(back, pickle.loads(pickle.dumps(back)), f"{label} pickled twice")

    def test_every_result_round_trips_by_value_and_small(self):
        for label, result in self.results.items():
            with self.subTest(result=label):
                self.round_trip(label, result)

    def test_every_class_of_the_module_is_reached_by_a_round_trip(self):
        for label, result in self.results.items():
            self.round_trip(label, result)
        classes = {name for name, v in vars(ccal._ccal).items()
                   if isinstance(v, type) and not name.startswith("_") and not issubclass(v, BaseException)}
        self.assertGreater(len(classes), 40)
        self.assertEqual(sorted(classes - self.seen), [], "classes of ccal that no round trip here reaches: give "
                                                          "each a result in setUpClass that holds one")

    def test_the_reduction_is_small_and_needs_neither_logs_nor_computing(self):
        # The logs are gone, and reduce() would fail: unpickling reads only what was pickled.
        data = pickle.dumps(self.reduction)
        self.assertLess(len(data), 100_000)  # was 2.5 MB as its call, its logs with it
        moved = os.path.join(self.folder, "moved")
        os.rename(os.path.join(self.folder, "logs"), moved)
        original_reduce, ccal._ccal.reduce = ccal._ccal.reduce, None  # computing now would raise TypeError
        try:
            back = pickle.loads(data)
            self.assertEqual(back.to_json(), self.reduction.to_json())
            self.assertEqual(back.statement.to_csv(), self.reduction.statement.to_csv())
            self.assertEqual(back.display().rows, self.reduction.display().rows)
            self.assertEqual(back.coefficients.tobytes(), self.reduction.coefficients.tobytes())
        finally:
            ccal._ccal.reduce = original_reduce
            os.rename(moved, os.path.join(self.folder, "logs"))

    def test_the_samples_a_monte_carlo_kept_and_the_error_without_them(self):
        mc = ccal.monte_carlo(ccal.load_config(LAB), trials=500)
        back = pickle.loads(pickle.dumps(mc))
        with self.assertRaisesRegex(ccal.InputError, "keep_samples"):
            back.samples
        kept = ccal.monte_carlo(ccal.load_config(LAB), trials=2000, keep_samples=True)
        data = pickle.dumps(kept)
        # The samples are values too: 2000 × 3 doubles, 48 kB, which compress little; the rest as above.
        self.assertLess(len(data), 48_000 + SIZE_LIMIT["MonteCarlo"])
        self.assert_same(kept, pickle.loads(data), "MonteCarlo")

    def test_a_stored_simulation_writes_its_logs_by_simulating_again(self):
        # Its logs are not stored (about 1 MB compressed for the lab's six runs): run_logs(), logs_manifest() and
        # write_logs() simulate again from the stored call, to the same bytes.
        sim = self.results["Simulation"]
        back = pickle.loads(pickle.dumps(sim))
        self.assertEqual(back.run_logs(), sim.run_logs())
        self.assertEqual(back.run_logs(step=0.1), sim.run_logs(step=0.1))
        self.assertEqual(back.logs_manifest(), sim.logs_manifest())
        with tempfile.TemporaryDirectory() as folder:
            paths = back.write_logs(os.path.join(folder, "back"))
            originals = sim.write_logs(os.path.join(folder, "original"))
            self.assertEqual(sorted(os.listdir(os.path.join(folder, "back"))),
                             sorted([os.path.basename(p) for p in paths.values()] + ["manifest.toml"]))
            for run, path in paths.items():
                with open(path, "rb") as f, open(originals[run], "rb") as g:
                    self.assertEqual(f.read(), g.read(), run)

    def test_several_instruments(self):
        for label in ("Budget of two instruments", "Reduction of two instruments", "Design of two instruments"):
            back = pickle.loads(pickle.dumps(self.results[label]))
            self.assertEqual([b.config.instrument_id for b in back.instruments], ["A", "B"], label)

    def test_the_fit_of_plain_arrays(self):
        fit = ccal.fit(np.array([[1.0, 1.0], [1.0, 2.0], [1.0, 3.0]]), np.array([1.0, 2.0, 3.1]), ["a", "b"])
        self.assert_same(fit, pickle.loads(pickle.dumps(fit)), "Fit")

    def test_a_design_and_a_report_unpickle_without_computing_and_their_configurations_work(self):
        # design() and report() would raise now: unpickling computes neither. The designed configuration (and
        # the configured one with the design's measured inputs, the budgets') is a Config again, which budgets
        # to the same bytes as the original's: its part Python does not see (the encoders' measured rates) too.
        design, report, two = (self.results[k] for k in ("Design", "Report", "Design of two instruments"))
        data = [pickle.dumps(r) for r in (design, report, two)]
        saved = ccal._ccal.design, ccal._ccal.report
        ccal._ccal.design = ccal._ccal.report = None
        try:
            back, back_report, back_two = (pickle.loads(d) for d in data)
        finally:
            ccal._ccal.design, ccal._ccal.report = saved
        pairs = [(back.designed, design.designed), (back.before.config, design.before.config),
                 (back.after.config, design.after.config), (back_report.design.designed, report.design.designed),
                 (back_two.designed, two.designed), (back_two.instruments[1].before.config,
                                                     two.instruments[1].before.config)]
        for stored, original in pairs:
            self.assertIs(type(stored), ccal.Config)
            self.assertEqual(ccal.budget(stored).to_json(), ccal.budget(original).to_json())
        text = ccal.bundled_example_text() + SMALL_SPACE
        self.assertEqual(back.config_text(text), design.config_text(text))
        self.assertIsNone(back_two.before)
        self.assertIn("vega-embed", back_report.to_html())  # the scripts put back
        self.assertTrue(callable(back_report.to_pdf))

    def test_unpickling_is_fast(self):
        data = pickle.dumps(self.reduction)
        start = time.perf_counter()
        pickle.loads(data)
        # Well under the reduction's own time (its Monte Carlo check alone is 2000 trials): 1 s is a generous bound
        # for reading 33 kB on a loaded machine.
        self.assertLess(time.perf_counter() - start, 1.0)
        self.assertFalse(math.isnan(self.reduction.coefficients[0]))


if __name__ == "__main__":
    unittest.main()
