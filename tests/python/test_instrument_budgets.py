"""A test of several instruments from Python (examples/two_instruments.toml): ccal.budget gives each instrument's
Budget and the covariance of all their coefficients, as the program's JSON does; ccal.design one plan for all, with
each instrument's result. Run by ctest with Debian's python3, the module on PYTHONPATH and the program in
CCAL_PROGRAM."""

import json
import os
import subprocess
import unittest

import numpy as np

import ccal
from test_design import SMALL_SPACE  # a small design space, so that a design takes seconds

HERE = os.path.dirname(os.path.abspath(__file__))
TWO = os.path.join(HERE, "..", "..", "examples", "two_instruments.toml")


class BudgetOfInstrumentsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.result = ccal.budget(ccal.load_config(TWO))
        out = subprocess.run([os.environ["CCAL_PROGRAM"], "budget", TWO, "--format", "json"], check=True,
                             capture_output=True, text=True).stdout
        cls.cli = json.loads(out)

    def test_each_instrument_as_the_program(self):
        self.assertEqual(len(self.result.instruments), 2)
        for part, cli in zip(self.result.instruments, self.cli["instruments"]):
            mine = json.loads(part.to_json())
            self.assertEqual(mine, {k: v for k, v in cli.items() if k != "id"})
            # The numbers in display units, read on the part as on any Budget: exactly the JSON's.
            for k, coefficient in enumerate(cli["coefficients"]):
                self.assertEqual(part.expanded_uncertainty[k] * part.display_scale[k],
                                 coefficient["expanded_uncertainty"])

    def test_the_covariance_as_the_program(self):
        c = self.result.instrument_covariance
        self.assertEqual(c.names, self.cli["covariance"]["coefficients"])
        self.assertEqual(c.instruments, ["A", "B"])
        # SI here (the one unit rule), display units in the JSON: × display_scale_i display_scale_j, to 1e-15
        # relative (a division and two multiplications by the scales, each rounding to half an ulp).
        self.assertEqual(c.display_scale, [180 / np.pi] * 6)
        np.testing.assert_allclose(c.lpu * np.outer(c.display_scale, c.display_scale),
                                   np.array(self.cli["covariance"]["lpu"]), rtol=1e-15, atol=0)
        np.testing.assert_allclose(c.lpu_correlation, np.array(self.cli["covariance"]["lpu_correlation"]), rtol=0,
                                   atol=1e-15)  # the same quotients of the same doubles
        self.assertEqual(c.trials, 0)

    def test_one_instrument_has_none(self):
        one = ccal.budget(ccal.bundled_example())
        self.assertEqual(one.instruments, [])
        self.assertIsNone(one.instrument_covariance)
        self.assertEqual(one.covariance.shape, (3, 3))  # the budget's own, as before




class DesignOfInstrumentsTest(unittest.TestCase):
    def test_one_plan_with_each_instruments_result(self):
        with open(TWO, encoding="utf-8") as f:
            text = f.read().replace('setup = "lab.toml"',
                                    'setup = "' + os.path.join(HERE, "..", "..", "examples", "lab.toml") + '"')
        d = ccal.design(ccal.parse_config(text + SMALL_SPACE, "two.toml"), {"K3": 1e-3}, threads=1)
        self.assertEqual(len(d.instruments), 2)
        report = json.loads(d.to_json())
        self.assertEqual([x["id"] for x in report["instruments"]], ["A", "B"])
        for one, x in zip(d.instruments, report["instruments"]):
            # Each instrument's U of the one plan, in the display unit, as the report gives it, below the target.
            u = one.after.expanded_uncertainty[2] * one.after.display_scale[2]
            self.assertEqual(u, x["coefficients"]["K3"]["designed_expanded"])
            self.assertLessEqual(u, 1e-3)
            self.assertEqual(len(one.sheet.lines), len(d.sheet.lines))


if __name__ == "__main__":
    unittest.main()
