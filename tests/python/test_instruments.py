"""A test of several instruments from Python (docs/python.md): Config.instruments and Config.instrument(id) (the
command line's --instrument), a simulation of the whole test on one machine whose logs hold every instrument's
column, and its reduction to each instrument with the covariance between them."""

import os
import tempfile
import unittest

import ccal

DAQ = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "daq")


class Instruments(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.config = ccal.load_config(os.path.join(DAQ, "two_short.toml"))

    def test_each_instrument_is_a_configuration_and_one_is_chosen_by_its_id(self):
        self.assertEqual([c.instrument_id for c in self.config.instruments], ["A", "B"])
        b = self.config.instrument("B")
        self.assertEqual(b.instrument_id, "B")
        self.assertEqual(len(b.instruments), 1)
        self.assertEqual(b.numbers_sha256, self.config.instruments[1].numbers_sha256)
        with self.assertRaisesRegex(ccal.InputError, r"instrument: C is no instrument of .*two_short.toml; "
                                                     r"accepted: A, B"):
            self.config.instrument("C")
        # A verb of one instrument asks for one.
        with self.assertRaisesRegex(ccal.InputError, r"answers for one at a time; accepted: one of A, B"):
            ccal.sensed_input(self.config, run="5g")
        self.assertIsNotNone(ccal.sensed_input(b, run="5g"))

    def test_the_sample_folder_reduces_to_each_instrument_and_their_covariance(self):
        r = ccal.reduce(self.config, os.path.join(DAQ, "two_instruments"), statement=True, statement_trials=2000)
        self.assertEqual([one.config.instrument_id for one in r.instruments], ["A", "B"])
        cov = r.covariance
        self.assertEqual(cov.names, ["A K0", "A K2", "A K3", "B K0", "B K2", "B K3"])
        self.assertEqual(cov.lpu.shape, (6, 6))
        self.assertEqual(cov.monte_carlo.shape, (6, 6))
        # The correlations are those of the command line's table (docs/tutorial.md §12), to its three digits.
        self.assertAlmostEqual(cov.lpu_correlation[0, 3], -0.259, delta=5e-4)
        self.assertAlmostEqual(cov.lpu_correlation[4, 5], 0.991, delta=5e-4)
        # Each instrument's part is its reduction alone, bit for bit.
        b = ccal.reduce(self.config.instrument("B"), os.path.join(DAQ, "two_instruments"))
        self.assertEqual(list(b.coefficients), list(r.instruments[1].coefficients))

    def test_a_simulated_test_writes_one_folder_for_every_instrument(self):
        sim = ccal.simulate(self.config, draw_truth=True, seed=7)
        self.assertEqual(len(sim.instruments), 2)
        self.assertTrue(sim.run_logs()[0][1].startswith("time,pulses_A,pulses_B,theta1,gamma\n"))
        self.assertIn("B = { pulses = 'pulses_B' }", sim.logs_manifest())
        with tempfile.TemporaryDirectory() as folder:
            sim.write_logs(folder)
            # The same machine and seed as the sample folder: the same files, bit for bit.
            for name in ("5g.csv", "manifest.toml"):
                with open(os.path.join(folder, name)) as mine, \
                        open(os.path.join(DAQ, "two_instruments", name)) as sample:
                    self.assertEqual(mine.read(), sample.read(), name)


if __name__ == "__main__":
    unittest.main()
