"""Bad arguments of the Python module that used to crash or were silently misread (issue 12): each raises
ccal.InputError (a ValueError) naming the argument and the accepted range."""

import unittest

import ccal


class ThreadCountTest(unittest.TestCase):
    def test_thread_counts_beyond_the_range_are_refused(self):
        cfg = ccal.bundled_example()
        for threads in (100000, 1025, -1):
            with self.assertRaisesRegex(ccal.InputError, "threads.*1 to 1024"):
                ccal.monte_carlo(cfg, trials=100, threads=threads)
            with self.assertRaisesRegex(ccal.InputError, "threads.*1 to 1024"):
                ccal.allocate(cfg, {"K3": 1e-9}, verify_trials=0, threads=threads)


if __name__ == "__main__":
    unittest.main()
