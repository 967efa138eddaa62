"""One refusal, worded for each front end: the same out-of-range option value gives the library's message in
Python (naming the keyword) and on the command line (naming the flag), because both check it against the
verb's options table (core/options.hpp). Run by ctest with the module on PYTHONPATH and the program in
CCAL_PROGRAM."""

import os
import subprocess
import unittest

import ccal

# (Python call, the command line): every numeric option shared by several verbs, and a verb's own ones.
CASES = [
    (lambda c: ccal.monte_carlo(c, trials=1), ["montecarlo", "--trials", "1"]),
    (lambda c: ccal.monte_carlo(c, trials=0), ["montecarlo", "--trials", "0"]),
    (lambda c: ccal.monte_carlo(c, digits=7), ["montecarlo", "--digits", "7"]),
    (lambda c: ccal.monte_carlo(c, threads=-1), ["montecarlo", "--threads", "-1"]),
    (lambda c: ccal.monte_carlo(c, coverage_probability=1.0), ["montecarlo", "--coverage-probability", "1"]),
    (lambda c: ccal.allocate(c, {"K3": 1e-3}, verify_trials=1),
     ["allocate", "--target", "K3=1e-3", "--verify-trials", "1"]),
    (lambda c: ccal.allocate(c, {"K3": 1e-3}, max_scale=0.0), ["allocate", "--target", "K3=1e-3", "--max-scale", "0"]),
    (lambda c: ccal.budget(c, coverage_factor=0.5), ["budget", "--coverage-factor", "0.5"]),
    (lambda c: ccal.budget(c, mode="fast"), ["budget", "--mode", "fast"]),
]


def flag(field):
    return "--" + field.replace("_", "-")


class SameRefusal(unittest.TestCase):
    def test_python_and_the_program_refuse_alike(self):
        config = ccal.bundled_example()
        for call, args in CASES:
            with self.subTest(args=" ".join(args)):
                with self.assertRaises(ccal.InputError) as caught:
                    call(config)
                python_message = str(caught.exception)
                field, rest = python_message.split(": ", 1)
                self.assertEqual(flag(field), args[-2], python_message)  # the keyword is the flag's field
                run = subprocess.run([os.environ["CCAL_PROGRAM"], *args], capture_output=True, text=True)
                self.assertEqual(run.returncode, 2)
                self.assertEqual(run.stderr, f"ccal: error: {flag(field)}: {rest}\n")

    def test_trials_none_is_the_default(self):
        r = ccal.monte_carlo(ccal.bundled_example(), trials=None, digits=1, threads=1, seed=3)
        self.assertGreaterEqual(r.trials, 20000)  # stages of 10⁴, at least two


if __name__ == "__main__":
    unittest.main()
