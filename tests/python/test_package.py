"""The module as a package: its layout (the compiled part ccal._ccal, the Python modules beside it, importable
and with real file names in tracebacks), its metadata, the standard exception for a missing file, the frames
of results, the defaults and checks taken from the library, and reduce's calibration statement. Run by ctest
(python.bindings) with the build tree's python folder on PYTHONPATH and the program in CCAL_PROGRAM."""

import importlib
import importlib.machinery
import importlib.metadata
import inspect
import json
import os
import subprocess
import tempfile
import unittest

import ccal
import ccal._ccal

from test_same_as_cli import normalised, program_json

SECOND = os.path.join(os.path.dirname(__file__), "..", "data", "golden", "second.toml")
PROGRAM = os.environ.get("CCAL_PROGRAM")


class Layout(unittest.TestCase):
    def test_a_package_with_a_private_compiled_module(self):
        folder = os.path.dirname(ccal.__file__)
        self.assertEqual(os.path.basename(ccal.__file__), "__init__.py")
        self.assertEqual(os.path.dirname(ccal._ccal.__file__), folder)
        self.assertTrue(ccal._ccal.__file__.endswith(importlib.machinery.EXTENSION_SUFFIXES[0]))
        for name in ("_signatures", "_tables", "_pickling", "_results", "_install"):
            with self.subTest(module=name):
                module = importlib.import_module(f"ccal.{name}")
                self.assertEqual(module.__file__, os.path.join(folder, name + ".py"))

    def test_the_python_code_has_its_file_names(self):
        # It was run from strings compiled into the extension: "<string>" in tracebacks and for inspect.
        folder = os.path.dirname(ccal.__file__)
        self.assertEqual(inspect.getsourcefile(ccal.Table.to_frame), os.path.join(folder, "_tables.py"))
        self.assertEqual(inspect.getsourcefile(ccal.Budget.display), os.path.join(folder, "_results.py"))
        cfg = ccal.bundled_example()
        try:
            ccal._pickling.restore_result("budget", cfg, {}, None, ccal.budget(cfg).to_json().replace(
                '"expanded_uncertainty": ', '"expanded_uncertainty": 1', 1))
            self.fail("a tampered pickle was accepted")
        except ValueError as e:
            tb = e.__traceback__
        while tb.tb_next:
            tb = tb.tb_next
        self.assertEqual(tb.tb_frame.f_code.co_filename, os.path.join(folder, "_pickling.py"))

    def test_public_names_live_in_ccal(self):
        for name in ("Budget", "Config", "InputError", "FileNotFound", "Table"):
            with self.subTest(name=name):
                self.assertEqual(getattr(ccal, name).__module__, "ccal")
        self.assertEqual(ccal.budget.__module__, "ccal")
        self.assertNotIn("_ccal", inspect.signature(ccal.budget).parameters["config"].annotation)


class Metadata(unittest.TestCase):
    def test_the_distribution_has_the_project_version(self):
        self.assertEqual(importlib.metadata.version("ccal"), ccal.__version__)
        meta = importlib.metadata.metadata("ccal")
        self.assertEqual(meta["Name"], "ccal")
        self.assertIn("accelerometers", meta["Summary"])


class MissingFiles(unittest.TestCase):
    def missing(self, name):
        return os.path.join(tempfile.gettempdir(), "ccal no such folder", name)

    def test_a_missing_file_is_a_file_not_found_error_and_an_input_error(self):
        cfg = ccal.bundled_example()
        cases = [("config.toml", lambda p: ccal.load_config(p)),
                 ("table.csv", lambda p: ccal.identify_file(p)),
                 # As many logs as free terms (fewer are refused before any is read), the first missing.
                 ("run1.csv", lambda p: ccal.reduce_logs(cfg, {0: p, 1: p + ".2", 2: p + ".3"}))]
        for name, call in cases:
            path = self.missing(name)
            with self.subTest(file=name):
                with self.assertRaises(FileNotFoundError) as e:
                    call(path)
                self.assertIsInstance(e.exception, ccal.InputError)
                self.assertIsInstance(e.exception, ccal.FileNotFound)
                self.assertEqual(str(e.exception), f"{path}: cannot read the file: no such file; accepted: the path "
                                                   "of an existing file (check its spelling and folder)")

    def test_other_bad_input_is_not_a_file_error(self):
        with self.assertRaises(ccal.InputError) as e:
            ccal.parse_config("[plan\n", "bad.toml")
        self.assertNotIsInstance(e.exception, OSError)

    @unittest.skipUnless(PROGRAM, "CCAL_PROGRAM is not set")
    def test_the_program_keeps_exit_2_and_the_message(self):
        path = self.missing("config.toml")
        with self.assertRaises(FileNotFoundError) as e:
            ccal.load_config(path)
        run = subprocess.run([PROGRAM, "budget", path], capture_output=True, text=True)
        self.assertEqual(run.returncode, 2)
        self.assertIn(str(e.exception), run.stderr)


class Frames(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.budget = ccal.budget(ccal.bundled_example())

    def test_per_source_table_in_display_units(self):
        b, table = self.budget, self.budget.sources_table()
        self.assertEqual([r["source"] for r in table.rows], [s["id"] for s in b.to_dict()["sources"]])
        self.assertEqual(sorted(r["source"] for r in table.rows), sorted(b.source_ids))
        row_of = {r["source"]: r for r in table.rows}
        for i, source in enumerate(b.source_ids):
            for k, (name, unit) in enumerate(zip(b.coefficients, b.units)):
                with self.subTest(source=source, coefficient=name):
                    # The JSON's effect is the SI effect times the display scale: equal to rounding of the
                    # product (a few ulp).
                    self.assertAlmostEqual(row_of[source][f"effect {name} [{unit}]"] /
                                           (b.effect[i, k] * b.display_scale[k]) if b.effect[i, k] else 1.0,
                                           1.0, delta=1e-12)
                    self.assertEqual(row_of[source][f"share {name}"], b.share[i, k])
                    # The GUM line (EA-4/02): c_i u(x_i) = u_i(y), one product's rounding (relative 1e-15).
                    row = row_of[source]
                    self.assertAlmostEqual(row[f"c {name} [{unit} per unit]"] * row["standard_uncertainty"],
                                           row[f"effect {name} [{unit}]"],
                                           delta=1e-15 * abs(row[f"effect {name} [{unit}]"]))
        for row in table.rows:
            with self.subTest(source=row["source"]):
                # u(x_i) = bound / divisor (relative 1e-15), a tolerance is Type B with ν = ∞, x_i = 0 here.
                self.assertAlmostEqual(row["standard_uncertainty"] * row["divisor"], row["bound"],
                                       delta=1e-15 * row["bound"])
                self.assertEqual((row["type"], row["dof"], row["estimate"]), ("B", float("inf"), 0.0))
                self.assertTrue(row["name"])

    def test_identification_has_the_display_view(self):
        with tempfile.TemporaryDirectory() as tmp:
            obs = os.path.join(tmp, "obs.csv")
            with open(obs, "w") as f:
                f.write(ccal.simulate(ccal.bundled_example()).to_csv())
            r = ccal.identify_file(obs)
        j = json.loads(r.to_json())
        self.assertEqual(r.to_dict(), j)
        table = r.display()
        self.assertEqual([row["coefficient"] for row in table.rows], list(j["coefficients"]))
        self.assertEqual([row["value"] for row in table.rows], [c["value"] for c in j["coefficients"].values()])
        self.assertIn("ccal.Identification", repr(r))

    def test_frames_are_indexed_by_the_first_column(self):
        try:
            import pandas  # noqa: F401
        except ImportError:
            self.skipTest("pandas is not installed (it is optional)")
        frame = self.budget.to_frame()
        self.assertEqual(list(frame.index), ["K0", "K2", "K3"])
        self.assertEqual(frame.loc["K3", "expanded_uncertainty"], self.budget.to_dict()["coefficients"][2]
                         ["expanded_uncertainty"])
        sources = self.budget.sources_frame()
        self.assertEqual(list(sources.index), list(sources["source"]))
        self.assertEqual(len(sources), len(self.budget.source_ids))


class LibraryDefaults(unittest.TestCase):
    def test_defaults_are_the_options_of_the_library(self):
        # AllocateOptions, DesignOptions, ReduceOptions, BudgetOptions (include/ccal/verbs/*.hpp). A verb that also
        # takes a stated coverage factor leaves its coverage probability unset (None: 0.95, its help says), so
        # that one given beside the factor is refused.
        expected = {"allocate": {"coverage_probability": 0.95, "max_scale": 10.0, "verify_trials": 2000,
                                 "seed": 1, "threads": 0},
                    "design": {"threads": 0, "verify_trials": 0, "tradeoff": [], "coverage_probability": None,
                               "coverage_factor": None},
                    "reduce": {"statement": False, "coverage_probability": None, "angle_unit": "rad"},
                    "identify_file": {"statement": False, "input_column": "a_i", "output_column": "output",
                                      "config": None},
                    "budget": {"coverage_probability": None, "coverage_factor": None, "compare_with_paper": True,
                               "derivatives": "linearised"}}
        for function, defaults in expected.items():
            parameters = inspect.signature(getattr(ccal, function)).parameters
            for name, value in defaults.items():
                with self.subTest(function=function, parameter=name):
                    self.assertEqual(parameters[name].default, value)
        for function in ("design", "reduce", "budget", "monte_carlo", "report", "identify_file"):
            with self.subTest(function=function):
                self.assertIn("coverage_probability (Optional[float], default None): Coverage probability",
                              getattr(ccal, function).__doc__)
                self.assertIn("(None: 0.95); accepted: a number in [0.5, 1)", getattr(ccal, function).__doc__)

    def test_the_library_checks_the_coverage_factor(self):
        # The library's message for k < 1 (the command line's), also for 0 and 0.5: no check of Python's own.
        for k in (0.0, 0.5):
            with self.subTest(k=k):
                with self.assertRaisesRegex(ccal.InputError, f"coverage_factor: {k:g} is out of range; accepted: 1 to 10"):
                    ccal.budget(ccal.bundled_example(), coverage_factor=k)


class ReduceStatement(unittest.TestCase):
    @unittest.skipUnless(PROGRAM, "CCAL_PROGRAM is not set")
    def test_reduce_with_statement_is_the_programs(self):
        cfg = ccal.bundled_example()
        with tempfile.TemporaryDirectory() as tmp:
            logs = ccal.simulate(cfg).write_logs(tmp)
            plain = ccal.reduce(cfg, logs)
            self.assertFalse(plain.has_statement)
            r = ccal.reduce(cfg, logs, statement=True, coverage_probability=0.9)
            self.assertTrue(r.has_statement)
            args = ["reduce", *[f"--log={k + 1}={p}" for k, p in enumerate(logs.values())], "--statement",
                    "--coverage-probability", "0.9"]
            self.assertEqual(normalised(r.to_dict()), program_json(*args))
            self.assertEqual(r.to_dict()["statement"]["coverage_probability"], 0.9)
            text = subprocess.run([PROGRAM, *args], check=True, capture_output=True, text=True).stdout
            self.assertEqual(str(r), text)


if __name__ == "__main__":
    unittest.main()
