"""Bad arguments of the Python module that used to crash or were silently misread (issue 12): each raises
ccal.InputError (a ValueError) naming the argument or the place, and run indices agree between int and str."""

import math
import os
import tempfile
import unittest

import ccal

EXAMPLE_DIR = os.path.join(os.path.dirname(__file__), "..", "..", "examples")


def example_text():
    with open(os.path.join(EXAMPLE_DIR, "wang_ren_2014.toml"), encoding="utf-8") as f:
        return f.read()


class ThreadCountTest(unittest.TestCase):
    def test_thread_counts_beyond_the_range_are_refused(self):
        cfg = ccal.bundled_example()
        for threads in (100000, 1025, -1):
            with self.assertRaisesRegex(ccal.InputError, "threads.*1 to 1024"):
                ccal.monte_carlo(cfg, trials=100, threads=threads)
            with self.assertRaisesRegex(ccal.InputError, "threads.*1 to 1024"):
                ccal.allocate(cfg, {"K3": 1e-9}, verify_trials=0, threads=threads)


class BadArgumentCatalogueTest(unittest.TestCase):
    """Each bad argument: ccal.InputError whose one-line message names the place."""

    def test_catalogue(self):
        cfg = ccal.bundled_example()
        text = example_text()
        with tempfile.TemporaryDirectory() as d:
            log = os.path.join(d, "log.csv")
            with open(log, "w", encoding="utf-8") as f:
                f.write("time,output\n0,1\n2,1\n1,1\n")
            cases = [
                ("parse_config radius", lambda: ccal.parse_config(text.replace('"2.5 m"', '"1e30 m"'), "c.toml"),
                 "radius"),
                ("parse_config duration", lambda: ccal.parse_config(
                    text.replace('duration = "450 s"', 'duration = "1e12 s"'), "c.toml"), "duration"),
                ("parse_config g_level", lambda: ccal.parse_config(
                    text.replace('g_level = "5 g"', 'g_level = "1e6 g"'), "c.toml"), "g_level"),
                ("load_config missing", lambda: ccal.load_config(os.path.join(d, "none.toml")), "none.toml"),
                ("monte_carlo trials memory", lambda: ccal.monte_carlo(cfg, trials=10**9), "GiB"),
                ("monte_carlo coverage",
                 lambda: ccal.monte_carlo(cfg, trials=100, coverage_probability=1.5), "coverage_probability: 1.5"),
                ("allocate tiny target", lambda: ccal.allocate(cfg, {"K3": 1e-300}, verify_trials=0), "K3"),
                ("allocate unknown target", lambda: ccal.allocate(cfg, {"K9": 1.0}, verify_trials=0), "K9"),
                ("sensed_input run", lambda: ccal.sensed_input(cfg, run="99g"), "99g"),
                ("sensed_input index", lambda: ccal.sensed_input(cfg, run=17), "17"),
                ("budget mode", lambda: ccal.budget(cfg, mode="fast"), "fast"),
                ("reduce_logs angle unit", lambda: ccal.reduce_logs(cfg, {"5g": log}, angle_unit="grad"), "grad"),
                ("reduce_logs bad log", lambda: ccal.reduce_logs(cfg, {0: log, 1: log, 2: log}), "log.csv"),
            ]
            for name, call, place in cases:
                with self.subTest(name):
                    with self.assertRaises(ccal.InputError) as caught:
                        call()
                    message = str(caught.exception)
                    self.assertIn(place, message)
                    self.assertNotIn("\n", message)


class SwappedLogsTest(unittest.TestCase):
    """reduce(strict_runs=True) refuses a run whose mean is not what the nominal instrument reads there (the
    pulse logs of two runs swapped), as `ccal reduce --strict-runs` does; without it the two are warnings."""

    def test_swapped_pulse_logs(self):
        cfg = ccal.load_config(os.path.join(EXAMPLE_DIR, "lab.toml"))
        sim = ccal.simulate(cfg)
        with tempfile.TemporaryDirectory() as d:
            logs = {}
            for run, (name, text) in zip(["5g", "10g", "15g", "20g", "25g", "30g"], sim.run_logs()):
                path = os.path.join(d, name)
                with open(path, "w", encoding="utf-8") as f:  # time and pulses only: no encoder to tell them apart
                    f.write("\n".join(",".join(line.split(",")[:2]) for line in text.splitlines()) + "\n")
                logs[run] = path
            logs["5g"], logs["10g"] = logs["10g"], logs["5g"]
            r = ccal.reduce(cfg, logs, statement=False)
            self.assertEqual(sum("nominal instrument" in w for w in r.warnings), 2)
            with self.assertRaisesRegex(ccal.InputError, r"logs: run '5g': the log's mean .* so are runs '10g'; accepted: "
                                                         r"each run's own log \(to see the fit anyway: the runs' "
                                                         r"check as a warning, not strict\)$"):
                ccal.reduce(cfg, logs, strict_runs=True)
            # reduce_logs does not identify, so has no statement and no run check: their keywords are refused,
            # coverage_factor among them (it was accepted and ignored).
            for keyword in ("strict_runs", "coverage_factor"):
                with self.assertRaisesRegex(TypeError, keyword):
                    ccal.reduce_logs(cfg, {"5g": logs["5g"]}, **{keyword: 2})


class NonFiniteResultTest(unittest.TestCase):
    """Results that cannot be finite are refused with what to change, not returned as nan or inf."""

    def test_a_flag_takes_only_true_or_false(self):
        with self.assertRaises(TypeError) as caught:
            ccal.design(ccal.bundled_example(), fresh_candidates="maybe")
        self.assertIn("fresh_candidates", str(caught.exception))
        self.assertIn("maybe", str(caught.exception))

    def test_a_fit_that_overflows_is_refused(self):
        # Finite data near 1e308 overflow in the solution: fit() returned [nan, nan] without an error.
        import numpy as np
        x = np.array([1.0, 2.0, 3.0, 4.0])
        H = np.column_stack([np.ones_like(x), x])
        y = np.array([1.0e308, 1.2e308, 1.4e308, 1.7e308])
        with self.assertRaisesRegex(ccal.InputError, "not a finite number.*scale y"):
            ccal.fit(H, y, ["K0", "K1"])
        # scaled by 1e-300 the same data fit: slope 1.15/5 (exact to rounding; 1e-12 relative is ample)
        r = ccal.fit(H, y * 1e-300, ["K0", "K1"])
        self.assertAlmostEqual(r.value[1] / 0.23e8, 1.0, delta=1e-12)

    def test_a_coverage_interval_the_trials_cannot_give_is_refused(self):
        cfg = ccal.bundled_example()
        with self.assertRaisesRegex(ccal.InputError, "coverage_probability.*trials at least 500001"):
            ccal.monte_carlo(cfg, trials=10, coverage_probability=0.999999)

    def test_a_tolerance_beyond_any_physical_size_is_refused_where_it_is_written(self):
        text = example_text().replace('dx3_s1 = { bound = "10 um"', 'dx3_s1 = { bound = "1e300 um"')
        with self.assertRaisesRegex(ccal.InputError, r"c\.toml:\d+:\d+: tolerances\.dx3_s1\.bound: .*1e100"):
            ccal.parse_config(text, "c.toml")


class RunIndexTest(unittest.TestCase):
    def test_a_string_of_digits_is_the_same_index_as_the_int(self):
        cfg = ccal.bundled_example()
        for k in range(len(cfg.runs)):
            by_int = ccal.sensed_input(cfg, run=k, time=1.0)
            by_str = ccal.sensed_input(cfg, run=str(k), time=1.0)
            self.assertEqual(by_int.specific_force[0], by_str.specific_force[0])
        # run=1 is the second run (10g): A = 10 g nominal, so |a_i| ≈ 10 at a quarter-free time.
        self.assertAlmostEqual(abs(ccal.sensed_input(cfg, run="1", time=0.0).specific_force[0]),
                               abs(ccal.sensed_input(cfg, run="10g", time=0.0).specific_force[0]), places=12)


if __name__ == "__main__":
    unittest.main()
