"""ccal.design against the command-line program (`ccal design`): the same designed plan and the same JSON, and the
configuration text with the designed [plan] budgets as the design reports. Run by ctest with Debian's python3, the
module on PYTHONPATH and the program in CCAL_PROGRAM."""

import json
import os
import subprocess
import tempfile
import unittest

import ccal

# A small space (192 candidates) so that a design takes seconds.
SMALL_SPACE = """
[design]
g_step = "5 g"
turn_fractions = 4
phase_step = "90 deg"
azimuth_step = "180 deg"
starts = 2
"""


class DesignTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.text = ccal.bundled_example_text() + SMALL_SPACE
        cls.cfg = ccal.parse_config(cls.text, "small.toml")
        cls.result = ccal.design(cls.cfg, threads=1)

    def test_same_plan_as_the_program(self):
        with tempfile.TemporaryDirectory() as folder:
            path = os.path.join(folder, "small.toml")
            with open(path, "w", encoding="utf-8") as f:
                f.write(self.text)
            out = subprocess.run([os.environ["CCAL_PROGRAM"], "design", path, "--format", "json"], check=True,
                                 capture_output=True, text=True).stdout
        cli = json.loads(out)
        ours = json.loads(self.result.to_json())
        # The plan and the budgets are the same numbers (the timings and the file name differ).
        self.assertEqual(ours["designed_plan"], cli["designed_plan"])
        self.assertEqual(ours["coefficients"], cli["coefficients"])

    def test_written_configuration_budgets_the_same(self):
        designed = ccal.parse_config(self.result.config_text(self.text), "designed.toml")
        budget = ccal.budget(designed)
        for k in range(3):
            # Relative 1e-12: the file carries 17 significant digits, so it reads back to the same numbers.
            self.assertAlmostEqual(budget.expanded_uncertainty[k] / self.result.after.expanded_uncertainty[k],
                                   1.0, delta=1e-12)

    def test_never_worse(self):
        self.assertLessEqual(self.result.designed_objective, self.result.configured_objective)
        self.assertTrue(all(t.weight > 0 for t in self.result.targets))

    def test_bad_arguments(self):
        with self.assertRaises(ccal.InputError):
            ccal.design(self.cfg, objective="best")
        with self.assertRaises(ccal.InputError):
            ccal.design(self.cfg, targets={"K9": 1.0})


if __name__ == "__main__":
    unittest.main()
