"""[[correlations]] through the Python module: the budget's input correlation matrix and the cross terms'
part of u², and the Monte Carlo that draws them (its u agrees with the budget's). Run by ctest with Debian's
python3 and the module on PYTHONPATH."""

import math
import unittest

import ccal

PAIRS = """
[[correlations]]
between = ["ripple1_c1", "ripple3_c1"]
r = -0.5

[[correlations]]
between = ["dthy4", "dthy5"]
r = 0.6
"""


class CorrelationsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.cfg = ccal.parse_config(ccal.bundled_example_text() + PAIRS, "pairs.toml")

    def test_the_budget_carries_the_matrix(self):
        b = ccal.budget(self.cfg)
        ids = [s.id for s in b.sources]
        a, c = ids.index("ripple1_c1"), ids.index("ripple3_c1")
        self.assertEqual(b.input_correlation[a, c], -0.5)
        self.assertEqual(b.input_correlation[a, a], 1.0)
        # K2's ripples cancel: the cross terms take back nearly all of its u² (-98.9 %).
        k2 = b.coefficients.index("K2")
        self.assertLess(b.correlation_variance[k2] / b.standard_uncertainty[k2] ** 2, -0.9)

    def test_the_monte_carlo_draws_them(self):
        # u(K2) of 20000 trials against the LPU's: 5 standard errors, 5/sqrt(2M) = 2.5 % (without the
        # correlation it would be 9.4 times the LPU's).
        mc = ccal.monte_carlo(self.cfg, trials=20000, threads=1)
        k2 = mc.budget.coefficients.index("K2")
        lpu = mc.budget.standard_uncertainty[k2]
        self.assertLess(abs(mc.outputs[k2].std_dev / lpu - 1), 5 / math.sqrt(2 * 20000))
        self.assertEqual(mc.budget.input_correlation.shape[0], len(mc.budget.sources))
        self.assertIn("Gaussian copula", mc.notes)

    def test_a_pair_the_copula_cannot_draw_is_refused(self):
        far = ccal.parse_config(ccal.bundled_example_text() +
                                '\n[[correlations]]\nbetween = ["dthy4", "ripple1_c1"]\nr = 0.999\n', "far.toml")
        with self.assertRaisesRegex(ccal.InputError, r"far\.toml: \[\[correlations\]\] .* accepted: \|r\| ≤ 0\.9484"):
            ccal.monte_carlo(far, trials=100)


if __name__ == "__main__":
    unittest.main()
