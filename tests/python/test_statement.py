"""The calibration statement in Python (ccal.Statement): the same statement as `ccal reduce --statement
--statement-out`, its rounded figures those of the command line's lines, its covariance symmetric, positive
semi-definite with u_c² on the diagonal, and its conversion to correlated uncertain numbers (the package
uncertainties is optional: that test is skipped without it). Run by ctest with the module on PYTHONPATH and the
program in CCAL_PROGRAM."""

import json
import math
import os
import subprocess
import sys
import tempfile
import types
import unittest

import numpy as np

import ccal

LAB = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "lab.toml")
LAB_TRUTH = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "lab_truth.toml")


class StatementObject(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.folder = tempfile.TemporaryDirectory()
        config = ccal.load_config(LAB)
        cls.logs = ccal.simulate(config, truth=LAB_TRUTH).write_logs(cls.folder.name)
        cls.statement = ccal.reduce(config, cls.logs, statement=True).statement
        args = [os.environ["CCAL_PROGRAM"], "reduce", LAB, "--statement"]
        for run, path in cls.logs.items():
            args += ["--log", f"{run}={path}"]
        cls.json_file = os.path.join(cls.folder.name, "st.json")
        cls.text = subprocess.run(args + ["--statement-out", cls.json_file], check=True, capture_output=True,
                                  text=True).stdout

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    def test_the_same_statement_as_the_command_line(self):
        with open(self.json_file, encoding="utf-8") as f:
            self.assertEqual(json.loads(self.statement.to_json()), json.load(f))
        self.assertIn(str(self.statement), self.text)
        self.assertIsNone(ccal.reduce(ccal.load_config(LAB), self.logs).statement)

    def test_display_rows_are_the_rounded_lines(self):
        rows = self.statement.display().rows
        self.assertEqual([r["coefficient"] for r in rows], self.statement.names)
        for r in rows:
            if r["interval_method"] == "monte_carlo":  # the Monte Carlo's interval: its ends, not ± U
                line = f"  {r['coefficient']} = {r['value']} {r['unit']}, p = 95 %: [{r['low']}, {r['high']}]"
            else:
                line = f"  {r['coefficient']} = ({r['value']} ± {r['U']}) {r['unit']}, k = {r['k']:.3f}"
            self.assertIn(line, self.text)
        # K0 of the bundled lab: its Student-t interval, which the Monte Carlo check validates (every part has
        # ν = ∞ and the inputs are many), U to two significant digits; K2's is the Monte Carlo's, the encoders'
        # cyclic error (an arcsine input read as the drives' ripple) making most of it.
        self.assertEqual(rows[0]["interval_method"], "student_t")
        self.assertEqual(rows[0]["U"], "0.018")
        self.assertEqual(rows[1]["interval_method"], "monte_carlo")
        self.assertEqual([r["interval_method"] for r in rows], self.statement.interval_methods)
        self.assertEqual(self.statement.monte_carlo_requested_trials, 100000)
        self.assertGreaterEqual(self.statement.monte_carlo_trials, 100000)  # more while a verdict is unsettled
        # The attributes are SI, the JSON in the statement's units: × display_scale, to 1e-15 relative (a division
        # and a multiplication by the scale, each rounding by half an ulp).
        np.testing.assert_allclose(np.array(self.statement.intervals[1]) * self.statement.display_scale[1],
                                   self.statement.to_dict()["coefficients"]["K2"]["interval"], rtol=1e-15, atol=0)
        self.assertEqual([r["significant"] for r in rows], self.statement.significant)

    def test_to_frame_has_numbers_and_the_rounded_figures_as_text(self):
        # A stand-in for pandas records what to_frame gives it: value, U, low and high as numbers (the JSON's,
        # unrounded), the certificate's rounded figures as text columns of their own (trailing zeros kept).
        fake = types.ModuleType("pandas")
        fake.DataFrame = lambda data, columns, index: (data, columns, index)
        saved = sys.modules.get("pandas")
        sys.modules["pandas"] = fake
        try:
            data, columns, index = self.statement.to_frame()
        finally:
            if saved is None:
                del sys.modules["pandas"]
            else:
                sys.modules["pandas"] = saved
        self.assertEqual(index, self.statement.names)
        d = self.statement.to_dict()["coefficients"]
        for row in data:
            r = dict(zip(columns, row))
            c = d[r["coefficient"]]
            for column in ("value", "U", "low", "high", "k", "p", "nu_eff"):
                self.assertIsInstance(r[column], float, column)
            self.assertEqual(r["value"], c["corrected_estimate"])
            self.assertEqual(r["U"], c["expanded_uncertainty"])
            self.assertEqual([r["low"], r["high"]], c["interval"])
            self.assertEqual(r["value_rounded"], c["rounded"]["estimate"])
            self.assertEqual(r["U_rounded"], c["rounded"]["expanded_uncertainty"])
            self.assertEqual([r["low_rounded"], r["high_rounded"]], c["rounded"]["interval"])
            self.assertIsInstance(r["U_rounded"], str)

    def test_a_stated_coverage_factor_gives_k_times_uc(self):
        config = ccal.load_config(LAB)
        s = ccal.reduce(config, self.logs, statement=True, coverage_factor=2, statement_trials=0).statement
        self.assertEqual(s.coverage_factor, 2)
        self.assertIsNone(self.statement.coverage_factor)
        self.assertEqual(s.interval_methods, ["coverage_factor"] * len(s.names))
        for U, u in zip(s.expanded_uncertainties, s.standard_uncertainties):
            self.assertEqual(U, 2 * u)  # exactly: a product by 2 is exact in binary
        self.assertEqual(s.setup_sha256, config.setup_sha256)
        with self.assertRaisesRegex(ccal.InputError, "two coverages"):
            ccal.reduce(config, self.logs, statement=True, coverage_factor=2, coverage_probability=0.9)

    def test_the_inputs_and_the_type_a_evaluation_are_the_jsons(self):
        # The lab's encoders measured six inputs; every input's effects are the JSON's, and so is the check.
        d = self.statement.to_dict()
        self.assertEqual([i["id"] for i in self.statement.inputs], [i["id"] for i in d["inputs"]])
        self.assertEqual(sum(i["measured"] for i in self.statement.inputs), 6)
        scale = dict(zip(self.statement.names, self.statement.display_scale))
        for mine, theirs in zip(self.statement.inputs, d["inputs"]):
            self.assertEqual(mine["effect"].keys(), theirs["effect"].keys())
            for name, effect in mine["effect"].items():  # SI here, the statement's units in the JSON (as above)
                self.assertAlmostEqual(effect * scale[name], theirs["effect"][name],
                                       delta=1e-15 * abs(theirs["effect"][name]))
            self.assertEqual(mine["standard_uncertainty"], theirs["u_si"])
            self.assertEqual((mine["u"], mine["unit"]), (theirs["u"], theirs["unit"]))
        # The measuring chain's inputs in the units the configuration wrote: K1 relative to its value.
        k1 = next(i for i in self.statement.inputs if i["id"] == "K1")
        self.assertEqual(k1["unit"], "ppm")
        self.assertAlmostEqual(k1["u"], 2.0, places=12)
        self.assertTrue(self.statement.type_a_from_noise_model)
        check = self.statement.residual_check
        self.assertEqual(check["statistic"], d["type_a"]["residual_check"]["statistic"])
        self.assertFalse(check["excess"])

    def test_covariance_is_symmetric_psd_with_the_squared_uncertainties_on_its_diagonal(self):
        c = np.asarray(self.statement.covariance)
        u = np.asarray(self.statement.standard_uncertainties)
        self.assertTrue(np.array_equal(c, c.T))
        # 1e-12 relative: u_c is the hypot of the same Type A and Type B parts whose squares the diagonal sums.
        np.testing.assert_allclose(np.diag(c), u * u, rtol=1e-12)
        eigenvalues = np.linalg.eigvalsh(c)
        self.assertGreaterEqual(eigenvalues.min(), -1e-12 * eigenvalues.max())
        np.testing.assert_allclose(np.asarray(self.statement.correlation), c / np.outer(u, u), rtol=1e-14)
        np.testing.assert_allclose(c, np.asarray(self.statement.covariance_a) + np.asarray(self.statement.covariance_b),
                                   rtol=1e-14, atol=0)

    def test_modelled_outputs_are_the_jsons(self):
        outputs = self.statement.outputs
        stated = self.statement.to_dict()["modelled_output"]
        self.assertEqual([o["run"] for o in outputs], ["5g", "10g", "15g", "20g", "25g", "30g"])
        for o, j in zip(outputs, stated):
            self.assertEqual(o["g_level"], j["g_level"])
            # SI here, deg/s in the JSON: × display_scale (180/π), to 1e-15 relative as above.
            self.assertEqual(o["display_scale"], 180 / math.pi)
            self.assertAlmostEqual(o["value"] * o["display_scale"], j["corrected_estimate"],
                                   delta=1e-15 * abs(j["corrected_estimate"]))
            self.assertAlmostEqual(o["expanded_uncertainty"] * o["display_scale"], j["expanded_uncertainty"],
                                   delta=1e-15 * j["expanded_uncertainty"])
            self.assertEqual(o["unit"], "deg/s")

    def test_csv_rows_follow_the_names(self):
        lines = self.statement.to_csv().splitlines()
        self.assertTrue(lines[0].endswith(",cov_K0,cov_K2,cov_K3"))
        self.assertEqual([l.split(",")[0] for l in lines[1:]], self.statement.names)

    def test_correlated_uncertain_numbers(self):
        try:
            import uncertainties  # noqa: F401
        except ImportError:
            self.skipTest("the package uncertainties is not installed (python3-uncertainties)")
        numbers = self.statement.to_uncertainties()
        self.assertEqual(list(numbers), self.statement.names)
        for name, value, u in zip(self.statement.names, self.statement.values, self.statement.standard_uncertainties):
            self.assertEqual(numbers[name].nominal_value, value)
            self.assertAlmostEqual(numbers[name].std_dev / u, 1, delta=1e-12)
        # A function of correlated numbers carries the covariance: u(K2 + K3) from the matrix, 1e-12 relative.
        c = np.asarray(self.statement.covariance)
        total = numbers["K2"] + numbers["K3"]
        self.assertAlmostEqual(total.std_dev / np.sqrt(c[1, 1] + c[2, 2] + 2 * c[1, 2]), 1, delta=1e-12)


if __name__ == "__main__":
    unittest.main()
