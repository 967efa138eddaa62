"""The one unit rule of the module's results (docs/python.md, "Units"): every result with coefficients gives them
in SI, with `units` (the display unit of each, as the command line shows it) and `display_scale` (SI → display)
beside them; display(), to_dict(), to_json() and str() are in the display units. For each result class, an SI
attribute × display_scale is the displayed figure. Run by ctest with Debian's python3 and the module on
PYTHONPATH."""

import json
import math
import os
import tempfile
import unittest

import numpy as np

import ccal

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
LAB = os.path.join(ROOT, "examples", "lab.toml")
# A small design space (as tests/python/test_design.py), so that a design takes a fraction of a second.
SMALL_SPACE = '\n[design]\ng_step = "5 g"\nturn_fractions = 4\nphase_step = "90 deg"\nazimuth_step = "180 deg"\nstarts = 2\n'
# An SI value × display_scale against the figure the result displays: equal to 1e-15 relative, since the two
# differ by at most a division and a multiplication by the scale (the statement is computed in its units, the
# other results in SI), each rounding to half an ulp (1.1e-16), and the JSON keeps 17 significant digits.
RTOL = 1e-15

# The results that carry no coefficient, each with the reason; every other class with display() is checked.
WITHOUT_COEFFICIENTS = {
    "SensedInput": "specific force in g (its display unit) and angular rates in rad/s, shown in deg/s by display()",
    "Config": "a configuration: its values are SI as read, display() its runs",
}


def _rows(table, column):
    return [r[column] for r in table.rows]


class UnitRule(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cfg = ccal.load_config(LAB)
        sim = ccal.simulate(cfg)
        cls.folder = tempfile.TemporaryDirectory()
        logs = sim.write_logs(os.path.join(cls.folder.name, "logs"))
        observations = os.path.join(cls.folder.name, "observations.csv")
        with open(observations, "w", encoding="utf-8") as f:
            f.write(sim.to_csv())
        reduction = ccal.reduce(cfg, logs, statement=True, statement_trials=1000)
        small = ccal.parse_config(ccal.bundled_example_text() + SMALL_SPACE, "small.toml")
        statement_file = os.path.join(cls.folder.name, "statement.json")
        with open(statement_file, "w", encoding="utf-8") as f:
            f.write(reduction.statement.to_json())
        db = os.path.join(cls.folder.name, "h.sqlite")
        ccal.history_add(statement_file, db=db, serial="SN 1", date="2024-01-02")
        cls.results = {
            "Budget": ccal.budget(cfg),
            "MonteCarlo": ccal.monte_carlo(cfg, trials=2000),
            "Allocation": ccal.allocate(cfg, {"K2": "5e-4 deg/s/g^2"}, verify_trials=200),
            "Simulation": sim,
            "Reduction": reduction,
            "Statement": reduction.statement,
            "Identification": ccal.identify_file(observations),
            "Fit": ccal.identify(sim.observations, cfg),
            "Design": ccal.design(small, threads=1),
            "History": ccal.history("SN 1", db=db),
            "Observability": ccal.observability(sim.observations, cfg),
        }

    @classmethod
    def tearDownClass(cls):
        cls.folder.cleanup()

    def assert_displayed(self, si, scale, shown, what):
        np.testing.assert_allclose(np.asarray(si, dtype=float) * np.asarray(scale), np.asarray(shown, dtype=float),
                                   rtol=RTOL, atol=0, err_msg=what)

    def test_every_result_class_is_checked_or_named_without_coefficients(self):
        shown = {name for name, cls in vars(ccal).items()
                 if isinstance(cls, type) and hasattr(cls, "display") and name != "Table"}
        self.assertEqual(shown - set(WITHOUT_COEFFICIENTS), set(self.results) - {"Design", "Observability"})
        for name, result in self.results.items():
            units, scale = result.units, result.display_scale
            self.assertEqual(len(units), len(scale), name)
            self.assertGreater(len(units), 0, name)
            for unit, factor in zip(units, scale):  # deg/s/gⁿ: 180/π per rad/s/gⁿ, a g-level being 1 in SI
                self.assertRegex(unit, r"^deg/s(/g\^[23])?$", name)
                self.assertEqual(factor, 180 / math.pi, name)

    def test_budget(self):
        b = self.results["Budget"]
        d = b.display()
        self.assertEqual(_rows(d, "unit"), b.units)
        self.assert_displayed(b.expanded_uncertainty, b.display_scale, _rows(d, "expanded_uncertainty"), "U")
        self.assert_displayed(b.standard_uncertainty, b.display_scale, _rows(d, "standard_uncertainty"), "u")

    def test_monte_carlo(self):
        mc = self.results["MonteCarlo"]
        d = mc.display()
        self.assertEqual(_rows(d, "unit"), mc.units)
        self.assert_displayed(mc.mean, mc.display_scale, _rows(d, "mean"), "mean")
        self.assert_displayed(mc.std_dev, mc.display_scale, _rows(d, "std_dev"), "std_dev")

    def test_allocation(self):
        a = self.results["Allocation"]
        d = a.display()
        self.assertEqual(_rows(d, "unit"), a.units)
        self.assertEqual([c.display_scale for c in a.coefficients], a.display_scale)
        self.assert_displayed([c.allocated_expanded for c in a.coefficients], a.display_scale,
                              _rows(d, "allocated_expanded"), "allocated U")

    def test_simulation_and_reduction(self):
        for name in ("Simulation", "Reduction"):
            r = self.results[name]
            d = r.display()
            self.assertEqual(_rows(d, "unit"), r.units, name)
            self.assert_displayed(r.coefficients, r.display_scale, _rows(d, "value"), name)

    def test_statement(self):
        s = self.results["Statement"]
        c = s.to_dict()["coefficients"]
        self.assertEqual([c[n]["unit"] for n in s.names], s.units)
        self.assertEqual(_rows(s.display(), "unit"), s.units)
        self.assert_displayed(s.values, s.display_scale, [c[n]["corrected_estimate"] for n in s.names], "value")
        self.assert_displayed(s.expanded_uncertainties, s.display_scale,
                              [c[n]["expanded_uncertainty"] for n in s.names], "U")
        self.assert_displayed([i[1] for i in s.intervals], s.display_scale, [c[n]["interval"][1] for n in s.names],
                              "interval")
        self.assert_displayed(np.diag(s.covariance), np.square(s.display_scale),
                              [c[n]["combined_standard_uncertainty"] ** 2 for n in s.names], "u_c²")
        # The SI values agree with the reduction's SI coefficients (the corrected estimate is K̂ + b: within a few
        # of its standard uncertainties of the fit's K̂).
        r = self.results["Reduction"]
        self.assertTrue(np.all(np.abs(np.subtract(s.values, r.coefficients)) < 5 * np.array(s.standard_uncertainties)))

    def test_identification_and_its_fit(self):
        i = self.results["Identification"]
        d = i.display()
        self.assertEqual(_rows(d, "unit"), i.units)
        self.assertEqual((i.fit.units, i.fit.display_scale), (i.units, i.display_scale))
        self.assert_displayed(i.fit.value, i.display_scale, _rows(d, "value"), "value")
        self.assert_displayed(i.fit.std_error, i.display_scale, _rows(d, "std_error"), "std_error")

    def test_fit_of_observations(self):
        # The observations are SI, so is the fit: it is the simulation's identification, in SI, to 1e-9 relative
        # (the simulation fits the observations file's figures in deg/s, this fit their SI values).
        f, sim = self.results["Fit"], self.results["Simulation"]
        self.assertEqual(f.names, sim.names)
        np.testing.assert_allclose(f.value, sim.coefficients, rtol=1e-9)
        self.assert_displayed(f.value, f.display_scale, _rows(f.display(), "value"), "value")
        plain = ccal.fit(np.array([[1.0, 1.0], [1.0, 2.0], [1.0, 3.0]]), np.array([1.0, 2.0, 3.1]), ["a", "b"])
        self.assertEqual((plain.units, plain.display_scale), (["", ""], [1.0, 1.0]))  # no units: the data's

    def test_history(self):
        h = self.results["History"]
        d, rows = h.display(), h.display().rows
        self.assertEqual([h.unit for h in h.coefficients], h.units)
        self.assertEqual([c.unit for c in h.records[0].coefficients], h.units)
        self.assert_displayed([c.values[0] for c in h.coefficients], h.display_scale, _rows(d, "value"), "value")
        self.assert_displayed([c.expanded[0] for c in h.coefficients], h.display_scale, _rows(d, "U"), "U")
        self.assert_displayed([c.value for c in h.records[0].coefficients], h.display_scale,
                              [r["value"] for r in rows], "record's value")
        # The recorded statement is the reduction's: its SI values (to 1e-15 relative, as above).
        np.testing.assert_allclose([c.value for c in h.records[0].coefficients], self.results["Statement"].values,
                                   rtol=RTOL, atol=0)

    def test_observability(self):
        # No display(): its units are the budget's, the same free terms in the same order.
        o, b = self.results["Observability"], self.results["Budget"]
        self.assertEqual([t.term for t in o.terms], b.coefficients)
        self.assertEqual((o.units, o.display_scale), (b.units, b.display_scale))

    def test_design(self):
        d = self.results["Design"]
        c = json.loads(d.to_json())["coefficients"]
        names = d.after.coefficients
        self.assertEqual([c[n]["unit"] for n in names], d.units)
        self.assert_displayed(d.tolerance_after, d.display_scale,
                              [c[n]["designed_tolerance_expanded"] for n in names], "tolerance U")
        self.assert_displayed(d.after.expanded_uncertainty, d.display_scale,
                              [c[n]["designed_expanded"] for n in names], "U")


if __name__ == "__main__":
    unittest.main()
