"""One refusal, worded for each front end: the same out-of-range option value gives the library's message in
Python (naming the keyword) and on the command line (naming the flag), because both check it against the
verb's options table (core/options.hpp). Run by ctest with the module on PYTHONPATH and the program in
CCAL_PROGRAM."""

import os
import re
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
    # Read by the same parsers: a float that is not whole, a negative unsigned, an enumeration's name.
    (lambda c: ccal.monte_carlo(c, trials=1e5 + 0.5), ["montecarlo", "--trials", "100000.5"]),
    (lambda c: ccal.monte_carlo(c, seed=-1), ["montecarlo", "--seed", "-1"]),
    (lambda c: ccal.design(c, objective="best"), ["design", "--objective", "best"]),
    (lambda c: ccal.sensed_input(c, time=-1.0), ["force", "--time", "-1"]),
]

# Each Python verb and the command whose flags are its keywords.
VERBS = {"budget": "budget", "monte_carlo": "montecarlo", "allocate": "allocate", "design": "design",
         "simulate": "simulate", "observe": "simulate", "sensed_input": "force"}
# The flags spelled otherwise than their field (apps/ccal/option_flags.cpp): a list given one element per flag.
SPELLINGS = {"targets": "target"}


# Every keyword of the module's verbs: the options a message may name.
KEYWORDS = {name for f in vars(ccal).values() if callable(f) and not isinstance(f, type)
            for name in getattr(getattr(f, "__signature__", None), "parameters", {})}


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
                # Each front end names every option in its own words, in the message's body too.
                worded = re.sub(r"\b[a-z]+(?:_[a-z]+)+\b",
                                lambda m: flag(m.group()) if m.group() in KEYWORDS else m.group(), rest)
                self.assertEqual(run.stderr, f"ccal: error: {flag(field)}: {worded}\n")

    def test_every_keyword_is_a_flag_of_the_command(self):
        # The keywords come from the verb's options table (python/option_keywords.hpp), as the flags do.
        import inspect
        for function, command in VERBS.items():
            keywords = [p.name for p in inspect.signature(getattr(ccal, function)).parameters.values()
                        if p.kind == inspect.Parameter.KEYWORD_ONLY and p.name not in ("progress", "keep_samples",
                                                                                        "compare_with_paper")]
            self.assertTrue(keywords, function)
            help_text = subprocess.run([os.environ["CCAL_PROGRAM"], command, "--help"], capture_output=True,
                                       text=True).stdout
            for keyword in keywords:
                with self.subTest(function=function, keyword=keyword):
                    self.assertIn(flag(SPELLINGS.get(keyword, keyword)) + " ", help_text)

    def test_a_mistyped_keyword_names_the_likely_one(self):
        with self.assertRaisesRegex(TypeError, r"monte_carlo\(\) got an unexpected keyword argument 'trails'; "
                                               r"did you mean 'trials'\?"):
            ccal.monte_carlo(ccal.bundled_example(), trails=10)

    def test_a_value_of_the_wrong_type_is_a_type_error(self):
        config = ccal.bundled_example()
        for keywords, words in [({"trials": "100"}, "trials: expected an integer, got str ('100')"),
                                ({"threads": True}, "threads: expected an integer, got bool (True)"),
                                ({"mode": 1}, "mode: expected a str, got int (1)")]:
            with self.subTest(keywords=keywords):
                with self.assertRaises(TypeError) as caught:
                    ccal.monte_carlo(config, **keywords)
                self.assertEqual(str(caught.exception), words)
        with self.assertRaisesRegex(TypeError, "tradeoff: expected a list of numbers"):
            ccal.design(config, tradeoff="1,2")

    def test_a_whole_float_is_an_integer(self):
        # As on the command line (--trials 1e4): a float of a whole value is read as that integer.
        r = ccal.monte_carlo(ccal.bundled_example(), trials=1e4, threads=1, seed=3)
        self.assertEqual(r.trials, 10000)

    def test_trials_none_is_the_default(self):
        r = ccal.monte_carlo(ccal.bundled_example(), trials=None, digits=1, threads=1, seed=3)
        self.assertGreaterEqual(r.trials, 20000)  # stages of 10⁴, at least two


if __name__ == "__main__":
    unittest.main()
