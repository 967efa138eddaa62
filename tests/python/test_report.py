"""ccal.report: the page of `ccal report` from Python, from the same options (the report's table and the Monte
Carlo's), its sections readable as results."""

import hashlib
import os
import re
import shutil
import subprocess
import tempfile
import unittest

import ccal

PROGRAM = os.environ.get("CCAL_PROGRAM")
EXAMPLE = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "wang_ren_2014.toml")


def without_provenance_lines(page):
    """The page without the line that names how it was made (the command line or the Python call)."""
    return re.sub(r"<tr><th>command line</th><td><code>[^\n]*</code></td></tr>\n", "", page)


class Report(unittest.TestCase):
    def test_sections_and_options_are_the_verbs(self):
        cfg = ccal.bundled_example()
        r = ccal.report(cfg, trials=2000, seed=3, mode="paper", input_points=5)
        # The Monte Carlo section is ccal.monte_carlo with the same options, bit for bit (a fixed seed).
        mc = ccal.monte_carlo(cfg, trials=2000, seed=3, mode="paper")
        self.assertEqual(r.monte_carlo.to_dict()["coefficients"], mc.to_dict()["coefficients"])
        self.assertEqual(r.budget.to_dict(), ccal.budget(cfg, mode="paper").to_dict())
        self.assertIsNone(r.allocation)
        self.assertIsNone(r.design)
        self.assertIsNone(r.observed)

    def test_refusals_are_those_of_the_command_line(self):
        cfg = ccal.bundled_example()
        with self.assertRaisesRegex(ccal.InputError, r"^trials: 1 is out of range; accepted: 2 to 1000000000"):
            ccal.report(cfg, trials=1)
        with self.assertRaisesRegex(ccal.InputError, r"^input_points: 1 is out of range"):
            ccal.report(cfg, trials=2000, input_points=1)
        with self.assertRaisesRegex(TypeError, r"did you mean 'trials'\?.*accepted: config, allocate_targets"):
            ccal.report(cfg, trails=2000)
        with self.assertRaisesRegex(TypeError, r"unexpected keyword argument 'mode_'"):
            ccal.report(cfg, mode_="paper")

    def test_the_pdf_is_printed_and_replaces_a_file_only_when_complete(self):
        r = ccal.report(ccal.bundled_example(), trials=2000, input_points=5)
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "report.pdf")
            with open(out, "w", encoding="utf-8") as f:
                f.write("the old file")
            os.environ["CCAL_CHROMIUM"] = "/nonexistent/chromium"
            try:
                with self.assertRaisesRegex(ccal.InputError, "is not an executable file.*apt-get install chromium"):
                    r.to_pdf(out)
            finally:
                del os.environ["CCAL_CHROMIUM"]
            with open(out, encoding="utf-8") as f:
                self.assertEqual(f.read(), "the old file")
            self.assertEqual(os.listdir(tmp), ["report.pdf"])  # no temporary left
            if not shutil.which("chromium"):
                self.skipTest("no Chromium installed")
            r.to_pdf(out)
            with open(out, "rb") as f:
                self.assertEqual(f.read(5), b"%PDF-")

    @unittest.skipUnless(PROGRAM, "CCAL_PROGRAM is not set")
    def test_the_page_is_the_programs(self):
        # SOURCE_DATE_EPOCH fixes the date of both; they differ only in how they were made (the call or the
        # command line), which the provenance shows.
        os.environ["SOURCE_DATE_EPOCH"] = "1800000000"
        try:
            r = ccal.report(ccal.load_config(EXAMPLE), trials=2000, input_points=5,
                            allocate_targets={"K3": "2e-3 deg/s/g^3"})
            page = r.to_html()
            with tempfile.TemporaryDirectory() as tmp:
                out = os.path.join(tmp, "report.html")
                subprocess.run([PROGRAM, "report", EXAMPLE, "--trials", "2000", "--input-points", "5",
                                "--allocate-target", "K3=2e-3 deg/s/g^3", "-o", out], check=True,
                               capture_output=True)
                with open(out, encoding="utf-8") as f:
                    program_page = f.read()
        finally:
            del os.environ["SOURCE_DATE_EPOCH"]
        self.assertEqual(without_provenance_lines(page), without_provenance_lines(program_page))
        self.assertIn("ccal.report(ccal.load_config(", page)
        self.assertIn("allocate_targets={&#39;K3&#39;: &#39;2e-3 deg/s/g^3&#39;}", page)
        with open(EXAMPLE, "rb") as f:
            self.assertIn(hashlib.sha256(f.read()).hexdigest(), page)
        self.assertIsNotNone(r.allocation)

    def test_an_edited_configuration_is_named_with_its_edits(self):
        cfg = ccal.bundled_example()
        # The page's configuration text is the file's; the call names what was changed in Python.
        first = cfg.tolerances[0].id
        page = ccal.report(cfg.without_tolerance(first), trials=2000, input_points=5).to_html()
        self.assertIn(f"ccal.bundled_example().without_tolerance(&#39;{first}&#39;)", page)

    def test_a_certificate_shows_no_tolerance_monte_carlo_and_warns_of_traceability_gaps(self):
        lab = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "lab.toml")
        with tempfile.TemporaryDirectory() as tmp:
            cfg = ccal.load_config(lab)
            obs = os.path.join(tmp, "obs.csv")
            with open(obs, "w", encoding="utf-8") as f:
                f.write(ccal.simulate(cfg).to_csv())
            r = ccal.report(cfg, observations=obs, statement_trials=0)
            self.assertTrue(r.certificate)
            self.assertIsNone(r.monte_carlo)  # the certificate does not compute what it does not show
            self.assertEqual(r.warnings, [])  # the lab example states every kind its budget needs
            self.assertIn("End of certificate", r.to_html())
            engineering = ccal.report(cfg, observations=obs, statement_trials=0, trials=2000, engineering=True)
            self.assertFalse(engineering.certificate)
            self.assertEqual(engineering.monte_carlo.trials, 2000)
            # Without the angles' standard: shown as not stated, and a warning naming the key that states it.
            text = open(lab, encoding="utf-8").read()
            gap = os.path.join(tmp, "gap.toml")
            with open(gap, "w", encoding="utf-8") as f:
                f.write(text.replace('angle = "autocollimator', '# angle = "autocollimator'))
            r = ccal.report(ccal.load_config(gap), observations=obs, statement_trials=0)
            self.assertEqual(len(r.warnings), 1)
            self.assertIn("angles of the axes and of the mounting", r.warnings[0])
            self.assertIn("[certificate.traceability]: angle", r.warnings[0])
            self.assertIn("not stated", r.to_html())


if __name__ == "__main__":
    unittest.main()
